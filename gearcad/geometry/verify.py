"""Checks of rings as written: simple (no crossing, no touching), and within a distance of the
exact outline they stand for."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .arcfit import decimate

__all__ = ["distances", "is_simple", "max_distance", "nearest", "thin", "to_segments"]


def is_simple(ring: np.ndarray) -> bool:
    """True when the closed ring (open (n, 2) array) neither crosses nor touches itself."""
    return bool(len(ring) >= 3 and shapely.LinearRing(ring).is_simple)


def thin(ring: np.ndarray, tolerance: float) -> np.ndarray:
    """:func:`~.arcfit.decimate` that keeps a simple ring simple: where dropping vertices would
    make the ring cross or touch itself (two thin teeth close together), the tolerance is halved,
    and at worst the ring is kept as it is."""
    if not is_simple(ring):
        return decimate(ring, tolerance)
    for attempt in range(4):
        thinned = decimate(ring, tolerance / 2**attempt)
        if is_simple(thinned):
            return thinned
    return ring


def nearest(points: np.ndarray, vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each point, the index of the nearest of ``vertices`` and the distance to it: the
    answers of GEOS's R-tree (``shapely.STRtree.query_nearest``), bit for bit.

    A k-d tree finds the two nearest, and the distance is GEOS's, √(dx² + dy²).  Where the two are
    within :data:`_TIE` of each other the R-tree picks, as it always has: among vertices that
    near it takes the one it meets first, which can be an ulp farther (a point on a symmetric
    gear's axis).  Memory O(n + m); the searches are nearest-neighbour searches, as the R-tree's."""
    points, vertices = np.asarray(points, dtype=float).reshape(-1, 2), np.asarray(vertices, dtype=float).reshape(-1, 2)
    if not len(points) or not len(vertices) or not (np.isfinite(points).all() and np.isfinite(vertices).all()):
        return _nearest_vertex(points, vertices, np.arange(len(points)))
    k = min(2, len(vertices))
    distance, index = cKDTree(vertices).query(points, k=k)
    distance, index = distance.reshape(len(points), k), index.reshape(len(points), k)
    tied = np.flatnonzero(distance[:, -1] <= distance[:, 0] * (1 + _TIE) + _TINY) if k > 1 else []
    index = index[:, 0]
    dx, dy = (points - vertices[index]).T
    distance = np.sqrt(dx * dx + dy * dy)
    if len(tied):
        index[tied], distance[tied] = _nearest_vertex(points, vertices, tied)
    return index, distance


def max_distance(points: np.ndarray, ring: np.ndarray, *, limit: float = 0.0) -> float:
    """The largest distance from ``points`` to the closed polyline ``ring`` (mm), as
    :func:`distances` gives them.  (``limit`` is accepted for callers that only need to know
    whether it exceeds it.)"""
    return float(distances(points, [ring]).max()) if len(points) else 0.0


