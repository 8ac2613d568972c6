"""A gear pair's outlines as the files write them, for its band: each gear made as the finishing
line makes it (:func:`~..mechanisms.parts.make_part`, :func:`~..mechanisms.parts.cut_paths`:
the cut path offset half the cutter into the waste and fitted with arcs), its outer path's arcs
flattened to a sagitta of a quarter of the tolerance (at most :data:`SAGITTA`), and — where a
cutter of width w ran along it — the part that cutter leaves: the path's region shrunk by w/2
(a round beam or tool cannot cut a concave corner sharper than its radius: the part's roots
come out rounded by w/2).

The band and its proof then measure what is written and made, not the thinned outlines the mesh
proof holds (which differ from the written arcs by up to 1.5 tolerances each; at a 73° working
pressure angle that is up to 10 tolerances of play).  The flattening's chords lie within a
quarter of the tolerance of the arcs (either side: the points between an arc's ends stand half
the sagitta outside it, so a steep contact's play carries no bias from inscribed chords), which
the band's margin of two tolerances holds even where the contact is steep (2·(tol/4)/cos 73° ≈
1.7·tol)."""

from __future__ import annotations

import math

import numpy as np
import shapely

from ..geometry.arcfit import arc_points
from ..mechanisms.parts import cut_paths
from ..tolerances import budget

__all__ = ["written_paths", "written_regions", "written_rings", "written_shapes", "SAGITTA"]

SAGITTA = 0.00025
"""The most (mm) the flattened outline strays from the written arcs: a quarter of the default
tolerance, and no more at a coarser one — the band reports the files' least play to within a
micrometre at any tolerance (issue 33's independent check)."""


def written_paths(design, count: int = 2) -> tuple[tuple[np.ndarray, ...], float]:
    """The outer paths (mm, pivot at the origin, counter-clockwise) the files write for the first
    ``count`` parts, flattened as the module's docstring says, and the radius (mm) of the cutter
    that runs along them (0: none): the part made is the path's region shrunk by it.

    The band measures these: a cutter of width w ± v leaves the path's region shrunk by (w ± v)/2
    in one step (a Minkowski difference), which rounds the roots by that radius and leaves the
    tips' corners as the path has them.  The part cut to the nominal width and then grown by v/2
    rounds the tips' corners by v/2 as well: up to 18 µm more play than the files at the laser
    focus pair's steep contact (issue 33's independent check)."""
    out = design.params.output
    sagitta = min(budget(out.tolerance).fine, SAGITTA)
    paths = tuple(_oriented(arc_points(p.cut[0], sagitta, balanced=True)) for p in _parts(design, count))
    return paths, out.kerf / 2


def _oriented(xy: np.ndarray) -> np.ndarray:
    ring = shapely.geometry.polygon.orient(shapely.Polygon(xy), 1.0).exterior
    return np.asarray(ring.coords)[:-1]


def _parts(design, count: int | None):
    """The first ``count`` parts as the finishing line makes them (a finished design's own)."""
    parts = getattr(design, "part_list", None)
    if parts is None:
        process = getattr(design.params, "process", None)
        blanks = tuple(s.blank(design.params.output) for s in design.parts[:count])
        parts = cut_paths(blanks, design.params.output, router=getattr(process, "kind", None) == "cnc")
    return parts[:count]


def written_rings(design) -> tuple[np.ndarray, np.ndarray]:
    """The outer outlines (mm, pivot at the origin, counter-clockwise) of a pair's two gears (the
    first two parts) as written and cut: see the module's docstring.  ``design``: a draft (its
    parts made here as the finishing line will make them) or a finished design (its own)."""
    return tuple(np.asarray(shape.exterior.coords)[:-1] for shape in written_shapes(design, 2))


def written_shapes(design, count: int | None = None, regions: tuple | None = None) -> tuple[shapely.Polygon, ...]:
    """The first ``count`` parts (all: None) as written and cut, each a polygon with its holes (a
    ring gear's toothed hole, a bore): see the module's docstring; ``regions``: what
    :func:`written_regions` gave for them (not made again)."""
    paths, radius = regions or written_regions(design, count)
    sagitta = min(budget(design.params.output.tolerance).fine, SAGITTA)
    return tuple(_made(p, radius, sagitta) for p in paths)


def written_regions(design, count: int | None = None) -> tuple[tuple[shapely.Polygon, ...], float]:
    """The regions the first ``count`` parts' written paths bound (all: None; each outer path
    with its holes', flattened as the module's docstring says), and the radius (mm) of the cutter
    that runs along them (0: none): the part made is each region shrunk by it (what
    :func:`written_shapes` gives; a band grows the region by its edge less the radius, the beam
    in one step)."""
    out = design.params.output
    sagitta = min(budget(out.tolerance).fine, SAGITTA)
    regions = []
    for part in _parts(design, count):
        outer, *holes = (arc_points(c, sagitta, balanced=True) for c in part.cut)
        regions.append(shapely.geometry.polygon.orient(shapely.Polygon(outer, holes), 1.0))
    return tuple(regions), out.kerf / 2


def _made(region: shapely.Polygon, radius: float, sagitta: float) -> shapely.Polygon:
    """The part a cutter of ``radius`` (mm) leaves running along the boundary of ``region`` (0:
    the region itself), its outer ring counter-clockwise."""
    part = region
    if radius > 0:
        steps = max(2, math.ceil(math.pi / 4 / math.acos(1 - sagitta / radius)))
        part = part.buffer(-radius, quad_segs=steps)
        if part.geom_type != "Polygon":  # cut_paths refuses a cutter that splits a part
            part = max(part.geoms, key=lambda g: g.area)
    return shapely.geometry.polygon.orient(part, 1.0)
