"""The play of a placed gear pair at driver positions (mm on the pitch curve): gear 2 turned each
way from the rolling angle until it touches gear 1, the made outlines offset by an edge offset
and the centres moved; negative where the parts overlap (the shrink that frees them, −4ε/cos α).
Only a window of each gear around the contact (three modules) is offset and intersected.  The
band (:mod:`.band`) and its certificate (:mod:`.certify`) measure through it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
import shapely

from ..geometry.depth import inradius, overlap_areas, overlap_exceeds
from ..geometry.outline import place_each
from ..geometry.sweep import free_turns
from ..roots import golden_sections

__all__ = ["PairGeometry", "measure", "play_along", "play_between", "signed_play"]

JOIN_SAGITTA = 0.00025
"""The most (mm) an offset's round join (a tip's corner grown by the process) falls short of the
true offset, at any tolerance: at 0.01 mm the joins drawn at the tolerance took up to 10 µm off
the laser focus pair's tips, where the contact is steep (73°), and the band read 64.4 µm where
the files have 54.7."""

_WINDOW = 3.0
"""Radius of the window about the contact, modules: contact stays within about one pitch."""


@dataclass(frozen=True)
class PairGeometry:
    """A gear pair as the band needs it: the made outlines' drawn outer rings (mm, pivot at the
    origin), the centre distance E, and per driver angle φ1 (rad) the mate's angle φ2 and the
    contact radius on gear 1; gear 1 turns by −φ1 about the origin, gear 2 by +φ2 about (E, 0)."""

    rings: tuple
    """Each gear's outer ring (an array), or its polygon (a ring gear's, with its toothed hole)."""
    center_distance: float
    phi1: np.ndarray
    phi2: np.ndarray
    r1: np.ndarray
    module: float
    pressure_angle: float
    teeth: np.ndarray
    """Gear 1's tooth at the contact at each φ1 (index from its first)."""
    at: Callable[[np.ndarray], PairGeometry] | None = field(default=None, compare=False, repr=False)
    """The same pair at other driver angles (what the certificate refines with); None: no refining."""
    ratio: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = field(default=None, compare=False, repr=False)
    """(lo, hi) -> over each driver interval [lo, hi] (rad): the largest follower speed k = dφ2/dφ1,
    the largest speed of the instant centre over the centre distance, and the largest |dk/dφ1|."""
    slope: Callable[[np.ndarray], np.ndarray] | None = field(default=None, compare=False, repr=False)
    """φ1 -> the follower speed dφ2/dφ1 there (what the certificate's bound starts from)."""
    cycle: float = 2 * math.pi
    """The driver's turn after which the pair repeats (rad): the positions wrap there."""
    first: np.ndarray | None = field(default=None, compare=False, repr=False)
    """The driver angles the certificate starts from (rad): even steps along the driver's pitch
    curve, :data:`~.certify.PER_TOOTH` a tooth (None: ``phi1``)."""
    cut: float = 0.0
    """Where ``rings`` are cut paths: the cutter's radius (mm), by which the made parts lie inside
    them (:func:`~.written.written_paths`); an edge offset e is the rings grown by e − ``cut``."""

    def subset(self, keep) -> PairGeometry:
        """The same pair at the positions ``keep`` (indices or a mask) only."""
        return replace(self, phi1=self.phi1[keep], phi2=self.phi2[keep], r1=self.r1[keep], teeth=self.teeth[keep])


def _windows(ring: np.ndarray, centres: np.ndarray, radius: float, offset, tol: float) -> np.ndarray:
    """The gear's shape near each centre, grown by ``offset`` (mm, scalar or per centre), clipped
    to ``radius``; ``ring`` its outer ring, or its polygon (a ring gear's, with its toothed hole)."""
    gear = ring if isinstance(ring, shapely.Geometry) else shapely.Polygon(ring)
    largest = float(np.max(np.abs(offset)))
    pieces = cut_about(gear, centres, radius + largest + radius / 6)
    if largest:
        joins = min(tol, JOIN_SAGITTA)  # a tip's rounded corner within this of the true offset
        steps = max(2, int(math.ceil(math.pi / 4 / math.acos(max(1 - joins / largest, -1.0)))))
        pieces = shapely.buffer(pieces, offset, quad_segs=steps)
    return shapely.intersection(pieces, shapely.buffer(shapely.points(centres), radius, quad_segs=16))


