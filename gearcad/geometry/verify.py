"""Checks of rings as written: simple (no crossing, no touching), and within a distance of the
exact outline they stand for."""

from __future__ import annotations

import numpy as np
import shapely

from .arcfit import decimate

__all__ = ["is_simple", "max_distance", "nearest", "thin"]


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
    """For each point, the index of the nearest of ``vertices`` and the distance to it."""
    tree = shapely.STRtree(shapely.points(vertices))
    (i, j), d = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    index, distance = np.empty(len(points), dtype=int), np.empty(len(points))
    index[i], distance[i] = j, d
    return index, distance


def max_distance(points: np.ndarray, ring: np.ndarray, *, limit: float = 0.0) -> float:
    """The largest distance from ``points`` to the closed polyline ``ring`` (mm), exact.

    The segments sit in an R-tree and each point is measured against its nearest one by GEOS:
    O(n log m).  (``limit`` is accepted for callers that only need to know whether it exceeds it.)
    """
    if not len(points):
        return 0.0
    segments = shapely.linestrings(np.stack([ring, np.roll(ring, -1, axis=0)], axis=1))
    _, d = shapely.STRtree(segments).query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    return float(d.max())
