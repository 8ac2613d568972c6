"""The 2-D content of a DXF or SVG file: a design's cut and mark paths, per part or assembled."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.arcfit import ArcRing
from ..geometry.outline import place
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
    return ArcRing(place(ring.vertices, placement.angle, placement.offset), ring.bulges)


def _drawing(items: list[tuple[Part, Placement]], design: Design) -> Drawing:
    out = design.params.output
    cut, mark = out.cut_layer, out.mark_layer
    closed: dict[str, list] = {cut: [], mark: []}
    strokes: dict[str, list] = {mark: []}
    for part, placement in items:
        closed[cut] += [_placed(r, placement) for r in part.cut]
        closed[mark] += [_placed(r, placement) for r in part.mark]
        if part.pivot_mark > 0:
            strokes[mark] += cross(tuple(placement.offset), part.pivot_mark)
    descriptions = {}
    if out.kerf > 0:
        descriptions[cut] = (
            f"kerf compensation: cut paths offset {out.kerf / 2:g} mm into the waste (kerf {out.kerf:g} mm)"
        )
    return Drawing(closed, strokes, descriptions)


def part_drawing(design: Design, part: Part) -> Drawing:
    """One part about its pivot at the origin."""
    return _drawing([(part, Placement(part.name))], design)


def assembly_drawing(design: Design) -> Drawing:
    """Every part where the assembly places it (touching: a fit check, not a cutting layout)."""
    parts = {p.name: p for p in design.parts()}
    return _drawing([(parts[pl.part], pl) for pl in design.placements], design)
