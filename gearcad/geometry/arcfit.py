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
    """
    width = int(lengths.max()) + 1
    cols = np.arange(width)
    idx = np.minimum(starts[:, None] + cols[None, :], len(pts) - 1)
    window = pts[idx]  # (runs, width, 2)
    a = window[:, 0]
    b = pts[np.minimum(starts + lengths, len(pts) - 1)]
    chord = b - a
    length = np.hypot(chord[:, 0], chord[:, 1])
    safe = np.where(length > 0, length, 1.0)
    normal = np.column_stack([-chord[:, 1], chord[:, 0]]) / safe[:, None]
    rel = window - a[:, None, :]
    off = np.einsum("rck,rk->rc", rel, normal)
    along = np.einsum("rck,rk->rc", rel, chord) / safe[:, None]
    inside = (cols[None, :] > 0) & (cols[None, :] < lengths[:, None])
    abs_off = np.where(inside, np.abs(off), 0.0)
    line_ok = (abs_off.max(axis=1) <= tol) & (length > 0)
    if not arcs:
        return line_ok, np.zeros(len(starts))
    step = np.hypot(*np.diff(window, axis=1).transpose(2, 0, 1))
    max_gap = np.where(cols[None, 1:] <= lengths[:, None], step, 0.0).max(axis=1)
    rows = np.arange(len(starts))
    k = np.argmax(abs_off, axis=1)
    x = along[rows, k] - length / 2
    y = off[rows, k]
    with np.errstate(divide="ignore", invalid="ignore"):
        c = -(length * length / 4 - x * x - y * y) / (2 * y)  # centre's offset from the chord
        radius = np.hypot(length / 2, c)
        h = c + np.sign(y) * radius  # signed sagitta
        dist = np.hypot(along - (length / 2)[:, None], off - c[:, None])
        miss = np.where(inside, np.abs(dist - radius[:, None]), 0.0).max(axis=1) + max_gap**2 / (8 * radius)
        prev = np.concatenate([np.full((len(starts), 1), -np.inf), along[:, :-1]], axis=1)
        ordered = np.all(~inside | ((along > 0) & (along < length[:, None]) & (along > prev)), axis=1)
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


_LONGEST = 128
"""Longest run tried by doubling (segments)."""
_SIDE_BY_SIDE = 16384
"""Rings of at least this many vertices, with runs of ``_LONG_RUN`` or more vertices on average,
are walked in blocks side by side: only the runs the walk takes are measured."""
_LONG_RUN = 8


def _turns(ring: np.ndarray) -> np.ndarray:
    prev, nxt = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    return np.abs(np.arctan2(prev[:, 0] * nxt[:, 1] - prev[:, 1] * nxt[:, 0], (prev * nxt).sum(1)))


def _rolled(ring: np.ndarray) -> tuple[np.ndarray, int]:
    """The closed point array starting at the sharpest corner (no run has to straddle it)."""
    start = int(np.argmax(_turns(ring)))
    return np.vstack([np.roll(ring, -start, axis=0), ring[start : start + 1]]), start


def _walk(pts: np.ndarray, n: int, tol: float, arcs: bool) -> np.ndarray:
    """Greedy runs along the closed array ``pts`` (n + 1 points, the first repeated): each run as
    long as one line (or arc) fits.  Returns the runs' first vertices, ascending.

    Measuring the longest run from every vertex at once costs about n × the run length; walking
    costs a few array steps per run.  A small ring, or one of short runs (judged from a few
    probes), is measured whole.  A large ring of long runs is cut at the sharpest vertex of each
    block of about 16 runs, and the blocks are walked side by side (a run never crosses a cut)."""
    typical = 0.0
    if n >= _SIDE_BY_SIDE:
        probes = np.linspace(0, n - 1, 32).astype(int)
        typical = float(_reach_at(pts, probes, n - probes, tol, arcs).mean())
    if typical < _LONG_RUN:
        starts = np.arange(n)
        reach = _reach_at(pts, starts, n - starts, tol, arcs)
        i, out = 0, []
        while i < n:
            out.append(i)
            i += int(reach[i])
        return np.array(out)
    block = int(16 * typical)
    turn = _turns(pts[:n])
    cuts = [0] + [lo + int(np.argmax(turn[lo : lo + block])) for lo in range(block, n - block // 2, block)] + [n]
    pos, end = np.array(cuts[:-1]), np.array(cuts[1:])
    chosen = [pos.copy()]
    active = np.nonzero(pos < end)[0]
    while len(active):
        pos[active] += _reach_at(pts, pos[active], end[active] - pos[active], tol, arcs)
        active = active[pos[active] < end[active]]
        chosen.append(pos[active])
    return np.sort(np.concatenate(chosen))  # each block's runs start where the last one ended: no repeats


def fit_arcs(ring: np.ndarray, tolerance: float) -> ArcRing:
    """Fit arcs and lines to a closed ring (open (n, 2) array) within ``tolerance`` mm.

    The ring's vertices must lie on the curve it stands for, with its chords within a small
    fraction of ``tolerance`` of that curve (sample it at a quarter of the tolerance).
    """
    pts, _ = _rolled(ring)
    n = len(ring)
    chosen = _walk(pts, n, tolerance, arcs=True)
    ends = np.append(chosen[1:], n)
    _, bulges = _runs_fit(pts, chosen, ends - chosen, tolerance, arcs=True)
    bulges = np.where(ends - chosen == 1, 0.0, bulges)
    return ArcRing(pts[chosen], bulges)


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


def arc_points(arcs: ArcRing, tolerance: float) -> np.ndarray:
    """The ring back as points, each arc flattened to within ``tolerance``: (m, 2) open ring."""
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
    on_arc = centre[owner] + radius[owner, None] * np.column_stack([np.cos(t), np.sin(t)])
    return np.where((j == 0)[:, None], v[owner], on_arc)
