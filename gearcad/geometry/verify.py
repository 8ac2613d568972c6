"""Checks of rings as written: simple (no crossing, no touching), and within a distance of the
exact outline they stand for."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

__all__ = ["is_simple", "max_distance"]


def is_simple(ring: np.ndarray) -> bool:
    """True when the closed ring (open (n, 2) array) neither crosses nor touches itself."""
    return bool(len(ring) >= 3 and shapely.LinearRing(ring).is_simple)


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(np.einsum("...j,...j->...", p - a, ab) / np.maximum(np.einsum("...j,...j->...", ab, ab), 1e-300), 0, 1)
    return np.hypot(*np.moveaxis(p - (a + t[..., None] * ab), -1, 0))


def max_distance(points: np.ndarray, ring: np.ndarray, *, limit: float, candidates: int = 8) -> float:
    """The largest distance from ``points`` to the closed polyline ``ring`` (mm): exact where it
    exceeds ``limit``, an upper bound at most ``limit`` otherwise.

    Each point is first measured against the ``candidates`` segments with the nearest midpoints
    (a true distance, so an upper bound); only points whose bound exceeds ``limit`` are measured
    against every segment.  O(n log m) for a ring that follows the points.
    """
    a, b = ring, np.roll(ring, -1, axis=0)
    k = min(candidates, len(ring))
    _, idx = cKDTree((a + b) / 2).query(points, k=k)
    idx = idx.reshape(len(points), k)
    d = _segment_distance(points[:, None, :], a[idx], b[idx]).min(axis=1)
    unsure = np.nonzero(d > limit)[0]
    if len(unsure):
        d[unsure] = shapely.distance(shapely.points(points[unsure]), shapely.LinearRing(ring))
    return float(d.max()) if len(d) else 0.0
