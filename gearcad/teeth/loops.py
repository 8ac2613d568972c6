"""Self-intersection loops cut out of open polylines (the rack path's undercut loops)."""

from __future__ import annotations

import math

import numpy as np
import shapely

__all__ = ["remove_loops", "remove_loops_each"]


def _crossings(a: np.ndarray, d: np.ndarray, line: np.ndarray):
    """Pairs (i, j), j ≥ i + 2, of segments a[i]→a[i]+d[i] of one polyline (``line[i] ==
    line[j]``) that cross, with their parameters.

    Candidate pairs come from an R-tree of the segments' boxes (O(n log n) for polylines that
    cross themselves a few times), never from all pairs; the exact test of GEOS is asked only
    of the pairs whose parameters say they cross."""
    segments = shapely.linestrings(np.stack([a, a + d], axis=1))
    i, j = shapely.STRtree(segments).query(segments)
    keep = (j >= i + 2) & (line[i] == line[j])
    i, j = i[keep], j[keep]
    denom = d[i, 0] * d[j, 1] - d[i, 1] * d[j, 0]
    w = a[j] - a[i]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[:, 0] * d[j, 1] - w[:, 1] * d[j, 0]) / denom
        u = (w[:, 0] * d[i, 1] - w[:, 1] * d[i, 0]) / denom
    hit = (denom != 0) & (t > 0) & (t < 1) & (u > 0) & (u < 1)
    i, j, t = i[hit], j[hit], t[hit]
    touch = shapely.intersects(segments[i], segments[j])
    return i[touch], j[touch], t[touch]


def _cut(points: np.ndarray, a, d, i, j, t) -> tuple[np.ndarray, int]:
    """Cut every outermost loop (i, j) of one pass out of ``points``: (points, loops cut)."""
    order = np.lexsort((-j, i))  # by first segment, the outermost loop first
    keep, start, after, removed = [], 0, -1, 0
    for k in order:
        if i[k] <= after:
            continue  # inside (or overlapping) a loop already cut
        keep += [points[start : i[k] + 1], (a[i[k]] + t[k] * d[i[k]])[None, :]]
        start, after = j[k] + 1, j[k]
        removed += 1
    keep.append(points[start:])
    return np.vstack(keep), removed


def remove_loops_each(lines: list[np.ndarray]) -> list[tuple[np.ndarray, int]]:
    """:func:`remove_loops` of every polyline, the crossings of all of them found at once.

    Returns (points, loops removed) for each of ``lines`` (each (m_k, 2) float), in order.
    """
    out = [(np.asarray(p), 0) for p in lines]
    todo = [k for k, (p, _) in enumerate(out) if len(p) > 3]
    while todo:
        sizes = np.array([len(out[k][0]) - 1 for k in todo])
        starts = np.concatenate([[0], np.cumsum(sizes)])
        a = np.concatenate([out[k][0][:-1] for k in todo])
        d = np.concatenate([out[k][0][1:] - out[k][0][:-1] for k in todo])
        line = np.repeat(np.arange(len(todo)), sizes)
        i, j, t = _crossings(a, d, line)
        of = line[i]
        again = []
        for m in np.unique(of):
            k, lo, hit = todo[m], starts[m], of == m
            points, removed = _cut(out[k][0], a[lo:], d[lo:], i[hit] - lo, j[hit] - lo, t[hit])
            out[k] = (points, out[k][1] + removed)
            if len(points) > 3:
                again.append(k)
        todo = again
    return [_spikes_cut(p, n) for p, n in out]


REVERSAL = math.radians(175)
"""A vertex where the path turns back by more than this is a spike's tip (no tooth outline turns
so sharply: a tooth's tip corner turns about 60°)."""


def _spikes_cut(points: np.ndarray, loops: int) -> tuple[np.ndarray, int]:
    """``points`` with every spike cut off — a vertex the path reaches and leaves the way it came
    (it turns back by more than :data:`REVERSAL`): a loop of no width, whose return runs along its
    outgoing segment without crossing it (where the rack's tip fillet starts tangent to the flank
    it cut, a flank's envelope meets its fillet's there), so the crossings test cannot see it —
    and the loops counted with them."""
    while len(points) > 3:
        d = np.diff(points, axis=0)
        heading = np.arctan2(d[:, 1], d[:, 0])
        turn = np.abs((np.diff(heading) + math.pi) % (2 * math.pi) - math.pi)
        tips = np.flatnonzero(turn > REVERSAL) + 1
        if not len(tips):
            break
        tips = tips[np.concatenate([[True], np.diff(tips) > 1])]  # one of two neighbours a pass
        points = np.delete(points, tips, axis=0)
        loops += len(tips)
    return points, loops


def remove_loops(points: np.ndarray) -> tuple[np.ndarray, int]:
    """Cut self-intersection loops out of an open polyline: (points, loops removed).

    Where segment i crosses a later segment j, the vertices between them form a loop that
    both sides of the rack removed; the polyline goes straight through the crossing instead.
    Every outermost loop found in one pass is cut at once (a loop starts after the previous
    one ends); passes repeat until no crossing is left.
    """
    return remove_loops_each([points])[0]
