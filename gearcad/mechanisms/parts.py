"""Parts: what a design hands to every exporter.

A :class:`Part` holds a part's shape at the tolerance (for solids, areas and the interference
proof) and its cut and mark paths exactly as they will be written — kerf applied, arcs fitted
and then verified: every cut ring is simple and within the tolerance of the exact outline.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..errors import DesignError
from ..geometry.arcfit import ArcRing, arc_points, decimate, fit_arcs
from ..geometry.inset import check_chamfer
from ..geometry.kerf import kerf_fault, kerf_path
from ..geometry.outline import Outline, ring_area, turn_repeats
from ..geometry.rings import bore_ring
from ..geometry.verify import is_simple, max_distance, thin
from ..threads import side_by_side
from ..tolerances import budget
from .budget import FINEST_TOLERANCE

__all__ = ["Part", "Blank", "Placement", "BoreSpec", "CutSpec", "check_bore", "make_part", "cut_paths"]


class BoreSpec(Protocol):
    diameter: float
    keyway_width: float
    keyway_depth: float
    flat: float
    pilot: float


class CutSpec(Protocol):
    """What the parts stage reads of a profile's [output] table."""

    tolerance: float
    kerf: float
    dxf: str
    thickness: float
    chamfer: float


@dataclass(frozen=True)
class Part:
    """One part, its pivot at the origin (mm).

    ``outline`` is the shape at the tolerance (outer ring counter-clockwise, holes clockwise);
    ``fine`` the same cut at a quarter of the tolerance (what the written paths are fitted to
    and checked against); ``cut`` and ``mark`` are the paths as written to DXF and SVG (kerf
    applied to ``cut``); ``pivot_mark`` the half-length of the engraved cross at the pivot.
    """

    name: str
    outline: Outline
    fine: Outline
    cut: tuple[ArcRing, ...]
    mark: tuple[ArcRing, ...]
    pivot_mark: float
    pivot: str = "cross"
    """What marks the pivot: "bore", "pilot" (a small hole where no bore is given), "cross"
    (engraved only) or "hole" (a ring's inner teeth are concentric with it)."""
    pivot_diameter: float = 0.0

    @property
    def cut_vertices(self) -> int:
        return sum(len(r.vertices) for r in self.cut)


@dataclass(frozen=True)
class Blank:
    """A part before its cut paths (:func:`make_part`): its shapes, marks and pivot, checked;
    :func:`cut_paths` makes every blank of a design a complete :class:`Part` together."""

    name: str
    outline: Outline
    fine: Outline
    mark: tuple[ArcRing, ...]
    pivot_mark: float
    pivot: str
    pivot_diameter: float


@dataclass(frozen=True)
class Placement:
    """Where a part sits in the assembly: turned by ``angle`` rad about its pivot, then moved."""

    part: str
    angle: float = 0.0
    offset: tuple[float, float] = (0.0, 0.0)


DEFAULT_PILOT = 1.0
"""Pilot hole diameter (mm) of a part whose profile has no [bore] table (``bore.pilot``)."""


def _pivot_hole(bore: BoreSpec | None, outer: np.ndarray, wall: float) -> tuple[str, float]:
    """What marks the part's pivot: its bore, else a pilot hole where it leaves the wall, else
    only the engraved cross; and the hole's diameter (mm)."""
    if bore is not None and bore.diameter > 0:
        return "bore", bore.diameter
    pilot = DEFAULT_PILOT if bore is None else bore.pilot
    root = float(np.min(np.hypot(outer[:, 0], outer[:, 1])))
    if pilot > 0 and pilot / 2 + max(wall, pilot) < root:
        return "pilot", pilot
    return "cross", 0.0


def _with_bore(outer: np.ndarray, bore: BoreSpec | None, tolerance: float, *, part: str, wall: float) -> Outline:
    """``outer`` and, if any, the bore (or pilot) hole — which must leave ``wall`` mm of material."""
    kind, diameter = _pivot_hole(bore, outer, wall)
    if kind == "cross":
        return Outline((outer,))
    if kind == "pilot":
        return Outline((outer, bore_ring(diameter, tolerance)))
    hole = bore_ring(
        bore.diameter, tolerance, keyway_width=bore.keyway_width, keyway_depth=bore.keyway_depth, flat=bore.flat
    )
    reach = float(np.max(np.hypot(hole[:, 0], hole[:, 1])))
    root = float(np.min(np.hypot(outer[:, 0], outer[:, 1])))
    if reach + wall >= root:
        key = "bore.keyway_depth" if bore.keyway_depth > 0 and reach > bore.diameter / 2 else "bore.diameter"
        value = bore.keyway_depth if key == "bore.keyway_depth" else bore.diameter
        largest = _largest_fitting(bore, key, tolerance, root - wall)
        remedy = f"{key} = {largest:g} fits" if largest > 0 else f"no {key} fits"
        raise DesignError(
            f"{key} = {value:g}: the bore reaches {reach:.3f} mm from the pivot of {part}, whose outline "
            f"comes within {root:.3f} mm of it; leave at least {wall:.3f} mm of material: {remedy}, or make "
            f"the gears larger, so that the outline keeps {reach + wall:.2f} mm from the pivot"
        )
    return Outline((outer, hole))


