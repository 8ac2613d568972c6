"""How deep two placed outlines cut into each other, not only how much area they share.

An overlap's area cannot tell a long hairline at the tolerance from a short sliver many times
deeper: 0.12 mm × 15 µm has the area of 1.8 mm × 1 µm.  The depth can.  Every point of the
overlap's boundary lies on one outline's boundary and inside the other; how far it lies inside
is its distance to the other boundary, and the largest of these over the overlap is the
penetration depth — how far one part must give way, along the normal, for the other to pass.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

__all__ = ["Depths", "overlap_depths", "overlap_areas"]


@dataclass(frozen=True)
class Depths:
    """Penetration depth of each pair of placed outlines and where it is deepest."""

    depth: np.ndarray
    """(n,) largest distance of an overlap boundary point inside the other outline, mm;
    0 where the pair does not overlap."""
    point: np.ndarray
    """(n, 2) that deepest point, mm (NaN where there is no overlap)."""
    area: np.ndarray
    """(n,) the overlap's area, mm²."""


def _overlaps(first: np.ndarray, second: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(indices, overlaps): the pairs that intersect and their intersections.  The overlay is
    computed only for them: the predicate is far cheaper, and most pairs of a meshing pair (or of
    a search for where it turns free) do not touch at all."""
    hit = np.flatnonzero(shapely.intersects(first, second))
    return hit, shapely.intersection(first[hit], second[hit])


def overlap_areas(first, second) -> np.ndarray:
    """The area each ``first[k]`` shares with ``second[k]`` (shapely polygons; either may be one
    polygon for all), mm²: what ``shapely.area(shapely.intersection(first, second))`` gives."""
    first, second = np.broadcast_arrays(np.asarray(first, dtype=object), np.asarray(second, dtype=object))
    area = np.zeros(first.shape)
    hit, overlap = _overlaps(first, second)
    area[hit] = shapely.area(overlap)
    return area


def overlap_depths(first, second, *, step: float) -> Depths:
    """Penetration depths of ``first[k]`` and ``second[k]`` (shapely polygons, arrays of n).

    The overlap's boundary is sampled at least every ``step`` mm (its vertices and points
    between them), and each sample's distance to the boundary of the outline it did not come
    from is measured: the sample on one boundary is at ~0 from its own, so the larger of the
    two distances is its depth in the other.

    >>> import shapely
    >>> a = shapely.box(0, 0, 10, 10)
    >>> b = shapely.Polygon([(4, 10.5), (5, 9.985), (6, 10.5)])  # a tip 15 µm into a
    >>> d = overlap_depths([a], [b], step=0.1)
    >>> round(float(d.depth[0]), 6), d.point[0].round(3).tolist()
    (0.015, [5.0, 9.985])
    """
    first = np.asarray(first, dtype=object)
    second = np.asarray(second, dtype=object)
    n = len(first)
    depth, area = np.zeros(n), np.zeros(n)
    point = np.full((n, 2), np.nan)
    touch, overlap = _overlaps(first, second)
    area[touch] = shapely.area(overlap)
    keep = area[touch] > 0
    hit, overlap = touch[keep], overlap[keep]
    if len(hit) == 0:
        return Depths(depth, point, area)
    rims = shapely.segmentize(shapely.boundary(overlap), step)
    xy, which = shapely.get_coordinates(rims, return_index=True)
    samples = shapely.points(xy)
    inside = np.maximum(
        shapely.distance(samples, shapely.boundary(first[hit])[which]),
        shapely.distance(samples, shapely.boundary(second[hit])[which]),
    )
    order = np.lexsort((inside, which))  # per overlap, its deepest sample last
    last = np.r_[np.nonzero(np.diff(which[order]))[0], len(order) - 1]
    deepest = order[last]
    depth[hit[which[deepest]]] = inside[deepest]
    point[hit[which[deepest]]] = xy[deepest]
    return Depths(depth, point, area)
