"""The 2-D content of a DXF or SVG file: a design's cut and mark paths, per part or assembled."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry.arcfit import ArcRing
from ..geometry.outline import place
from ..mechanisms import Design, Part, Placement

__all__ = ["DASH_MM", "Drawing", "cross", "dashes", "part_drawing", "assembly_drawing"]


@dataclass(frozen=True)
class Drawing:
    """What goes into one DXF: per layer, closed rings (ArcRing, or plain (n, 2) arrays for the
    flat encoding) and open strokes ((n, 2) arrays, or ArcRing whose last bulge is unused: dashes
    with arcs); and a description per layer (e.g. kerf compensation)."""

    closed: dict[str, list]
    strokes: dict[str, list[np.ndarray]]
    descriptions: dict[str, str]


def cross(center, size: float) -> list[np.ndarray]:
    """Two short open strokes marking a pivot: list of (2, 2) float, mm."""
    x, y = center
    return [np.array([[x - size, y], [x + size, y]]), np.array([[x, y - size], [x, y + size]])]


DASH_MM = 3.0
"""Pitch curves are engraved dashed: about 3 mm of line, then a third of that left out.  A dashed
line is open, so a program that fills closed shapes (an engrave-fill pass) cannot fill the pitch
curve's region — which crosses the toothed outline — and engrave a wrong area."""


def _point_on(a: np.ndarray, b: np.ndarray, bulge: float, t: float) -> np.ndarray:
    """The point a fraction ``t`` of the way along the segment a → b of ``bulge`` (by arc length)."""
    if bulge == 0.0:
        return a + t * (b - a)
    theta = 4 * math.atan(bulge)  # turn a → b about the arc's centre, by t·θ
    chord = b - a
    centre = (a + b) / 2 + np.array([-chord[1], chord[0]]) * (1 - bulge * bulge) / (4 * bulge)
    c, s = math.cos(t * theta), math.sin(t * theta)
    r = a - centre
    return centre + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]])


def _perimeter(ring: ArcRing) -> float:
    """The ring's length along its chords (mm): enough to tell a dot from a curve."""
    v = np.asarray(ring.vertices, dtype=float)
    return float(np.hypot(*(np.roll(v, -1, axis=0) - v).T).sum())


def _round(ring: ArcRing) -> ArcRing:
    """The closed ``ring`` as one open stroke back to its start (last bulge 0, meaning nothing):
    it looks the same, but a program that fills closed shapes has nothing to fill."""
    v, bulges = np.asarray(ring.vertices, dtype=float), np.asarray(ring.bulges, dtype=float)
    return ArcRing(np.vstack([v, v[:1]]), np.append(bulges, 0.0))


def dashes(ring: ArcRing) -> list[ArcRing]:
    """The closed ``ring`` as open dashes along it, each an :class:`ArcRing` whose last bulge is 0
    and means nothing (the dash does not close): its arcs stay arcs (bulges), so dashes add few
    vertices.  A whole number of dash-and-gap periods over the ring, so it looks the same all round."""
    v, bulges = np.asarray(ring.vertices, dtype=float), np.asarray(ring.bulges, dtype=float)
    ends = np.roll(v, -1, axis=0)
    chord = np.hypot(*(ends - v).T)
    theta = 4 * np.arctan(bulges)
    with np.errstate(divide="ignore", invalid="ignore"):
        length = np.where(bulges != 0, chord * (theta / 2) / np.sin(theta / 2), chord)
    s = np.concatenate([[0.0], np.cumsum(length)])
    period = s[-1] / max(1, round(s[-1] / (DASH_MM * 4 / 3)))
    out = []
    for start in np.arange(0.0, s[-1] - 1e-9, period):
        stop = start + period * 3 / 4
        points, arcs = [], []
        for k in np.flatnonzero((s[1:] > start) & (s[:-1] < stop)):
            if min(stop, s[k + 1]) - max(start, s[k]) < 1e-9:  # touches the dash's end only
                continue
            t0, t1 = (max(start, s[k]) - s[k]) / length[k], (min(stop, s[k + 1]) - s[k]) / length[k]
            if not points:
                points.append(_point_on(v[k], ends[k], float(bulges[k]), t0))
            points.append(_point_on(v[k], ends[k], float(bulges[k]), t1))
            arcs.append(math.tan((t1 - t0) * theta[k] / 4))
        out.append(ArcRing(np.array(points), np.array([*arcs, 0.0])))
    return out


def _placed(ring: ArcRing, placement: Placement) -> ArcRing:
    return ArcRing(place(ring.vertices, placement.angle, placement.offset), ring.bulges)


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
        for r in part.mark:  # a long mark (a pitch curve) as dashes, a small one (a dot) drawn round
            placed = _placed(r, placement)
            strokes[mark] += [_round(placed)] if _perimeter(placed) < 3 * DASH_MM else dashes(placed)
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
