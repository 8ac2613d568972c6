"""What the proof's bound (:mod:`.tube`) reads of each position's windows: the narrow window's
vertices where a mate can first touch it, with its own outline's direction at each, and the wide
window's edges, their middles in a k-d tree (docs/fit.md, "The vertex's own normal; only the
vertices a mate can first touch; the windows made once")."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

__all__ = ["corners", "outlines"]


def outlines(narrow: np.ndarray, wide: np.ndarray) -> list[tuple]:
    """For each pair of a gear's windows (arrays of geometries, alike in length): (the narrow
    window's vertices where the bound must look (:func:`corners`), the wide window's edge starts
    and ends, its edges for a search by distance (:func:`_pieces`), each vertex's normal: the unit
    normal to the chord between its neighbours, its own outline's direction there) — the work of
    all in a few array operations."""
    n = len(narrow)
    rings, window = _rings(wide)
    ends, ring = shapely.get_coordinates(rings, return_index=True)
    same = ring[1:] == ring[:-1]
    p, q, owner = ends[:-1][same], ends[1:][same], window[ring[:-1][same]]
    cuts = np.searchsorted(owner, np.arange(n + 1))  # each window's edges, in order
    middle, half, edge = _pieces(p, q)
    pieces = np.searchsorted(edge, cuts)  # each window's pieces, in order
    xy, normal, of = corners(narrow)
    starts = np.searchsorted(of, np.arange(n + 1))  # each window's vertices, in order
    return [
        (
            xy[starts[j] : starts[j + 1]],
            p[cuts[j] : cuts[j + 1]],
            q[cuts[j] : cuts[j + 1]],
            (
                cKDTree(middle[pieces[j] : pieces[j + 1]]),
                float(half[pieces[j] : pieces[j + 1]].max(initial=0.0)),
                edge[pieces[j] : pieces[j + 1]] - cuts[j],
            ),
            normal[starts[j] : starts[j + 1]],
        )
        for j in range(n)
    ]


def _pieces(p: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The edges p→q cut into pieces no longer than four times the median edge (the long ones:
    the window's own cut, a bore's flat) for a k-d tree of the pieces' middles: (middles,
    half-lengths, each piece's edge).  Every edge within d of a point has a piece whose middle
    lies within d + the largest half-length — a superset of the edges the bound wants, which it
    then filters exactly; without the cut the window's few long edges would widen every query."""
    half = np.hypot(*(q - p).T) / 2
    if not len(half):
        return np.empty((0, 2)), half, np.empty(0, dtype=np.intp)
    size = max(4 * float(np.median(half)), float(half.max()) / 256, 1e-9)  # (at most 256 pieces an edge)
    count = np.maximum(np.ceil(half / size), 1).astype(np.intp)
    edge = np.repeat(np.arange(len(half)), count)
    k = np.arange(len(edge)) - np.repeat(np.cumsum(count) - count, count)
    along = ((k + 0.5) / count[edge])[:, None]
    return p[edge] + along * (q - p)[edge], half[edge] / count[edge], edge


def _rings(windows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every ring of ``windows`` (exterior then holes, part by part) and the window each is of."""
    parts, window = shapely.get_parts(windows, return_index=True)
    rings, part = shapely.get_rings(parts, return_index=True)
    return rings, window[part]


def corners(narrow: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The vertices of the windows ``narrow`` where a mate can first touch them, at each the unit
    normal to the chord from the vertex before it to the one after it (a direction, not a side:
    either sign serves :func:`.tube.tubes`; (1, 0) where the chord is a point), and the window each is of.

    Two polygons that come together first touch with a vertex of one on an edge of the other, and
    that vertex is not reflex: at a reflex vertex the part fills more than a half-disc about it,
    so an edge's inside or a reflex vertex of the mate there would already overlap it — a reflex
    vertex touches only at a vertex of the mate that is not, which meets the reflex vertex's own
    edges.  So each ring's reflex vertices (a root fillet's, seen from the part) are left out, as
    is the vertex a closed ring repeats."""
    rings, window = _rings(shapely.orient_polygons(narrow))  # the inside on the left
    xy, ring = shapely.get_coordinates(rings, return_index=True)
    if not len(xy):
        return np.empty((0, 2)), np.empty((0, 2)), np.empty(0, dtype=int)
    new = np.r_[True, ring[1:] != ring[:-1]]
    starts = np.flatnonzero(new)
    run = np.cumsum(new) - 1  # each row's ring, counted among the rings that have rows
    first, size = starts[run], np.maximum(np.diff(np.r_[starts, len(ring)]) - 1, 1)[run]
    at = np.arange(len(ring)) - first
    before, after = xy[first + (at - 1) % size], xy[first + (at + 1) % size]
    chord = after - before
    length = np.hypot(*chord.T)
    normal = np.column_stack([-chord[:, 1], chord[:, 0]]) / np.maximum(length, 1e-300)[:, None]
    normal = np.where((length > 0)[:, None], normal, [1.0, 0.0])
    ab, bc = xy - before, after - xy
    turn = ab[:, 0] * bc[:, 1] - ab[:, 1] * bc[:, 0]  # < 0: a right turn, reflex with the inside on the left
    reflex = turn < -1e-9 * np.hypot(*ab.T) * np.hypot(*bc.T)
    keep = (at < size) & ~reflex  # (the last row of a closed ring repeats its first)
    return xy[keep], normal[keep], window[ring[keep]]
