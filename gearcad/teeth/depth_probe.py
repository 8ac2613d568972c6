"""The point of many that lies deepest inside a ring, measured exactly only where it can matter.

:func:`.overcut.rack_overcut` places a rack cell at thousands of poses and asks which placed point
lies deepest inside a gear's outline, and how deep: its distance to the ring as GEOS measures it
(to the nearest segment: the number reported), a few microseconds a point.  Cheaper upper bounds
of the depth leave GEOS the few points that can be the deepest:

* the distance to the nearest vertex of the ring densified to ``spacing`` (a k-d tree, about a
  microsecond a point), and to the two pieces of the densified ring that meet there;
* along a placed cell, a sample's bound (every :data:`SAMPLE` th point; 0 outside the ring) plus
  the distance to it, depth being 1-Lipschitz: the tree is asked only about the samples and about
  the points these bounds leave in question.

A point is passed over only where its bound falls :data:`MARGIN` short of the depth of a point
measured (or of a floor the caller sets): it can be neither the deepest nor as deep.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ..geometry.verify import to_segments

__all__ = ["DepthProbe", "MARGIN", "SAMPLE"]

SAMPLE = 16
"""Every how many points along a placed cell the depth is bounded through the k-d tree."""

MARGIN = 1e-9
"""mm a bound must fall short of a depth measured before its point is passed over: far above the
rounding of distances under a metre, far below any depth reported."""

BATCH = 32
"""Points measured by GEOS at a time, deepest bound first."""


class DepthProbe:
    """Depths of points inside a closed ring (n, 2), mm, with ``spacing`` (mm) between the
    vertices of the densified ring the bounds use."""

    def __init__(self, ring: np.ndarray, spacing: float):
        self.polygon = shapely.Polygon(ring)
        shapely.prepare(self.polygon)
        self.tree = shapely.STRtree(shapely.linestrings(np.stack([ring, np.roll(ring, -1, axis=0)], axis=1)))
        self.dense = shapely.get_coordinates(shapely.segmentize(shapely.LinearRing(ring), spacing))
        self.vertices = cKDTree(self.dense)

    def inside(self, xy: np.ndarray) -> np.ndarray:
        """Indices of the points of ``xy`` (n, 2) inside the ring."""
        return np.nonzero(shapely.contains_xy(self.polygon, xy[:, 0], xy[:, 1]))[0]

    def caps(self, placed: np.ndarray) -> np.ndarray:
        """(poses, n) upper bounds of the depths of a cell's points placed at some poses
        (poses, n, 2): at every :data:`SAMPLE` th point of the cell its own (0 outside the ring),
        elsewhere the smaller of the two samples' either side plus the distance to it."""
        samples = placed[:, ::SAMPLE]
        flat = samples.reshape(-1, 2)
        inside = self.inside(flat)
        bound = np.zeros(len(flat))
        bound[inside] = self._bounds(flat[inside])[0]
        bound = bound.reshape(samples.shape[:2])
        before = np.arange(placed.shape[1]) // SAMPLE
        after = np.minimum(before + 1, samples.shape[1] - 1)
        return np.minimum(
            *(bound[:, end] + np.linalg.norm(placed - samples[:, end], axis=-1) for end in (before, after))
        )

    def deepest(self, xy: np.ndarray, caps: np.ndarray, floor: float = 0.0) -> tuple[float, int]:
        """(depth, index) of the point of ``xy`` (n, 2) deepest inside the ring, if it is at least
        ``floor`` deep (mm); ``caps`` (n,) bound the points' depths from above (−inf: a point not
        to look at).  (0, −1) where none is inside (or as deep as the floor, less :data:`MARGIN`).
        Of equally deep points, the one farthest from the densified ring's vertices (the first
        that a search in that order meets), then the first in ``xy``."""
        least = max(floor - MARGIN, 0.0)
        lead = np.argmax(caps, keepdims=True) if len(caps) else np.zeros(0, dtype=int)
        lead = lead[np.isfinite(caps[lead])]
        lead = lead[self.inside(xy[lead])]
        if len(lead):  # a depth measured: the bound to beat
            floor = max(floor, float(self._depths(xy[lead])[1][0]))
        near = np.flatnonzero(caps >= floor - MARGIN)
        near = near[self.inside(xy[near])]
        close, bound = self._bounds(xy[near])
        keep = close >= floor - MARGIN
        near, close, bound = near[keep], close[keep], bound[keep]
        order = np.argsort(-close)
        depth = np.full(len(near), -np.inf)
        best = least
        for start in range(0, len(order), BATCH):
            batch = order[start : start + BATCH]
            if close[batch[0]] < best - MARGIN:
                break
            i, d = self._depths(xy[near[batch]])
            depth[batch[i]] = d
            best = max(best, float(d.max()))
        if best <= least:
            return 0.0, -1
        tied = np.flatnonzero(depth == best)
        return best, int(near[tied[np.lexsort((near[tied], -bound[tied]))[0]]])

    def _bounds(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Upper bounds of the distances of the points ``xy`` (n, 2) to the ring: to the two
        pieces of the densified ring at the nearest vertex, and to that vertex."""
        bound, vertex = self.vertices.query(xy)
        ring = self.dense[:-1]  # the closed ring's last vertex repeats its first
        at = vertex % len(ring)
        close = bound
        for side in (-1, 1):
            close = np.fmin(close, to_segments(xy, ring[at], ring[(at + side) % len(ring)]))
        return close, bound

    def _depths(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(indices into ``xy``, distances to the ring) of the points ``xy`` (n, 2): GEOS's."""
        (i, _), d = self.tree.query_nearest(shapely.points(xy), return_distance=True, all_matches=False)
        return i, d