def cut_about(shape, centres: np.ndarray, radius: float) -> np.ndarray:
    """``shape`` (a polygon) within ``radius`` of each centre: cut to each disc's box first
    (GEOS's fast rectangle clip; ~3× quicker than the overlay of the whole shape), then to the
    disc; a clip that is not valid is not used."""
    discs = shapely.buffer(shapely.points(centres), radius, quad_segs=16)
    lo, hi = centres - radius, centres + radius
    boxed = np.array([shapely.clip_by_rect(shape, *a, *b) for a, b in zip(lo.tolist(), hi.tolist())])
    boxed = np.where(shapely.is_valid(boxed), boxed, shape)
    return shapely.intersection(boxed, discs)


def contacts(g: PairGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The pitch point at each position in gear 1's frame, and in gear 2's before its turn (mm):
    the centres of the windows :func:`_placer` measures with."""
    c1 = g.r1[:, None] * np.column_stack([np.cos(g.phi1), np.sin(g.phi1)])
    back = g.r1 - g.center_distance
    return c1, back[:, None] * np.column_stack([np.cos(-g.phi2), np.sin(-g.phi2)])


def _placer(g: PairGeometry, offsets, spread: float, tol: float, *, turns: bool = False, windows=None):
    """(w1, place, free_turns): gear 1's windows, place(turn) -> gear 2's windows turned ``turn``
    (rad, per position) beyond the assembled angle in gear 1's frame, and free_turns(turn, limit,
    at) -> how far gear 2's windows so placed turn each way before they touch gear 1's (rad,
    :func:`~..geometry.sweep.free_turns`; with ``turns``, else None); the parts grown by
    ``offsets``, E by ``spread``.  ``windows``: the two gears' windows, made already (each
    gear's shape within :data:`_WINDOW` modules of :func:`contacts`, gear 2's in its own frame)."""
    e = g.center_distance + spread
    if windows is None:
        c1, c2 = contacts(g)
        radius = _WINDOW * g.module
        w1 = _windows(g.rings[0], c1, radius, offsets[0], tol)
        w2 = _windows(g.rings[1], c2, radius, offsets[1], tol)
    else:
        w1, w2 = windows
    shapely.prepare(w1)
    coords, which = shapely.get_coordinates(w2, return_index=True)
    counts = np.bincount(which, minlength=len(g.phi1))
    first = np.cumsum(counts) - counts  # each window's first row of ``coords``
    centre = e * np.column_stack([np.cos(g.phi1), np.sin(g.phi1)])  # gear 2's pivot in gear 1's frame

    def place(turn: np.ndarray, at=None) -> np.ndarray:
        """Gear 2's windows turned ``turn`` (per position); ``at`` (ascending indices): only those
        windows, ``turn`` given for them alone."""
        if at is None:
            at, rows = slice(None), slice(None)
            owner = which
        else:
            n = counts[at]  # the rows of the chosen windows, in order: a run per window
            owner = np.repeat(np.arange(len(n)), n)
            rows = np.repeat(first[at] - np.cumsum(n) + n, n) + np.arange(int(n.sum()))
        xy = place_each(coords[rows], owner, g.phi1[at] + g.phi2[at] + turn, centre[at])
        return shapely.set_coordinates(w2[at].copy(), xy)

    if not turns:
        return w1, place, None

    def free(turn: np.ndarray, limit: np.ndarray, at) -> tuple[np.ndarray, np.ndarray]:
        """How far gear 2's windows ``at``, turned ``turn``, turn on each way (rad, to ``limit``)."""
        return free_turns(w1[at], place(turn, at), centre[at], limit)

    return w1, place, free


