"""The distance between placed outlines, what ``shapely.distance`` gives, measured on their edges
cut into short runs, the runs nearest the contact first.

Between two polygons GEOS's distance looks at every edge of one against every edge of the other
(n·m pairs: ~85 µs for two 180-edge windows of a mesh); it skips only pairs whose bounding boxes
lie farther apart than the least distance found so far, and it finds that least late, walking the
rings from wherever they start.  The same edges cut into runs of a few and given as
multi-linestrings, nearest the contact first, bring the least distance in the first runs
compared; the boxes of the other runs then lie farther, and GEOS skips them run by run (its part
a sixth of the time on the bands' windows; with the runs' lines built, under half).  Each pair of
edges it does compare is measured by the same segment-to-segment formula with its points in the
same order, and a pair skipped in one order but not the other lies, box and all, no nearer than
the least: the least is the same number (short of a pair's distance and its box's differing in
the last bit where another pair ties it, which no band of the profiles or the tests met).  What
a polygon adds is checked apart, as GEOS does first: the distance is 0 where the first vertex of
a polygon of either outline lies in (or on) the other.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

__all__ = ["Runs", "distances", "runs"]

EDGES = 16
"""Edges a run holds: fewer make each run's box tighter but give more lines to build."""


@dataclass(frozen=True)
class Runs:
    """n outlines' rings cut into runs of edges, each outline's nearest a given point first.  A
    run is ``size`` consecutive rows of its outline's coordinates (``shapely.get_coordinates`` of
    it alone, rings one after another) from row ``start``; within a ring its last row is the next
    run's first."""

    owner: np.ndarray
    """(k,) the outline of each run, ascending."""
    start: np.ndarray
    """(k,) the run's first row, counted from its outline's first."""
    size: np.ndarray
    """(k,) its rows: its edges and one."""
    rows: np.ndarray
    """(n,) each outline's coordinate rows."""

    def lines(self, xy: np.ndarray, at: np.ndarray | None = None) -> np.ndarray:
        """The outlines ``at`` (ascending indices; default all) as MultiLineStrings of their runs,
        from their coordinates ``xy`` (placed anywhere: the rows of those outlines, one after
        another)."""
        at = np.arange(len(self.rows)) if at is None else np.asarray(at)
        slot = np.full(len(self.rows), -1)
        slot[at] = np.arange(len(at))
        first = np.cumsum(self.rows[at]) - self.rows[at]  # each chosen outline's first row of xy
        keep = slot[self.owner] >= 0
        owner, size = slot[self.owner[keep]], self.size[keep]
        begin = first[owner] + self.start[keep]
        rows = np.repeat(begin - np.cumsum(size) + size, size) + np.arange(int(size.sum()))
        lines = shapely.linestrings(xy[rows], indices=np.repeat(np.arange(len(size)), size))
        out = np.full(len(at), shapely.MultiLineString(), dtype=object)  # an empty outline: no runs
        return shapely.multilinestrings(lines, indices=owner, out=out)


def runs(outlines: np.ndarray, near: np.ndarray, *, edges: int = EDGES) -> Runs:
    """The rings of each of ``outlines`` (n shapely polygons) cut into runs of ``edges`` edges,
    ordered by the distance of their middle vertex from ``near`` ((n, 2), mm: the contact); an
    outline of another kind gets none (:func:`distances` measures it whole)."""
    outlines = np.asarray(outlines, dtype=object)
    rows = shapely.get_num_coordinates(outlines)
    parts, part_of = shapely.get_parts(np.where(_polygonal(outlines), outlines, None), return_index=True)
    rings, ring_of = shapely.get_rings(parts, return_index=True)
    owner_of_ring = part_of[ring_of]
    count = shapely.get_num_coordinates(rings)
    ring_first = np.cumsum(count) - count  # rows of all outlines' rings, one after another
    cuts = -(-(count - 1) // edges)  # runs of each ring
    ring = np.repeat(np.arange(len(rings)), cuts)
    step = np.arange(int(cuts.sum())) - np.repeat(np.cumsum(cuts) - cuts, cuts)
    start = ring_first[ring] + step * edges
    size = np.minimum(edges, count[ring] - 1 - step * edges) + 1
    owner = owner_of_ring[ring]
    xy = shapely.get_coordinates(rings)
    middle = xy[start + size // 2]
    local = start - ring_first[np.searchsorted(owner_of_ring, owner)]  # from the outline's first ring
    order = np.lexsort((np.hypot(*(middle - near[owner]).T), owner))
    return Runs(owner[order], local[order], size[order], rows)


def distances(first: np.ndarray, second: np.ndarray, first_lines: np.ndarray, second_lines: np.ndarray) -> np.ndarray:
    """``shapely.distance(first, second)`` of (n,) polygons, mm, from their runs' lines
    (:meth:`Runs.lines` of the same outlines as placed)."""
    gap = shapely.distance(first_lines, second_lines)
    gap[_holds_a_start(first, second) | _holds_a_start(second, first)] = 0.0
    odd = np.flatnonzero(~(_polygonal(first) & _polygonal(second)))  # lines or points among them
    gap[odd] = shapely.distance(first[odd], second[odd])
    return gap


def _polygonal(outlines: np.ndarray) -> np.ndarray:
    return np.isin(shapely.get_type_id(outlines), (shapely.GeometryType.POLYGON, shapely.GeometryType.MULTIPOLYGON))


def _holds_a_start(outer: np.ndarray, inner: np.ndarray) -> np.ndarray:
    """(n,) bool: the first vertex of some polygon of ``inner[k]`` lies in or on ``outer[k]`` (the
    points GEOS's distance tests first, and finds 0 at)."""
    parts, which = shapely.get_parts(inner, return_index=True)
    starts = shapely.get_point(shapely.get_exterior_ring(parts), 0)
    x, y = shapely.get_x(starts), shapely.get_y(starts)
    held = shapely.intersects_xy(outer[which], x, y)
    return np.bincount(which[held], minlength=len(inner)) > 0