def _largest_fitting(bore: BoreSpec, key: str, tolerance: float, room: float) -> float:
    """The largest value of ``key`` (bore.diameter or bore.keyway_depth) whose hole reaches less
    than ``room`` mm from the pivot, rounded down to 0.1 mm (0.01 mm below 0.1; 0 when none fits)."""
    field = key.split(".")[1]

    def reach(value: float) -> float:
        sizes = {"diameter": bore.diameter, "keyway_width": bore.keyway_width, "keyway_depth": bore.keyway_depth}
        sizes[field] = value
        hole = bore_ring(sizes.pop("diameter"), tolerance, flat=bore.flat, **sizes)
        return 0.0 if hole is None else float(np.max(np.hypot(hole[:, 0], hole[:, 1])))

    lo, hi = 0.0, float(getattr(bore, field))  # reach(lo) fits (or nothing does), reach(hi) does not
    if reach(lo) >= room:
        return 0.0
    for _ in range(40):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if reach(mid) < room else (lo, mid)
    for step in (0.1, 0.01):
        steps = math.floor(lo / step + 1e-9)
        for value in (round(steps * step, 2), round((steps - 1) * step, 2)):  # the first may round up to hi
            if value > 0 and reach(value) < room:
                return value
    return 0.0


def _circle_arcs(radius: float, *, clockwise: bool) -> ArcRing:
    """A circle about the pivot as four exact quarter arcs (no fitting needed)."""
    t = np.arange(4) * (np.pi / 2) * (-1 if clockwise else 1)
    bulge = np.tan(np.pi / 8) * (-1 if clockwise else 1)
    return ArcRing(radius * np.column_stack([np.cos(t), np.sin(t)]), np.full(4, bulge))


def _cut_ring(ring: np.ndarray, tolerance: float, fine_tol: float, *, flat: bool, part: str) -> ArcRing:
    """The ring as written: arcs fitted (or chords), refitted tighter until the written path is
    simple and within ``tolerance`` of ``ring``; chords as the last resort."""
    budget = tolerance - fine_tol
    # vertices and chord midpoints all on one circle about the pivot (a chord such as a D-flat's
    # has its midpoint well inside)
    probe = np.vstack([ring, (ring + np.roll(ring, -1, axis=0)) / 2])
    radii = np.hypot(probe[:, 0], probe[:, 1])
    if not flat and radii.max() - radii.min() <= fine_tol:
        return _circle_arcs((radii.max() + radii.min()) / 2, clockwise=ring_area(ring) < 0)
    if not flat:
        repeats = turn_repeats(ring)  # a gear drawn tooth by tooth: its arcs repeat by a tooth too
        for attempt in range(3):
            arcs = fit_arcs(ring, budget / 2**attempt, repeats)
            # an independent re-check of the fit: the arcs flattened finely must not cross, and
            # points on them (at most half the fine tolerance apart in sag) stay within the budget
            if (
                is_simple(arc_points(arcs, fine_tol / 4))
                and max_distance(arc_points(arcs, fine_tol / 2), ring) <= budget
            ):
                return arcs
    chords = decimate(ring, budget)
    if not is_simple(chords):
        raise DesignError(f"{part}: the outline crosses itself at this tolerance; use a smaller output.tolerance")
    return ArcRing(chords, np.zeros(len(chords)))


def _kerf_keeps_shape(fine: Outline, kerf: float, fine_tol: float) -> Outline | None:
    """The cut paths offset kerf/2 into the waste, or None where the beam fills a tooth space or
    closes a hole (rounding a corner is what a beam does and passes: see :mod:`..geometry.kerf`)."""
    path = kerf_path(fine, kerf / 2, fine_tol)
    return None if kerf_fault(fine, path, kerf / 2, fine_tol) else path


def _largest_kerf(fine: Outline, kerf: float, fine_tol: float) -> float:
    lo, hi = 0.0, kerf  # to 1 %
    while hi - lo > 0.01 * hi:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _kerf_keeps_shape(fine, mid, fine_tol) is not None else (lo, mid)
    return lo


def check_bore(name: str, fine_outer: np.ndarray, bore: BoreSpec | None, tolerance: float, wall: float) -> None:
    """Raise :class:`DesignError` if ``bore`` does not fit the part (as :func:`make_part` would):
    a cheap check a mechanism makes before expensive work (a twisted gear's sections)."""
    fine_tol = budget(tolerance).fine
    _with_bore(thin(fine_outer, tolerance - fine_tol), bore, tolerance, part=name, wall=wall)