def _least_overlap(w1, place, bound: np.ndarray, iterations: int = 24) -> np.ndarray:
    """Per position, a turn of gear 2 (rad, within ±``bound``) where the parts do not overlap, or
    where they overlap least: 0 where they are apart as placed, else a golden-section search (for
    a turn where they are apart: the gap from there is what measures the play, and parts that
    overlap even by a sliver show no gap either way).
    The assembled angle map is the pitch curves' rolling; with the centres moved or the edges
    grown unevenly the follower sits elsewhere in its play, and a pair that overlaps as placed
    may turn free (today's jam at the nominal angle overstated what a noncircular pair needs)."""
    turn = np.zeros_like(bound)
    stuck = np.flatnonzero(overlap_areas(w1, place(turn)) > 0)
    if not len(stuck):
        return turn

    def area(at: np.ndarray) -> np.ndarray:
        return overlap_areas(w1[stuck], place(at, stuck))

    a, b, fa, fb = golden_sections(
        area, -bound[stuck], bound[stuck].copy(), iterations, lambda lo, hi, fa, fb: not np.any(np.minimum(fa, fb))
    )
    turn[stuck] = np.where(fa <= fb, a, b)
    return turn


def play_between(
    g: PairGeometry,
    offsets,
    spread: float,
    tol: float,
    *,
    reach: float,
    steps: int = 1,
    start=None,
    halves=None,
    windows=None,
) -> tuple[np.ndarray, np.ndarray]:
    """Free play at each position (mm on gear 2's pitch curve, at its nominal contact radius);
    NaN where the parts overlap wherever gear 2 sits; and the turn of gear 2 it was measured from.

    Gear 2 is first turned to where it is free (:func:`_least_overlap`; ``start`` given: there);
    from there, each way, it is turned until it touches gear 1, found exactly as the least turn
    at which a vertex of either window meets an edge of the other
    (:func:`~..geometry.sweep.free_turns`).  ``steps`` 0: only whether it is free (0 where it is).
    ``reach`` (mm) bounds the play sought; ``halves`` (a list): the free turn each way (rad, (2, n))
    is appended to it; ``windows``: the gears' windows, made already (:func:`_placer`)."""
    w1, place, turns = _placer(g, offsets, spread, tol, turns=steps > 0, windows=windows)
    arm = g.center_distance - g.r1
    limit = min(reach, 1.2 * math.pi * g.module) / arm  # more than a pitch never frees a tooth
    touching = 1e-9 * g.module**2
    if start is None:  # the follower's play lies within a quarter pitch of the rolling angle
        start = _least_overlap(w1, place, np.minimum(limit, 0.25 * math.pi * g.module / arm))
    free = ~overlap_exceeds(w1, place(start), touching)
    live = np.flatnonzero(free)  # overlapping: the play is NaN, no gap to close
    up, down = np.zeros_like(g.phi1), np.zeros_like(g.phi1)
    if steps and len(live):
        up[live], down[live] = turns(start[live], limit[live], live)
    if halves is not None:
        halves += [up, down]
    return np.where(free, (up + down) * arm, np.nan), start


def measure(g: PairGeometry, offsets, spread: float, tol: float, *, reach: float) -> np.ndarray:
    """The signed play at ``g``'s positions (:func:`signed_play`)."""
    play, start = play_between(g, offsets, spread, tol, reach=reach)
    return _signed_from(g, play, start, offsets, spread, tol, reach=reach)


def play_along(g: PairGeometry, *, edge: float, tol: float, reach: float) -> np.ndarray:
    """The play at each of ``g``'s driver angles (mm on the pitch curve; NaN where the parts
    overlap), both parts grown by ``edge`` mm at the drawn centre distance."""
    return play_between(g, (edge, edge), 0.0, tol, reach=reach)[0]


