"""Circular arcs fitted to a closed polyline within a tolerance (for DXF bulges).

A laser cutter or CAD program draws an arc exactly, so every run of vertices that lies within
the tolerance of one circular arc becomes a single segment with a bulge.  Runs are grown
greedily (exponential then binary search on the run length); each candidate arc has its ends on
the run's end vertices and its bulge chosen to minimise the largest radial miss of the run.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import bulge as B

__all__ = ["ArcRing", "fit_arcs", "decimate", "decimate_indices", "arc_points"]


@dataclass(frozen=True)
class ArcRing:
    """A closed ring of segments: ``vertices[k]`` to ``vertices[k+1]`` (cyclic) with
    ``bulges[k]`` = tan(sweep/4), positive counter-clockwise, 0 for a straight segment."""

    vertices: np.ndarray
    bulges: np.ndarray

    @property
    def arcs(self) -> int:
        return int(np.count_nonzero(self.bulges))


def _runs_fit(pts: np.ndarray, starts: np.ndarray, lengths: np.ndarray, tol: float, arcs: bool):
    """For each start i and run length L (segments), whether one line (or arc) fits the
    vertices i…i+L of the closed point array within ``tol``; and the bulge it needs.

    An arc passes through both run ends and the run's vertex farthest from the chord, and must
    stay within ``tol`` of every vertex including what it strays between two vertices d apart
    (its own chord sag d²/8R): the curve the vertices stand for follows their chords.

    The runs' vertices are laid end to end in one flat array (no run padded to the longest),
    each run's maxima taken by ``reduceat`` over its own slice; so there must be at least one
    run, each of at least one segment, ending at or before the array's last point.
    """
    width = lengths + 1
    first = np.cumsum(width) - width  # each run's slice of the flat arrays
    last = first + lengths
    flat = pts[np.arange(last[-1] + 1) + np.repeat(starts - first, width)]
    inside = np.ones(len(flat), dtype=bool)
    inside[first], inside[last] = False, False
    a = pts[starts]
    chord = pts[starts + lengths] - a
    length = np.hypot(chord[:, 0], chord[:, 1])
    safe = np.where(length > 0, length, 1.0)
    nx, ny = -chord[:, 1] / safe, chord[:, 0] / safe
    rx, ry = flat[:, 0] - np.repeat(a[:, 0], width), flat[:, 1] - np.repeat(a[:, 1], width)
    off = rx * np.repeat(nx, width) + ry * np.repeat(ny, width)
    abs_off = np.where(inside, np.abs(off), 0.0)
    peak = np.maximum.reduceat(abs_off, first)
    line_ok = (peak <= tol) & (length > 0)
    if not arcs:
        return line_ok, np.zeros(len(starts))
    along = (rx * np.repeat(chord[:, 0], width) + ry * np.repeat(chord[:, 1], width)) / np.repeat(safe, width)
    step = np.empty(len(flat))
    step[1:] = np.hypot(flat[1:, 0] - flat[:-1, 0], flat[1:, 1] - flat[:-1, 1])
    step[first] = 0.0
    max_gap = np.maximum.reduceat(step, first)
    k = np.minimum.reduceat(np.where(abs_off == np.repeat(peak, width), np.arange(len(flat)), len(flat)), first)
    x = along[k] - length / 2  # the farthest vertex (the first, if several)
    y = off[k]
    rising = np.empty(len(flat), dtype=bool)
    rising[0] = True
    rising[1:] = along[1:] > along[:-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        c = -(length * length / 4 - x * x - y * y) / (2 * y)  # centre's offset from the chord
        radius = np.hypot(length / 2, c)
        h = c + np.sign(y) * radius  # signed sagitta
        dist = np.hypot(along - np.repeat(length / 2, width), off - np.repeat(c, width))
        miss = np.maximum.reduceat(np.where(inside, np.abs(dist - np.repeat(radius, width)), 0.0), first)
        miss += max_gap**2 / (8 * radius)
        ordered = np.minimum.reduceat(~inside | ((along > 0) & (along < np.repeat(length, width)) & rising), first)
        arc_ok = ordered & np.isfinite(miss) & (miss <= tol) & (np.abs(h) < length / 2) & (length > 0)
        bulge = np.where(line_ok, 0.0, -2 * h / safe)
    return line_ok | arc_ok, bulge


def _reach_at(pts: np.ndarray, starts: np.ndarray, limits: np.ndarray, tol: float, arcs: bool) -> np.ndarray:
    """For each start, the longest run (in segments, ≥ 1, at most its limit) that one line or
    arc fits: doubling on all starts at once, then bisection between the last fit and the first
    miss."""
    good = np.ones(len(starts), dtype=int)
    length = 2
    alive = limits > 1
    while length <= _LONGEST and np.any(alive):
        lengths = np.minimum(length, limits)
        idx = np.nonzero(alive)[0]
        ok, _ = _runs_fit(pts, starts[idx], lengths[idx], tol, arcs)
        ok &= lengths[idx] > good[idx]
        good[idx[ok]] = lengths[idx][ok]
        alive[idx[~ok]] = False
        alive &= lengths < limits
        length *= 2
    lo, hi = good.copy(), np.minimum(2 * good, limits)
    for size in np.unique(good):  # one bucket per doubling level: arrays only as wide as needed
        bucket = np.nonzero(good == size)[0]
        while True:
            test = bucket[hi[bucket] - lo[bucket] > 1]
            if len(test) == 0:
                break
            mid = (lo[test] + hi[test]) // 2
            ok, _ = _runs_fit(pts, starts[test], mid, tol, arcs)
            lo[test[ok]] = mid[ok]
            hi[test[~ok]] = mid[~ok]
    return lo


def _reach_ahead(pts: np.ndarray, starts: np.ndarray, limits: np.ndarray, tol: float, arcs: bool) -> np.ndarray:
    """:func:`_reach_at` for a few starts in a few array steps: the lengths its doubling and its
    bisection would try next are tried together (``_AHEAD`` levels of each at once), and its
    choices are then replayed from their answers, so the reach is the same to the vertex."""
    good = np.ones(len(starts), dtype=int)
    alive = limits > 1
    length = 2
    while length <= _LONGEST and np.any(alive):
        idx = np.nonzero(alive)[0]
        tries = length << np.arange(_AHEAD[0])
        tries = tries[tries <= _LONGEST]
        lengths = np.minimum(tries[None, :], limits[idx, None])
        ok, _ = _runs_fit(pts, np.repeat(starts[idx], len(tries)), lengths.ravel(), tol, arcs)
        # taken up to the first miss; past its limit a run's tries repeat one length, taken alike
        taken = np.cumprod(ok.reshape(lengths.shape), axis=1, dtype=bool)
        count = taken.sum(axis=1)
        good[idx] = np.where(count > 0, lengths[np.arange(len(idx)), count - 1], good[idx])
        alive[idx] = (count == len(tries)) & (lengths[:, -1] < limits[idx])
        length = int(tries[-1]) * 2
    lo, hi = good.copy(), np.minimum(2 * good, limits)
    nodes = 2 ** _AHEAD[1] - 1  # the next levels of the bisection as a tree: node i has children 2i+1, 2i+2
    while True:
        idx = np.nonzero(hi - lo > 1)[0]
        if len(idx) == 0:
            return lo
        below, above = np.empty((len(idx), nodes), dtype=int), np.empty((len(idx), nodes), dtype=int)
        below[:, 0], above[:, 0] = lo[idx], hi[idx]
        for i in range(nodes // 2):  # a node's children: the halves either side of its middle
            middle = (below[:, i] + above[:, i]) // 2
            below[:, 2 * i + 1], above[:, 2 * i + 1] = below[:, i], middle
            below[:, 2 * i + 2], above[:, 2 * i + 2] = middle, above[:, i]
        mid = (below + above) // 2
        wanted = above - below > 1
        ok = np.zeros(wanted.shape, dtype=bool)
        row, col = np.nonzero(wanted)
        ok[row, col], _ = _runs_fit(pts, starts[idx[row]], mid[row, col], tol, arcs)
        node = np.zeros(len(idx), dtype=int)
        rows = np.arange(len(idx))
        for _ in range(_AHEAD[1]):
            at = hi[idx] - lo[idx] > 1
            went = ok[rows, node]
            m = mid[rows, node]
            lo[idx[at & went]] = m[at & went]
            hi[idx[at & ~went]] = m[at & ~went]
            node = np.where(went, 2 * node + 2, 2 * node + 1)


_AHEAD = (5, 2)
"""Levels of the doubling and of the bisection :func:`_reach_ahead` tries at once."""
_LONGEST = 128
"""Longest run tried by doubling (segments)."""
_SIDE_BY_SIDE = 16384
"""Rings of at least this many vertices, with runs of ``_LONG_RUN`` or more vertices on average,
are walked in blocks side by side: only the runs the walk takes are measured."""
_LONG_RUN = 8
_SPACING = 64
"""Vertices between the starts of the walks :func:`_chained` takes side by side."""


def _turns(ring: np.ndarray) -> np.ndarray:
    prev, nxt = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    return np.abs(np.arctan2(prev[:, 0] * nxt[:, 1] - prev[:, 1] * nxt[:, 0], (prev * nxt).sum(1)))


def _rolled(ring: np.ndarray) -> tuple[np.ndarray, int]:
    """The closed point array starting at the sharpest corner (no run has to straddle it)."""
    start = int(np.argmax(_turns(ring)))
    return np.vstack([np.roll(ring, -start, axis=0), ring[start : start + 1]]), start


def _chained(pts: np.ndarray, n: int, tol: float) -> np.ndarray:
    """The reach of every arc run the greedy walk from vertex 0 takes (0 where not measured).

    Walks start every ``_SPACING`` vertices side by side, and a walk stops where it lands on a
    vertex already measured: greedy walks soon fall onto the same vertices, so only a little
    more than the runs taken is measured, in a few dozen array steps, not every vertex's reach."""
    reach = np.zeros(n, dtype=int)
    pos = np.arange(0, n, _SPACING)
    while len(pos):
        reach[pos] = _reach_ahead(pts, pos, n - pos, tol, True)
        land = np.sort(pos + reach[pos])
        land = land[(land < n) & np.append(True, land[1:] != land[:-1])]
        pos = land[reach[land] == 0]
    return reach


