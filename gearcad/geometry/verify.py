"""Checks of rings as written: simple (no crossing, no touching), and within a distance of the
exact outline they stand for."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .arcfit import decimate

__all__ = ["distances", "is_simple", "max_distance", "nearest", "thin"]


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
    """For each point, the index of the nearest of ``vertices`` and the distance to it.

    A k-d tree finds the two nearest (its distance is GEOS's, √(dx² + dy²)); where they tie, the
    R-tree of GEOS picks, as it always has (a point on a symmetric gear's axis)."""
    points, vertices = np.asarray(points, dtype=float), np.asarray(vertices, dtype=float)
    k = min(2, len(vertices))
    distance, index = cKDTree(vertices).query(points, k=k)
    distance, index = distance.reshape(len(points), k), index.reshape(len(points), k)
    tied = np.flatnonzero(distance[:, 0] == distance[:, -1]) if k > 1 else []
    distance, index = distance[:, 0], index[:, 0]
    if len(tied):
        tree = shapely.STRtree(shapely.points(vertices))
        (i, j), d = tree.query_nearest(shapely.points(points[tied]), return_distance=True, all_matches=False)
        index[tied[i]], distance[tied[i]] = j, d
    return index, distance


def max_distance(points: np.ndarray, ring: np.ndarray, *, limit: float = 0.0) -> float:
    """The largest distance from ``points`` to the closed polyline ``ring`` (mm), exact
    (:func:`distances`).  (``limit`` is accepted for callers that only need to know whether it
    exceeds it.)"""
    return float(distances(points, [ring]).max()) if len(points) else 0.0


def distances(points: np.ndarray, rings) -> np.ndarray:
    """Each point's distance to the nearest of the closed polylines ``rings`` ((n, 2) arrays,
    mm), exact: the numbers GEOS gives (:func:`_to_segments` is its point-to-segment distance,
    operation for operation).

    The rings are sampled at least every h mm (their vertices, and points between them on the
    longer segments; h twice the median segment: fewer samples for a few more pairs) into a k-d
    tree.  The nearest sample bounds each point's distance, r; its nearest segment comes within
    r, so a sample of it (or its end) lies within r + h/2, and the segments either side of every
    sample that near are measured.  Points farther off than ``_FAR`` samples (rare: the pairs
    would grow with r) are measured by GEOS against an R-tree of the segments.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    rings = [np.asarray(r, dtype=float) for r in rings]
    start = np.cumsum([0] + [len(r) for r in rings])
    a = np.concatenate(rings)
    b = np.concatenate([np.roll(r, -1, axis=0) for r in rings])
    before = np.concatenate([s + (np.arange(len(r)) - 1) % len(r) for s, r in zip(start, rings)])
    length = np.hypot(*(b - a).T)
    h = max(2 * float(np.median(length)), 1e-12)
    count = np.maximum(np.ceil(length / h).astype(int), 1)
    owner = np.repeat(np.arange(len(a)), count)  # each sample's segment
    t = (np.arange(len(owner)) - np.repeat(np.cumsum(count) - count, count)) / count[owner]
    tree = cKDTree(a[owner] + t[:, None] * (b - a)[owner])
    r = tree.query(points)[0]  # each point's nearest sample: a bound on its distance
    bound = min(float(r.max(initial=0.0)), _FAR * h)
    near = np.flatnonzero(r <= bound)
    reach = (bound + h / 2) * (1 + 1e-9) + 1e-12  # with room for the tree's rounding
    pairs = cKDTree(points[near]).sparse_distance_matrix(tree, reach, output_type="ndarray")
    i, j = near[pairs["i"]], owner[pairs["j"]]
    d = np.full(len(points), np.inf)
    for seg in (j, before[j]):  # the segments either side of the sample
        np.minimum.at(d, i, _to_segments(points[i], a[seg], b[seg]))
    far = np.flatnonzero(r > bound)
    if len(far):
        segments = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
        (k, _), measured = segments.query_nearest(shapely.points(points[far]), return_distance=True, all_matches=False)
        d[far[k]] = measured
    return d


_FAR = 64
"""Samples' spacings beyond which a point is left to GEOS."""


def _to_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
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