def signed_play(g: PairGeometry, offsets, spread: float, tol: float, *, reach: float) -> np.ndarray:
    """:func:`play_between`, negative where jammed: the shrink ε that frees it (gear 2 where it overlapped
    least) counts −4ε/cos α."""
    play, start = play_between(g, offsets, spread, tol, reach=reach)
    return _signed_from(g, play, start, offsets, spread, tol, reach=reach)


def _signed_from(g: PairGeometry, play, start, offsets, spread: float, tol: float, *, reach: float) -> np.ndarray:
    """The play ``play`` (:func:`play_between`, gear 2 from ``start``) signed where it is NaN
    (jammed): −4ε/cos α for the least shrink ε of both parts that frees gear 2 at some turn.

    At a turn, ε is the inradius of the parts' overlap (:func:`~..geometry.depth.inradius`: the
    shrunk parts share a point exactly while the overlap holds a disc of radius ε), first where
    gear 2 overlapped least.  Where two teeth bite, the turn of least overlap need not be the one
    that frees first (on a circular train's mesh it cost 0.19 mm where 0.127 frees it), so gear 2
    is then moved to the middle of its free turn at 2 % more shrink and its overlap measured again.
    An overlap that reaches its window's rim (a bite wider than the window, whose rim is no
    outline) has the shrink bisected on the parts' offsets instead (:func:`_shrink_to_free`)."""
    play = play.copy()
    jammed = np.isnan(play)
    if not jammed.any():
        return play
    sub = PairGeometry(
        g.rings, g.center_distance, g.phi1[jammed], g.phi2[jammed], g.r1[jammed], g.module, g.pressure_angle, g.teeth
    )
    turn = start[jammed]
    most = 0.5 * g.module
    hi = np.full(int(jammed.sum()), most)
    contact = sub.r1[:, None] * np.column_stack([np.cos(sub.phi1), np.sin(sub.phi1)])
    rim = shapely.buffer(shapely.points(contact), 0.95 * _WINDOW * g.module, quad_segs=16)
    w1, place, _ = _placer(sub, offsets, spread, tol)  # the windows, gear 2's placed at any turn
    for again in range(2):
        lap = shapely.intersection(w1, place(turn))
        inside = shapely.within(lap, rim)
        depth = np.full_like(hi, most)
        depth[inside] = inradius(lap[inside], 1e-6 * g.module)
        wide = np.flatnonzero(~inside)
        if len(wide):
            depth[wide] = _shrink_to_free(sub.subset(wide), offsets, spread, tol, reach, turn[wide], hi[wide])
        hi = np.minimum(hi, depth)
        if again:
            break
        halves: list[np.ndarray] = []
        # 2 % past the touch: free over the flat floor of a tip's bite into a root, whose middle
        # lies in the basin (just past it, the exact free turn is a sliver about the first turn:
        # the laser oval's first cut kept 29.3 µm of jam where 22.9 frees it; a dense sweep 20.5)
        give = hi * 1.02 + 1e-9 * g.module
        shrunk = (offsets[0] - give, offsets[1] - give)
        _, at = play_between(sub, shrunk, spread, tol, reach=reach, start=turn, halves=halves)
        up, down = halves
        turn = at + (up - down) / 2  # the middle of the free turn there
    play[jammed] = -4 * hi / math.cos(g.pressure_angle)
    return play


def _shrink_to_free(g: PairGeometry, offsets, spread: float, tol: float, reach: float, turn, hi) -> np.ndarray:
    """The least shrink (mm, to ``hi``/2¹⁴) of both parts' offsets under which gear 2 is free
    at ``turn``, bisected below ``hi``."""
    lo = np.zeros_like(hi)
    for _ in range(14):
        mid = 0.5 * (lo + hi)
        shrunk = (offsets[0] - mid, offsets[1] - mid)
        free = ~np.isnan(play_between(g, shrunk, spread, tol, reach=reach, steps=0, start=turn)[0])
        hi, lo = np.where(free, mid, hi), np.where(free, lo, mid)
    return hi
