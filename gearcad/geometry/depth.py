"""How deep two placed outlines cut into each other, not only how much area they share.

An overlap's area cannot tell a long hairline at the tolerance from a short sliver many times
deeper: 0.12 mm × 15 µm has the area of 1.8 mm × 1 µm.  The depth can.  Every point of the
overlap's boundary lies on one outline's boundary and inside the other; how far it lies inside
is its distance to the other boundary, and the largest of these over the overlap is the
penetration depth — how far one part must give way, along the normal, for the other to pass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

__all__ = ["Depths", "inradius", "overlap_depths", "overlap_areas", "overlap_exceeds"]


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


def _overlaps(first: np.ndarray, second: np.ndarray, screen: bool) -> tuple[np.ndarray, np.ndarray]:
    """(indices, overlaps): the pairs that intersect and their intersections.  With ``screen`` the
    overlay is computed only for them: the predicate is far cheaper, and most pairs of a meshing
    pair with play, or of a search for where it turns free, do not touch at all.  Without, every
    pair is overlaid (those that do not touch give an empty overlap, of area 0 all the same):
    where all overlap, as a pair nudged into its mate, the predicate would only add its time."""
    if not screen:
        return np.arange(len(first)), shapely.intersection(first, second)
    hit = np.flatnonzero(shapely.intersects(first, second))
    return hit, shapely.intersection(first[hit], second[hit])


def overlap_areas(first, second, *, screen: bool = True) -> np.ndarray:
    """The area each ``first[k]`` shares with ``second[k]`` (shapely polygons; either may be one
    polygon for all), mm²: what ``shapely.area(shapely.intersection(first, second))`` gives.
    ``screen``: see :func:`_overlaps`."""
    first, second = np.broadcast_arrays(np.asarray(first, dtype=object), np.asarray(second, dtype=object))
    area = np.zeros(first.shape)
    hit, overlap = _overlaps(first, second, screen)
    area[hit] = shapely.area(overlap)
    return area


def overlap_exceeds(first, second, area: float, *, stride: int = 4) -> np.ndarray:
    """Whether each ``first[k]`` shares more than ``area`` mm² with ``second[k]``: what
    ``overlap_areas(first, second) > area`` gives for an ``area`` far above rounding (a search's
    1e-9 m²), with the overlay left out where a disc inside both shows it (``first`` prepared
    for speed: shapely.prepare).

    A bisection for where two parts come free asks only this, and many of its probes overlap
    deeply, where the overlay costs most.  A disc of twice ``area`` inside both outlines proves
    the overlap larger: the overlay's area is exact to its rounding (~1e-13 mm² on outlines of
    tens of mm), far under ``area``.  The disc is sought about every ``stride``-th vertex of
    ``second`` that lies inside ``first``: its centre a little to either side of ``second``'s
    outline there, where it may lie inside both.
    """
    first, second = np.broadcast_arrays(np.asarray(first, dtype=object), np.asarray(second, dtype=object))
    out = _disc_inside(first, second, math.sqrt(2 * area / math.pi), stride)
    rest = np.flatnonzero(~out)
    rest = rest[shapely.intersects(first[rest], second[rest])]
    out[rest] = shapely.area(shapely.intersection(first[rest], second[rest])) > area
    return out


def _disc_inside(first: np.ndarray, second: np.ndarray, radius: float, stride: int) -> np.ndarray:
    """(n,) bool: a disc of ``radius`` found inside both ``first[k]`` and ``second[k]``, centred
    1.5 radii off a vertex of ``second`` inside ``first``, square to the chord of its neighbours
    (rows of other rings at a ring's ends: a wrong side, never a wrong answer)."""
    sure = np.zeros(len(first), dtype=bool)
    xy, which = shapely.get_coordinates(second, return_index=True)
    rows = np.arange(1, len(xy) - 1, stride)
    rows = rows[shapely.contains_xy(first[which[rows]], xy[rows, 0], xy[rows, 1])]
    if not len(rows):
        return sure
    owner = which[rows]
    last = np.flatnonzero(np.append(owner[1:] != owner[:-1], True))  # each pair's last vertex found
    rows, owner = rows[last], owner[last]
    chord = xy[rows + 1] - xy[rows - 1]
    step = 1.5 * radius / np.maximum(np.hypot(chord[:, 0], chord[:, 1]), 1e-300)
    off = step[:, None] * np.column_stack([-chord[:, 1], chord[:, 0]])
    centre = np.vstack([xy[rows] + off, xy[rows] - off])
    owner = np.tile(owner, 2)
    inside = shapely.contains_xy(first[owner], centre[:, 0], centre[:, 1]) & shapely.contains_xy(
        second[owner], centre[:, 0], centre[:, 1]
    )
    centre, owner = shapely.points(centre[inside]), owner[inside]
    clear = (shapely.distance(centre, shapely.boundary(first[owner])) > radius * (1 + 1e-6) + 1e-9) & (
        shapely.distance(centre, shapely.boundary(second[owner])) > radius * (1 + 1e-6) + 1e-9
    )
    sure[owner[clear]] = True
    return sure


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
    touch, overlap = _overlaps(first, second, screen=True)
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


def inradius(overlaps, tol: float) -> np.ndarray:
    """The radius of the largest disc inside each of ``overlaps`` (shapely polygons; 0 where
    empty), to ``tol`` mm: where two parts overlap, the least shrink of both their edges that
    parts them.  A point of the overlap keeps ε from both outlines exactly when it keeps ε from
    the overlap's boundary (which lies on one outline or the other, and any way out of the
    overlap crosses it), so the parts shrunk by ε share a point exactly while the overlap shrunk
    by ε is not empty: bisected on that, from πr² ≤ its area (an overlap is a sliver: shrinking
    it, not the parts, is cheap; its concave corners' arcs in 16 chords a quarter: 0.12 % under).

    >>> import shapely
    >>> lens = shapely.Point(0, 0).buffer(5, 256).intersection(shapely.Point(9.9, 0).buffer(5, 256))
    >>> round(float(inradius([lens], 1e-7)[0]), 6)  # half of 2·5 − 9.9
    0.05
    """
    overlaps = np.asarray(overlaps, dtype=object)
    area = shapely.area(overlaps)
    hi = np.where(area > 0, np.sqrt(area / math.pi) * (1 + 1e-6) + 1e-12, 0.0)
    lo = np.zeros_like(hi)
    live = np.flatnonzero(hi > tol)
    while len(live):
        mid = 0.5 * (lo[live] + hi[live])
        gone = shapely.is_empty(shapely.buffer(overlaps[live], -mid, quad_segs=16))
        hi[live], lo[live] = np.where(gone, mid, hi[live]), np.where(gone, lo[live], mid)
        live = live[hi[live] - lo[live] > tol]
    return hi
