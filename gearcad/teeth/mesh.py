"""Proof that a toothed pair meshes: overlap of the two outlines over a full cycle.

At every driver position the two outlines, placed as assembled, must overlap by no more than a
tolerance-sized area; turned a little further against each other they must overlap (so the
test can fail both ways).  Only the few teeth around the pitch point are intersected.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from ..geometry.depth import Depths, overlap_areas, overlap_depths, overlap_exceeds
from ..geometry.outline import place_each
from ..pitch.pair import PairData
from ..tolerances import budget
from .frame import ArcFrame
from .gear import ToothedGear

__all__ = ["MeshData", "mesh_check", "placing"]


@dataclass(frozen=True)
class MeshData:
    positions: int
    max_overlap: float
    """Largest overlap area as assembled, mm²."""
    allowed_overlap: float
    """Tolerance-level area it is held to, mm²."""
    nudge: float
    """How far gear 2 is turned for the nudged test, as arc length on its pitch curve at the
    contact (mm): the turn is this over gear 2's radius at each position."""
    nudged_min_overlap: float
    """Smallest (over positions) of the larger overlap when nudged either way, mm²."""
    worst_phi: float
    """Driver angle of the largest overlap, rad."""
    max_depth: float = 0.0
    """Largest penetration depth as assembled (:mod:`~gearcad.geometry.depth`), mm."""
    allowed_depth: float = np.inf
    """The depth the outlines may reach from writing alone: each may stray by the tolerance."""
    depth_at: tuple[float, int, float] = (0.0, 0, 0.0)
    """Where it is deepest: gear 1's angle φ1 (rad), its tooth there, and the deepest point's
    height above its pitch curve (mm)."""
    too_deep: tuple[float, ...] = ()
    """Driver angles (rad) at which the pair is deeper than allowed."""

    @property
    def meshes(self) -> bool:
        return (
            self.max_overlap <= self.allowed_overlap
            and self.max_depth <= self.allowed_depth
            and self.nudged_min_overlap > self.allowed_overlap
        )


_REACH = 2
"""Tooth spaces either side of the pitch point that a window keeps: contact stays within about
one pitch of it, so two leave a margin."""


def _windows(gear: ToothedGear, spaces: np.ndarray) -> dict[int, np.ndarray]:
    """For each space k of ``spaces``, the outline from space k−2's root to space k+2's root,
    closed through points a module under those roots: a small simple polygon that is all of the
    gear near k."""
    ring, z = gear.outline.outer, gear.teeth
    n = len(ring)
    out = {}
    for k in np.unique(spaces).tolist():
        a = gear.space_root[(k - _REACH) % z]
        b = gear.space_root[(k + _REACH) % z]
        run = ring[a : b + 1] if b > a else np.vstack([ring[a:], ring[: b + 1]])
        if z <= 4 * _REACH or len(run) > n // 2:
            out[k] = ring  # few teeth: the window would be most of the gear, so take all of it
            continue
        inner = gear.under_root[[(k + j) % z for j in range(_REACH, -_REACH - 1, -1)]]
        out[k] = np.vstack([run, inner])
    # where the pitch curve turns sharply the points under the roots can cross the teeth: then
    # the whole gear stands in for the window
    cut = [k for k, w in out.items() if w is not ring]
    if cut:
        sizes = [len(out[k]) for k in cut]
        rings = shapely.linearrings(np.vstack([out[k] for k in cut]), indices=np.repeat(np.arange(len(cut)), sizes))
        out.update((k, ring) for k, simple in zip(cut, shapely.is_simple(rings)) if not simple)
    return out


def _space_at(frame: ArcFrame, gear: ToothedGear, phi: np.ndarray) -> np.ndarray:
    """Index of the tooth space nearest polar angle φ."""
    s = frame.arc(phi)
    return np.round((s - gear.phase) / gear.rack.pitch).astype(int) % gear.teeth


def placing(pair: PairData, gears, frames, phi1: np.ndarray):
    """place(turn, at=None) -> gear 1's and gear 2's windows as polygons (positions,) each, for
    gear 2 turned ``turn`` (rad, scalar or per position) beyond its assembled angle at each
    driver angle φ1, in gear 1's frame; ``at`` (indices): those positions only, ``turn`` given
    for them alone.  Gear 1 turned by −φ1 and gear 2 by +φ2 about (E, 0) is, relative to gear 1,
    gear 2 turned by φ2, moved to (E, 0) and turned back by φ1."""
    e = pair.center_distance
    phi2 = pair.angle_map(phi1)
    spaces = _space_at(frames[0], gears[0], phi1 % (2 * np.pi))
    w1 = _windows(gears[0], spaces)
    sizes = [len(w) for w in w1.values()]
    rings = shapely.linearrings(np.vstack(list(w1.values())), indices=np.repeat(np.arange(len(w1)), sizes))
    polygons = dict(zip(w1, shapely.polygons(rings)))
    g1 = np.array([polygons[k] for k in spaces.tolist()], dtype=object)
    spaces = _space_at(frames[1], gears[1], (np.pi - phi2) % (2 * np.pi))
    w2 = _windows(gears[1], spaces)
    picked = [w2[k] for k in spaces.tolist()]
    sizes = np.array([len(w) for w in picked])
    coords, which = np.vstack(picked), np.repeat(np.arange(len(phi1)), sizes)
    shapely.prepare(g1)

    centre = e * np.column_stack([np.cos(phi1), np.sin(phi1)])  # (E, 0) turned back by φ1

    def place(turn, at=None):
        if at is None:
            xy = place_each(coords, which, phi1 + phi2 + turn, centre)
            return g1, shapely.polygons(shapely.linearrings(xy, indices=which))
        # the sines and cosines taken over all positions' angles, as for all at once: each
        # placement is to the bit the one ``place`` gives with ``turn`` for every position
        angle = phi1 + phi2
        angle[at] = angle[at] + turn
        xy = place_each(np.vstack([picked[k] for k in at]), np.repeat(at, sizes[at]), angle, centre)
        return g1[at], shapely.polygons(shapely.linearrings(xy, indices=np.repeat(np.arange(len(at)), sizes[at])))

    return place