def _walk(pts: np.ndarray, n: int, tol: float, arcs: bool) -> np.ndarray:
    """Greedy runs along the closed array ``pts`` (n + 1 points, the first repeated): each run as
    long as one line (or arc) fits.  Returns the runs' first vertices, ascending.

    Measuring the longest run from every vertex at once costs about n × the run length; walking
    costs a few array steps per run.  A small ring, or one of short runs (judged from a few
    probes), is walked from vertex 0: its arcs' reach measured only along walks that soon meet
    (:func:`_chained`), its lines' (a few vertices each) at every vertex at once.  A large ring of
    long runs is cut at the sharpest vertex of each block of about 16 runs, and the blocks are
    walked side by side (a run never crosses a cut)."""
    typical = 0.0
    if n >= _SIDE_BY_SIDE:
        probes = np.linspace(0, n - 1, 32).astype(int)
        typical = float(_reach_ahead(pts, probes, n - probes, tol, arcs).mean())
    if typical < _LONG_RUN:
        every = np.arange(n)
        reach = _chained(pts, n, tol) if arcs else _reach_at(pts, every, n - every, tol, False)
        steps, i, out = reach.tolist(), 0, []  # Python ints: a thousand steps cost no array lookups
        while i < n:
            out.append(i)
            i += steps[i]
        return np.array(out)
    block = int(16 * typical)
    turn = _turns(pts[:n])
    cuts = [0] + [lo + int(np.argmax(turn[lo : lo + block])) for lo in range(block, n - block // 2, block)] + [n]
    pos, end = np.array(cuts[:-1]), np.array(cuts[1:])
    chosen = [pos.copy()]
    active = np.nonzero(pos < end)[0]
    while len(active):
        pos[active] += _reach_ahead(pts, pos[active], end[active] - pos[active], tol, arcs)
        active = active[pos[active] < end[active]]
        chosen.append(pos[active])
    return np.sort(np.concatenate(chosen))  # each block's runs start where the last one ended: no repeats


def fit_arcs(ring: np.ndarray, tolerance: float, repeats: int = 1) -> ArcRing:
    """Fit arcs and lines to a closed ring (open (n, 2) array) within ``tolerance`` mm.

    The ring's vertices must lie on the curve it stands for, with its chords within a small
    fraction of ``tolerance`` of that curve (sample it at a quarter of the tolerance).
    ``repeats``: the ring is its own vertices turned by 2π/repeats (a gear drawn tooth by tooth,
    :func:`~.outline.turn_repeats`); one turn's share is fitted and its arcs repeated on the
    ring's own vertices, so the written outline repeats by a tooth as exactly as the ring does
    (its mesh is then one pitch long, not a whole cycle).
    """
    pts, _ = _rolled(ring)
    n = len(ring)
    span = n // repeats if repeats > 1 and n % repeats == 0 else n
    chosen = _walk(pts[: span + 1], span, tolerance, arcs=True)
    ends = np.append(chosen[1:], span)
    _, bulges = _runs_fit(pts, chosen, ends - chosen, tolerance, arcs=True)
    bulges = np.where(ends - chosen == 1, 0.0, bulges)
    copies = n // span
    at = (chosen[None, :] + span * np.arange(copies)[:, None]).ravel()
    return ArcRing(pts[at], np.tile(bulges, copies))


def decimate(ring: np.ndarray, tolerance: float) -> np.ndarray:
    """The fewest of the ring's vertices (greedily) whose chords stay within ``tolerance`` of
    the ring: a ring sampled finely, thinned to a coarser tolerance."""
    return ring[decimate_indices(ring, tolerance)]


def decimate_indices(ring: np.ndarray, tolerance: float) -> np.ndarray:
    """The indices into ``ring`` of the vertices :func:`decimate` keeps, in ring order from the
    sharpest corner."""
    pts, start = _rolled(ring)
    n = len(ring)
    return (_walk(pts, n, tolerance, arcs=False) + start) % n


def arc_points(arcs: ArcRing, tolerance: float, balanced: bool = False) -> np.ndarray:
    """The ring back as points, each arc flattened to within ``tolerance``: (m, 2) open ring.
    ``balanced``: an arc's points between its ends stand half its chords' sagitta outside it, so
    the chords stray either side (by at most ¾ of it) rather than all inside: no bias in a play
    measured on them (a convex tip's inscribed chords made it smaller by up to the sagitta)."""
    v, bulges = B.segments(arcs)
    a, b = v, np.roll(v, -1, axis=0)
    sweep = B.sweep(bulges)
    curved = bulges != 0
    with np.errstate(divide="ignore", invalid="ignore"):
        centre, radius = B.centres(a, b, sweep)
        radius = np.where(curved, radius, np.inf)
        half_step = np.arccos(np.clip(1 - tolerance / radius, -1.0, 1.0))
        steps = np.where(curved, np.maximum(2, np.ceil(np.abs(sweep) / (2 * half_step))), 1).astype(int)
    start = np.arctan2(a[:, 1] - centre[:, 1], a[:, 0] - centre[:, 0])
    owner = np.repeat(np.arange(len(v)), steps)
    j = np.arange(len(owner)) - np.repeat(np.cumsum(steps) - steps, steps)  # 0 … steps − 1
    t = start[owner] + sweep[owner] * j / steps[owner]
    reach = radius
    if balanced:
        with np.errstate(invalid="ignore"):
            reach = np.where(curved, radius * (1 + (1 - np.cos(sweep / (2 * steps))) / 2), radius)
    on_arc = centre[owner] + reach[owner, None] * np.column_stack([np.cos(t), np.sin(t)])
    return np.where((j == 0)[:, None], v[owner], on_arc)