def distances(points: np.ndarray, rings) -> np.ndarray:
    """Each point's distance to the nearest of the closed polylines ``rings`` ((m, 2) arrays,
    mm): the least of GEOS's distances from it to every segment (:func:`to_segments` is GEOS's
    point-to-segment distance, operation for operation); for the points left to GEOS's R-tree
    (below), the R-tree's answer, as before, which can be a segment an ulp farther than the least.

    The rings are sampled at least every h mm into a k-d tree: their vertices, and points between
    them on the longer segments, h twice the median segment but no finer than the ring's length
    over its vertex count plus :data:`_BUDGET` (so at most 2m + :data:`_BUDGET` samples, whatever
    the lengths).  The nearest sample is at r, a bound on the point's distance; its nearest segment
    comes within r, so a sample of it (or its end) lies within r + h/2, and the segments either
    side of every sample that near are measured.  The k nearest samples are taken, k =
    :data:`_K`; a point with more than that within its reach (the centre of a circle, a cluster
    of tiny segments), and every point where a coordinate is not finite, is left to the R-tree.
    So at most 2m + :data:`_BUDGET` samples, and 64 a point measured :data:`_CHUNK` points at a
    time: memory O(n + m), and the searches are nearest-neighbour searches, as the R-tree's.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings]
    start = np.cumsum([0] + [len(r) for r in rings])
    a = np.concatenate(rings)
    b = np.concatenate([np.roll(r, -1, axis=0) for r in rings])
    before = np.concatenate([s + (np.arange(len(r)) - 1) % len(r) for s, r in zip(start, rings)])
    length = np.hypot(*(b - a).T)
    total = float(length.sum())
    if not len(points) or not len(a) or not (np.isfinite(total) and np.isfinite(points).all()):
        return _nearest_segment(points, a, b, np.arange(len(points)))
    h = max(2 * float(np.median(length)), total / (len(a) + _BUDGET)) or 1.0
    count = np.maximum(np.ceil(length / h).astype(int), 1)
    owner = np.repeat(np.arange(len(a)), count)  # each sample's segment
    t = (np.arange(len(owner)) - np.repeat(np.cumsum(count) - count, count)) / count[owner]
    tree = cKDTree(a[owner] + t[:, None] * (b - a)[owner])
    # room for the rounding of the samples, the tree's sums and GEOS's
    room = 1e-13 * max(float(np.abs(a).max()), float(np.abs(points).max()))
    d, reach, left = np.full(len(points), np.inf), np.empty(len(points)), []
    for todo in np.array_split(np.arange(len(points)), -(-len(points) // _CHUNK)):
        for step, k in enumerate(_K):
            bound = np.nextafter(reach[todo].max(), np.inf) if step else np.inf
            near, index = tree.query(points[todo], k=min(k, len(owner)), distance_upper_bound=bound)
            near, index = near.reshape(len(todo), -1), index.reshape(len(todo), -1)
            if not step:  # the nearest sample bounds the distance
                reach[todo] = (near[:, 0] + h / 2) * (1 + 1e-9) + room
            within = near <= reach[todo, None]
            row, col = np.nonzero(within)
            i, j = todo[row], owner[index[row, col]]
            np.minimum.at(d, i, to_segments(points[i], a[j], b[j]))  # the segments either side of the sample
            np.minimum.at(d, i, to_segments(points[i], a[before[j]], b[before[j]]))
            todo = todo[within[:, -1] & (len(owner) > within.shape[1])]  # more samples may lie within reach
            if not len(todo):
                break
        left.append(todo)
    todo = np.concatenate(left)
    if len(todo):
        d[todo] = _nearest_segment(points, a, b, todo)
    return d


_K = (8, 64)
"""How many of the nearest samples are measured: the first for every point, the second for those
with more within reach; past that the point is left to the R-tree."""

_CHUNK = 4096
"""Points measured at a time (their candidate pairs' arrays stay a few MB)."""

_BUDGET = 4096
"""Samples a ring may have beyond twice its vertices (a ring of a few long segments)."""

_TIE = 16 * np.finfo(float).eps
"""Relative difference of two vertices' distances within which :func:`nearest` lets the R-tree
choose, as it did (it is GEOS's own rounding that decides; a few ulps cover it)."""

_TINY = 1e-150
"""Distances below which all are ties (their squares underflow)."""


def _nearest_vertex(points: np.ndarray, vertices: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """GEOS's R-tree's nearest of ``vertices`` to ``points[which]``: indices and distances."""
    index, distance = np.zeros(len(which), dtype=int), np.full(len(which), np.nan)
    if len(which) and len(vertices):
        tree = shapely.STRtree(shapely.points(vertices))
        (i, j), d = tree.query_nearest(shapely.points(points[which]), return_distance=True, all_matches=False)
        index[i], distance[i] = j, d
    return index, distance


def _nearest_segment(points: np.ndarray, a: np.ndarray, b: np.ndarray, which: np.ndarray) -> np.ndarray:
    """GEOS's R-tree's distance from ``points[which]`` to the nearest of segments ``a``–``b``."""
    distance = np.full(len(which), np.nan)
    if len(which) and len(a):
        segments = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
        (i, _), d = segments.query_nearest(shapely.points(points[which]), return_distance=True, all_matches=False)
        distance[i] = d
    return distance


def to_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points ``p`` to segments ``a``–``b`` (broadcast (..., 2) arrays, mm), in
    GEOS's operations and order (``Distance::pointToSegment``), so the numbers are its own."""
    bx, by = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    len2 = bx * bx + by * by
    with np.errstate(divide="ignore", invalid="ignore"):
        r = ((p[..., 0] - a[..., 0]) * bx + (p[..., 1] - a[..., 1]) * by) / len2
        s = ((a[..., 1] - p[..., 1]) * bx - (a[..., 0] - p[..., 0]) * by) / len2
    to_a = np.sqrt((p[..., 0] - a[..., 0]) ** 2 + (p[..., 1] - a[..., 1]) ** 2)
    to_b = np.sqrt((p[..., 0] - b[..., 0]) ** 2 + (p[..., 1] - b[..., 1]) ** 2)
    # a zero-length segment is its point (GEOS: A == B), as r is NaN there
    return np.where((len2 == 0) | (r <= 0), to_a, np.where(r >= 1, to_b, np.abs(s) * np.sqrt(len2)))