def nudge_arc(*, module: float, tolerance: float, play: float) -> float:
    """Gear 2's extra turn for the nudged test, as arc length at the contact (mm): more than the
    designed ``play`` by an overlap that dwarfs the allowance (~0.44·δ/tol times it), capped for
    coarse tolerances well under a pitch, so that the turn never carries a tooth past a space."""
    return budget(tolerance).nudge_arc(module=module, play=play)


def nudge_turns(pair: PairData, phi1: np.ndarray, arc: float) -> np.ndarray:
    """The turn of gear 2 (rad) that moves it ``arc`` mm at the contact, at each driver angle: the
    contact sits on gear 2's pitch curve at radius E − r1(φ1), which varies on a noncircular pair."""
    return arc / (pair.center_distance - pair.gear1.r(phi1))


def mesh_check(
    pair: PairData,
    gears: tuple[ToothedGear, ToothedGear],
    frames: tuple[ArcFrame, ArcFrame],
    *,
    tolerance: float,
    play: float = 0.0,
    positions: int = 360,
) -> MeshData:
    """Overlap of the pair's outlines at ``positions`` driver angles over one full cycle, and
    at every fourth of them with gear 2 nudged either way by more than the designed ``play``
    (mm on the pitch curve)."""
    m = gears[0].rack.params.module
    phi1 = np.linspace(0.0, pair.cycle, positions, endpoint=False)
    # tolerance-level overlap: each of the two flanks in contact may stray by the tolerance
    # over its working depth (ha + hf ≈ 2.25 m)
    b = budget(tolerance)
    allowed = b.teeth_overlap(m)
    nudge = b.nudge_arc(module=m, play=play)
    turns = nudge_turns(pair, phi1[::4], nudge)
    depths = overlap_depths(*placing(pair, gears, frames, phi1)(0.0), step=0.1 * m)
    assembled = depths.area
    nudged = _least_nudged(placing(pair, gears, frames, phi1[::4]), turns)
    worst = int(np.argmax(assembled))
    return MeshData(
        positions=positions,
        max_overlap=float(assembled[worst]),
        allowed_overlap=allowed,
        nudge=float(nudge),
        nudged_min_overlap=nudged,
        worst_phi=float(phi1[worst]),
        max_depth=float(np.max(depths.depth)),
        allowed_depth=b.allowed_depth,
        depth_at=_deepest(depths, phi1, gears[0], frames[0]),
        too_deep=tuple(float(a) for a in phi1[depths.depth > b.allowed_depth]),
    )


def _least_nudged(place, turns: np.ndarray, batch: int = 8) -> float:
    """The smallest over positions of the larger overlap with gear 2 nudged either way (mm²):
    ``min(maximum(overlap(turns), overlap(-turns)))``, the second nudge intersected only where
    it can matter.  A position whose overlap nudged ahead is already no less than the least
    found cannot be the least, and a nudged overlay costs many times an assembled one (whole
    flanks overlap); in order of the overlap ahead, about half the positions need the other."""
    ahead = overlap_areas(*place(turns), screen=False)
    order = np.argsort(ahead, kind="stable")
    least = np.inf
    for start in range(0, len(order), batch):
        at = order[start : start + batch]
        at = at[ahead[at] < least]
        if not len(at):
            break
        back = overlap_areas(*place(-turns[at], at), screen=False)
        least = min(least, float(np.min(np.maximum(ahead[at], back))))
    return least


def _deepest(found: Depths, phi1: np.ndarray, gear: ToothedGear, frame: ArcFrame) -> tuple[float, int, float]:
    """Where the pair is deepest: driver angle, gear 1's tooth nearest the deepest point and that
    point's height above gear 1's pitch curve."""
    k = int(np.argmax(found.depth))
    if found.depth[k] == 0:
        return 0.0, 0, 0.0
    x, y = found.point[k]
    phi = float(np.arctan2(y, x)) % (2 * np.pi)
    tooth = int(np.round((float(frame.arc(phi)) - gear.phase) / gear.rack.pitch - 0.5)) % gear.teeth
    return float(phi1[k]), tooth, float(np.hypot(x, y) - frame.curve.r(np.array([phi]))[0])


def backlash_range(
    pair: PairData, gears, frames, *, limit: float, positions: int = 12, steps: int = 12
) -> tuple[float, float]:
    """Smallest and largest free play of the pair, measured on gear 2's pitch curve (mm).

    At each of ``positions`` driver angles, gear 2 is turned each way until it first overlaps
    gear 1 (bisection up to ``limit`` mm of arc at the contact); the two free turns add up to the
    play.
    """
    phi1 = np.linspace(0.0, pair.cycle, positions, endpoint=False)
    limit = nudge_turns(pair, phi1, limit)
    place = placing(pair, gears, frames, phi1)
    touching = 1e-9 * gears[0].rack.pitch ** 2
    total = np.zeros(positions)
    for sign in (1.0, -1.0):
        lo, hi = np.zeros(positions), limit.copy()
        for _ in range(steps):
            mid = 0.5 * (lo + hi)
            hit = overlap_exceeds(*place(sign * mid), touching)
            hi, lo = np.where(hit, mid, hi), np.where(hit, lo, mid)
        total += lo
    arc = total * (pair.center_distance - pair.gear1.r(phi1))
    return float(arc.min()), float(arc.max())
