"""The 2-D content of a DXF or SVG file: a design's cut and mark paths, per part or assembled."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.arcfit import ArcRing
from ..geometry.outline import rotate
from ..mechanisms import Design, Part, Placement

__all__ = ["Drawing", "cross", "part_drawing", "assembly_drawing"]


@dataclass(frozen=True)
class Drawing:
    """What goes into one DXF: per layer, closed rings (ArcRing, or plain (n, 2) arrays for the
    flat encoding) and open strokes; and a description per layer (e.g. kerf compensation)."""

    closed: dict[str, list]
    strokes: dict[str, list[np.ndarray]]
    descriptions: dict[str, str]


def cross(center, size: float) -> list[np.ndarray]:
    """Two short open strokes marking a pivot: list of (2, 2) float, mm."""
    x, y = center
    return [np.array([[x - size, y], [x + size, y]]), np.array([[x, y - size], [x, y + size]])]


def _placed(ring: ArcRing, placement: Placement) -> ArcRing:
    return ArcRing(rotate(ring.vertices, placement.angle) + np.asarray(placement.offset), ring.bulges)


def _nominal(part: Part) -> tuple[ArcRing, ...]:
    """The part's outline as drawn (no kerf): its rings at the tolerance, as chords."""
    return tuple(ArcRing(r, np.zeros(len(r))) for r in part.outline.rings)


def _drawing(items: list[tuple[Part, Placement]], design: Design, *, nominal: bool = False) -> Drawing:
    out = design.params.output
    cut, mark = out.cut_layer, out.mark_layer
    closed: dict[str, list] = {cut: [], mark: []}
    strokes: dict[str, list] = {mark: []}
    nominal = nominal and out.kerf > 0
    for part, placement in items:
        closed[cut] += [_placed(r, placement) for r in (_nominal(part) if nominal else part.cut)]
        closed[mark] += [_placed(r, placement) for r in part.mark]
        if part.pivot_mark > 0:
            strokes[mark] += cross(tuple(placement.offset), part.pivot_mark)
    descriptions = {}
    if nominal:
        descriptions[cut] = f"the parts as drawn, to check the fit: no kerf (cut files: offset {out.kerf / 2:g} mm)"
    elif out.kerf > 0:
        descriptions[cut] = (
            f"kerf compensation: cut paths offset {out.kerf / 2:g} mm into the waste (kerf {out.kerf:g} mm)"
        )
    return Drawing(closed, strokes, descriptions)


def part_drawing(design: Design, part: Part) -> Drawing:
    """One part about its pivot at the origin."""
    return _drawing([(part, Placement(part.name))], design)


def assembly_drawing(design: Design, *, cut: bool = False) -> Drawing:
    """Every part where the assembly places it (touching: a fit check, not a cutting layout),
    as drawn — or with ``cut`` its cut paths (the kerf applied: for a sheet to cut)."""
    parts = {p.name: p for p in design.parts()}
    return _drawing([(parts[pl.part], pl) for pl in design.placements], design, nominal=not cut)