def make_part(
    name: str,
    fine_outer: np.ndarray,
    *,
    output: CutSpec,
    bore: BoreSpec | None = None,
    wall: float = 0.0,
    marks: tuple[np.ndarray, ...] = (),
    hole: np.ndarray | None = None,
    caps: tuple[np.ndarray, ...] = (),
) -> Blank:
    """A part's blank from its outer ring sampled at the fine tolerance (counter-clockwise, mm).

    ``bore`` adds the shaft hole (leaving ``wall`` mm to the outline) — or where none is given a
    pilot hole — ``hole`` a given inner ring instead (clockwise, fine), ``marks`` closed rings to
    engrave (fine), ``caps`` other outer rings of the solid's end faces that the chamfer must fit
    too (a twisted gear's end sections).  The pivot is engraved as a cross sized to the part: a
    fifth of the radius the outline comes within, between 1 and 5 mm (none on a ring, whose hole
    is concentric).  The cut paths are made for every part of a design together, by
    :func:`cut_paths`, which makes the blanks parts.
    """
    tol = output.tolerance
    fine_tol = budget(tol).fine
    if not is_simple(fine_outer):
        across = float(np.ptp(fine_outer, axis=0).max()) if len(fine_outer) else 0.0
        if across < 10 * tol:  # a ring of a few chords folds on itself: the tolerance, not the shape
            raise DesignError(
                f"output.tolerance = {tol:g}: {name} is {across:.3g} mm across, too small to draw within it; "
                f"use output.tolerance ≤ {max(across / 10, FINEST_TOLERANCE):.2g} mm or a larger part"
            )
        raise DesignError(f"{name}: the outline crosses itself (the design cannot be cut as one piece)")
    pivot, diameter = ("hole", 0.0) if hole is not None else _pivot_hole(bore, fine_outer, wall)
    root = float(np.min(np.hypot(fine_outer[:, 0], fine_outer[:, 1])))
    pivot_mark = 0.0 if hole is not None else min(max(0.2 * root, 1.0), 5.0, 0.5 * root)
    if hole is not None:
        fine = Outline((fine_outer, hole))
        outline = Outline((thin(fine_outer, tol - fine_tol), thin(hole, tol - fine_tol)))
    else:
        fine = _with_bore(fine_outer, bore, fine_tol, part=name, wall=wall)
        outline = _with_bore(thin(fine_outer, tol - fine_tol), bore, tol, part=name, wall=wall)
    check_chamfer(outline, output.thickness, output.chamfer, name=name, sections=caps)
    flat = output.dxf == "polyline-flat"
    mark = tuple(_cut_ring(r, tol, fine_tol, flat=flat, part=name) for r in marks)
    return Blank(name, outline, fine, mark, pivot_mark, pivot, diameter)


def cut_paths(parts: tuple[Blank, ...], output: CutSpec, *, router: bool = False) -> tuple[Part, ...]:
    """Every blank made a complete part, its cut paths as they will be written: offset half the
    kerf into the waste, arcs fitted, each checked simple and within the tolerance.  A kerf that
    would fill a tooth space or close a hole of any part is refused with the largest kerf every
    part takes (``router``: the kerf is a router's tool, set by process.tool_diameter)."""
    tol = output.tolerance
    fine_tol = budget(tol).fine
    flat = output.dxf == "polyline-flat"
    kerfed = [p.fine if output.kerf <= 0 else kerf_path(p.fine, output.kerf / 2, fine_tol) for p in parts]
    faults = [(p, kerf_fault(p.fine, k, output.kerf / 2, fine_tol)) for p, k in zip(parts, kerfed) if output.kerf > 0]
    if any(f for _, f in faults):
        key, cutter = ("process.tool_diameter", "tool") if router else ("output.kerf", "beam")
        spoilt = "; ".join(one.describe(p.name, cutter) for p, f in faults for one in f)
        largest = min(_largest_kerf(p.fine, output.kerf, fine_tol) for p, f in faults if f)
        raise DesignError(
            f"{key} = {output.kerf:g}: {spoilt}; the largest {'tool' if router else 'kerf'} every part takes "
            f"is {largest:.3f} mm"
        )
    # a part whose rings repeat an earlier part's (the two gears of a self-conjugate pair are cut
    # alike to ~1e-13 mm) takes that part's fitted paths: fitted once, they are within the
    # budget of both, as the difference is a billionth of the tolerance
    same = [next((j for j in range(i) if _alike(kerfed[j], kerfed[i], 1e-9 * tol)), i) for i in range(len(parts))]
    # fitting is numpy work on large arrays, which releases the GIL: the parts go side by side
    with side_by_side() as pool:
        cuts = {
            i: pool.submit(lambda p=p, k=k: tuple(_cut_ring(r, tol, fine_tol, flat=flat, part=p.name) for r in k.rings))
            for i, (p, k) in enumerate(zip(parts, kerfed))
            if same[i] == i
        }
        return tuple(
            Part(p.name, p.outline, p.fine, cuts[same[i]].result(), p.mark, p.pivot_mark, p.pivot, p.pivot_diameter)
            for i, p in enumerate(parts)
        )


def _alike(a: Outline, b: Outline, within: float) -> bool:
    """Whether two outlines have the same vertices to ``within`` mm."""
    return len(a.rings) == len(b.rings) and all(
        x.shape == y.shape and float(np.max(np.abs(x - y))) <= within for x, y in zip(a.rings, b.rings)
    )
