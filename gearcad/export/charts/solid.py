"""A rendered picture of solids (matplotlib's 3-D axes): what a printed gear pair looks like."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from ...geometry.arcfit import decimate, decimate_indices
from ...geometry.outline import place
from ..loft import loft
from ..mesh import Solid, SolidItem, extrude
from .png import figure, save_png

__all__ = ["draw_solids", "draw_design", "picture_solid", "PICTURE_PIXELS"]

_COLOURS = ((0.2, 0.45, 0.75), (0.85, 0.45, 0.15), (0.35, 0.6, 0.3), (0.6, 0.35, 0.6))
"""The driver blue, its mate orange: as in every other picture of the pair."""
PICTURE_PIXELS = 1100
"""Pixels across the picture's wider side (10 in at 110 dpi)."""
_LIGHT = np.array([0.35, -0.55, 0.75]) / np.linalg.norm([0.35, -0.55, 0.75])


def _placed(item: SolidItem) -> np.ndarray:
    """(m, 3, 3) the item's triangles turned about z by its angle and moved by its offset."""
    v, (dx, dy, dz) = item.solid.vertices, item.offset
    xyz = np.column_stack([place(v[:, :2], item.angle, (dx, dy)), v[:, 2] + dz])
    return xyz[item.solid.triangles]


def picture_solid(part, sections, *, thickness: float, chamfer: float, tolerance: float) -> Solid:
    """A part's solid for a picture, its rings thinned to ``tolerance`` (about half a pixel):
    the printed solid's many sub-pixel triangles cost time to draw and show nothing."""
    holes = [decimate(r, tolerance) for r in part.outline.rings[1:]]
    if sections is None:
        outer = decimate(part.outline.outer, tolerance)
        return extrude(type(part.outline)((outer, *holes)), thickness, name=part.name, chamfer=chamfer)
    rings = np.asarray(sections.rings)
    # the vertices any section needs, kept in all (vertex j is the same point of every section)
    keep = np.unique(np.concatenate([decimate_indices(r, tolerance) for r in rings]))
    return loft(sections.heights, rings[:, keep], name=part.name, holes=holes, chamfer=chamfer)


def draw_solids(
    path: Path,
    items: Sequence[SolidItem],
    *,
    title: str = "",
    elev: float = 28.0,
    azim: float = -75.0,
    size: tuple[float, float] = (10.0, 6.0),
) -> None:
    """Render ``items`` flat-shaded (one colour each, lit from the upper left) to a PNG."""
    fig = figure(size)
    ax = fig.add_subplot(projection="3d", computed_zorder=False)
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for k, item in enumerate(items):
        tri = _placed(item)
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
        shade = 0.35 + 0.65 * np.clip(normal @ _LIGHT, 0.0, 1.0)
        colour = np.clip(np.outer(shade, _COLOURS[k % len(_COLOURS)]), 0, 1)
        # edges drawn in the face colour: no hairline seams between the triangles
        faces = Poly3DCollection(tri, facecolors=colour, edgecolors=colour, linewidths=0.25)
        faces.set_clip_on(False)  # mplot3d would clip to a square inside the wide figure
        ax.add_collection3d(faces)
        lo, hi = np.minimum(lo, tri.reshape(-1, 3).min(axis=0)), np.maximum(hi, tri.reshape(-1, 3).max(axis=0))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(hi - lo), zoom=1.2)  # true proportions, filling the figure
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    if title:
        fig.suptitle(title, parse_math=False)  # a title is text: a "$" is a dollar, not mathtext
    fig.subplots_adjust(left=-0.1, right=1.1, bottom=-0.15, top=1.05)
    save_png(fig, path)


def draw_design(path: Path, design) -> None:
    """The design's parts as solids, placed as assembled, thinned to half a pixel and drawn."""
    out = design.params.output
    reach = max(np.max(np.hypot(*p.outline.outer.T)) for p in design.parts())
    xs = [pl.offset[0] for pl in design.placements]
    ys = [pl.offset[1] for pl in design.placements]
    width = max(max(xs) - min(xs), max(ys) - min(ys)) + 2 * reach
    scene = []
    for pl in design.placements:
        solid = picture_solid(
            design.part(pl.part),
            design.sections.get(pl.part),
            thickness=out.thickness,
            chamfer=out.chamfer,
            tolerance=0.5 * width / PICTURE_PIXELS,
        )
        scene.append(SolidItem(solid, pl.angle, (*pl.offset, 0.0)))
    draw_solids(path, scene, title=design.params.title or design.name)
