"""How far a polygon turns about a pivot before it touches another: exact, in one pass.

Two polygons that move continuously first touch with a vertex of one on an edge of the other.
Turned about a pivot C, a vertex of the turning polygon runs on the circle about C through it, and
a vertex of the still one runs, seen from the turning one, on its own circle the other way.  So
the first touch each way is the least turn at which some vertex's circle meets an edge of the
other polygon: for each (vertex, edge) pair whose edge reaches the vertex's radius, the points of
the edge at that radius (a quadratic's roots) and the angle between.  The pairs are found by
radius: each edge is filed under the bands of radius it spans, each vertex looks only in its own.

The play a band measures is this turn each way (:func:`~gearcad.fitting.play.play_between`): it
replaces the steps by the gap and the bisection they stalled into, which approached the same
touch from the free side (to a millionth of a module, or a 2⁻¹⁸ of the turn sought).
"""

from __future__ import annotations

import numpy as np
import shapely

__all__ = ["free_turns"]

BANDS = 2.0
"""The bands of radius are this many times an edge's median radial span wide."""
EVEN = 1e-12
"""A touch this near a turn of 0 (rad) is where the polygons stand: it stops both ways."""


def _edges(polygons: np.ndarray, pivot: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(starts, ends, owner): every ring edge of each polygon (n,), from its pivot ((n, 2)); a
    collection's polygons however deep (its lines and points hold no material), no edge of
    length 0 (a repeated vertex)."""
    parts, part_of = shapely.get_parts(polygons, return_index=True)
    while len(parts) and np.any(shapely.get_num_geometries(parts) > 1) | np.any(_collections(parts)):
        parts, inner = shapely.get_parts(parts, return_index=True)
        part_of = part_of[inner]
    rings, ring_of = shapely.get_rings(parts, return_index=True)
    xy, row_ring = shapely.get_coordinates(rings, return_index=True)
    owner = part_of[ring_of][row_ring]
    xy = xy - pivot[owner]
    same = row_ring[1:] == row_ring[:-1]
    p, q, owner = xy[:-1][same], xy[1:][same], owner[:-1][same]
    keep = np.any(p != q, axis=1)
    return p[keep], q[keep], owner[keep]


def _collections(parts: np.ndarray) -> np.ndarray:
    kinds = shapely.get_type_id(parts)
    return np.isin(kinds, (shapely.GeometryType.MULTIPOLYGON, shapely.GeometryType.GEOMETRYCOLLECTION))


def _touches(v, vpos, p, q, epos, moving_vertex: bool, limit: np.ndarray, n: int):
    """(up, down) per polygon: the least turn each way (≥ 0) at which a vertex ``v`` (of polygon
    ``vpos``) meets an edge [p, q] (of ``epos``) of the other, all from the pivot; the vertex
    the turning polygon's (``moving_vertex``) or the still one's; ``limit`` where none does."""
    up, down = limit.copy(), limit.copy()
    if not len(v) or not len(p):
        return up, down
    rho = np.hypot(v[:, 0], v[:, 1])
    d = q - p
    a = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    pd = np.einsum("ij,ij->i", p, d)
    s = np.clip(-pd / a, 0.0, 1.0)
    rmin = np.hypot(p[:, 0] + s * d[:, 0], p[:, 1] + s * d[:, 1])
    rmax = np.maximum(np.hypot(p[:, 0], p[:, 1]), np.hypot(q[:, 0], q[:, 1]))
    span = rmax - rmin
    width = BANDS * max(float(np.median(span[span > 0])) if np.any(span > 0) else 0.0, 1e-6 * float(rmax.max()), 1e-12)
    lo, hi = np.floor(rmin / width).astype(np.int64), np.floor(rmax / width).astype(np.int64)
    bands = int(max(hi.max(), np.floor(rho.max() / width))) + 1
    count = hi - lo + 1
    entry = np.repeat(np.arange(len(p)), count)
    within = np.arange(len(entry)) - np.repeat(np.cumsum(count) - count, count)  # the band's place in the edge's
    key = epos[entry] * bands + np.repeat(lo, count) + within
    order = np.argsort(key, kind="stable")
    key, entry = key[order], entry[order]
    vkey = vpos * bands + np.floor(rho / width).astype(np.int64)
    first, last = np.searchsorted(key, vkey, "left"), np.searchsorted(key, vkey, "right")
    many = last - first
    vi = np.repeat(np.arange(len(v)), many)
    ei = entry[np.repeat(first - np.cumsum(many) + many, many) + np.arange(int(many.sum()))]
    keep = (rmin[ei] <= rho[vi]) & (rho[vi] <= rmax[ei])
    vi, ei = vi[keep], ei[keep]
    if not len(vi):
        return up, down
    # |p + s·d|² = ρ²: a·s² + 2(p·d)·s + |p|² − ρ² = 0
    half_b, c = pd[ei], np.einsum("ij,ij->i", p[ei], p[ei]) - rho[vi] ** 2
    root = np.sqrt(np.maximum(half_b * half_b - a[ei] * c, 0.0))
    angle_v = np.arctan2(v[vi, 1], v[vi, 0])
    owner = vpos[vi]
    for sign in (-1.0, 1.0):
        s = (-half_b + sign * root) / a[ei]
        on = (s >= 0.0) & (s <= 1.0)
        x = p[ei[on]] + s[on, None] * d[ei[on]]
        turn = np.arctan2(x[:, 1], x[:, 0]) - angle_v[on]
        turn = turn if moving_vertex else -turn
        turn = (turn + np.pi) % (2 * np.pi) - np.pi
        who = owner[on]
        ahead, behind = turn >= -EVEN, turn <= EVEN  # (a touch as placed stops both ways)
        np.minimum.at(up, who[ahead], np.maximum(turn[ahead], 0.0))
        np.minimum.at(down, who[behind], np.maximum(-turn[behind], 0.0))
    return up, down


def free_turns(still: np.ndarray, turning: np.ndarray, pivot: np.ndarray, limit) -> tuple[np.ndarray, np.ndarray]:
    """(up, down): for each k, how far (rad, ≥ 0) ``turning[k]`` turns about ``pivot[k]`` (mm)
    counter-clockwise and clockwise before it touches ``still[k]`` (polygons), at most ``limit``
    (rad, scalar or per k; no more than π: a turn is found within (−π, π]); 0 both ways where
    they overlap as placed (a vertex already inside meets no edge the way it goes deeper)."""
    n = len(still)
    pivot = np.asarray(pivot, dtype=float).reshape(n, 2)
    limit = np.minimum(np.broadcast_to(np.asarray(limit, dtype=float), (n,)), np.pi)
    if not n:
        return limit, limit.copy()
    p1, q1, o1 = _edges(np.asarray(still, dtype=object), pivot)
    p2, q2, o2 = _edges(np.asarray(turning, dtype=object), pivot)
    up, down = _touches(p2, o2, p1, q1, o1, True, limit, n)
    up2, down2 = _touches(p1, o1, p2, q2, o2, False, limit, n)
    up, down = np.minimum(up, up2), np.minimum(down, down2)
    still, turning = np.asarray(still, dtype=object), np.asarray(turning, dtype=object)
    inside = shapely.intersects(still, turning) & ~shapely.touches(still, turning)
    up[inside] = down[inside] = 0.0
    return up, down
