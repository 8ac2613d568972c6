"""The coupon's play, proven: a step's two sectors as made, put on the jig, the driver held and
the follower turned each way until it touches (see :mod:`gearcad.fitting.coupon`).

Every verdict here is a bracket, not a sample: a turn steps by the gap over the moving piece's
farthest reach (no point moves farther than the gap, so it never passes through), the contact lies
between the last turn shown apart and the first shown touching; a pair that binds is shown to
overlap at every turn of an interval (each overlapping turn covers those less than its deepest
vertex's depth over the reach away).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
import shapely.ops
from shapely import affinity

__all__ = ["Placed", "feeler_gap", "free_turn", "play_of", "tooth_mark", "turned"]


def turned(polygon: shapely.Polygon, pivot: tuple[float, float], angle: float) -> shapely.Polygon:
    return affinity.rotate(polygon, angle, origin=pivot, use_radians=True)


def _reach(polygon: shapely.Polygon, pivot: tuple[float, float]) -> float:
    """The farthest any point of ``polygon`` lies from ``pivot`` (a vertex's distance), mm."""
    xy = shapely.get_coordinates(polygon) - np.asarray(pivot)
    return float(np.hypot(xy[:, 0], xy[:, 1]).max())


def free_turn(
    fixed: shapely.Polygon,
    moving: shapely.Polygon,
    pivot: tuple[float, float],
    sigma: int,
    start: float,
    lever: float,
    *,
    eps: float = 1e-6,
    limit: float = math.inf,
) -> tuple[float, float] | None:
    """Turn ``moving`` about ``pivot`` from ``start`` (rad, where it is apart from ``fixed``) in the
    sense ``sigma`` (+1 anticlockwise) until it touches: (a, b) with every turn from ``start`` to
    ``a`` proven apart and the two touching or overlapping at ``b`` (so the first contact lies in
    (a, b]).  Each step turns by the gap over the farthest reach of ``moving``: no point of it moves
    farther than the gap, so it never passes through ``fixed``; the gap shrinks by about
    lever/reach each step (``lever``: the contact's arm, mm); under ``eps`` mm, ``b`` is tried at a
    few multiples of gap/lever until the two meet.  None: it turned more than ``limit`` (rad) free."""
    reach = _reach(moving, pivot)
    shapely.prepare(fixed)
    turn, last = start, start
    for _ in range(400):
        gap = float(shapely.distance(fixed, turned(moving, pivot, turn)))
        if gap <= 0:  # touching where the last step ended: [start, last] was apart
            return last, turn
        if gap <= eps:
            break
        if abs(turn - start) > limit:
            return None
        last, turn = turn, turn + sigma * gap / reach
    else:
        raise RuntimeError("the follower turns a whole cycle free: no mesh to measure")
    for k in (4, 16, 64, 256, 1024, 4096):
        far = turn + sigma * k * gap / lever
        if shapely.intersects(fixed, turned(moving, pivot, far)):
            return turn, far
    raise RuntimeError("no contact found past the last gap")


def _depth(fixed: shapely.Polygon, moving: shapely.Polygon) -> float:
    """How deep a vertex of either lies inside the other (mm; 0 where none does): turned by less
    than that over its reach, the two still overlap."""
    deepest = 0.0
    for a, b in ((fixed, moving), (moving, fixed)):
        xy = shapely.get_coordinates(b)
        inside = shapely.contains_xy(a, xy[:, 0], xy[:, 1])
        if inside.any():
            deepest = max(deepest, float(shapely.distance(a.boundary, shapely.points(xy[inside])).max()))
    return deepest


def _free_start(fixed, moving, pivot, bound: float) -> float | None:
    """A turn within ±``bound`` (rad) where ``moving`` is apart from ``fixed``: 0 if it is as
    placed, else the sample farthest apart; None when proven to touch or overlap at every turn
    within ±``bound`` (each overlapping sample covers the turns less than its depth over the reach
    away; the gaps between are bisected until covered)."""
    if not shapely.intersects(fixed, moving):
        return 0.0
    reach = _reach(moving, pivot)
    turns = list(np.linspace(-bound, bound, 17))
    gaps = [float(shapely.distance(fixed, turned(moving, pivot, t))) for t in turns]
    if max(gaps) > 0:
        return float(turns[int(np.argmax(gaps))])
    covered = [(t - d / reach, t + d / reach) for t in turns for d in [_depth(fixed, turned(moving, pivot, t))]]
    for _ in range(400):
        covered.sort()
        edge, hole = -bound, None
        for lo, hi in covered:
            if lo > edge:
                hole = (edge, lo)
                break
            edge = max(edge, hi)
        if hole is None and edge < bound:
            hole = (edge, bound)
        if hole is None:
            return None
        t = (hole[0] + hole[1]) / 2
        placed = turned(moving, pivot, t)
        if not shapely.intersects(fixed, placed):
            return t
        d = _depth(fixed, placed)
        covered.append((t - d / reach, t + d / reach) if d > 0 else (t, t))
        if d <= 0 and hole[1] - hole[0] < 1e-12:
            raise RuntimeError("cannot decide whether the pair binds")
    raise RuntimeError("cannot decide whether the pair binds")


@dataclass(frozen=True)
class Placed:
    """One place's pair on the jig: the world frame has the driver's pivot at the origin and the
    follower's at (E, 0); a sector placed is turned by its ``angle`` (rad) about its pivot."""

    center_distance: float
    angles: tuple[float, float]
    radius: float
    """The follower's pitch radius at the contact (mm): turns times it are play on its pitch curve."""
    lever: float
    module: float

    def world(self, polygon: shapely.Polygon, gear: int) -> shapely.Polygon:
        placed = turned(polygon, (0.0, 0.0), self.angles[gear])
        return affinity.translate(placed, self.center_distance, 0.0) if gear else placed


def play_of(pair: Placed, driver: shapely.Polygon, follower: shapely.Polygon):
    """(play, up, contact) of a step's pieces as made (world frame, follower at turn 0): the
    follower's free turn as a bracket (mm on its pitch curve), its anticlockwise stop's bracket
    (rad), and the clockwise contact (the driver's point, and the follower's at turn 0); all None
    where it binds."""
    pivot = (pair.center_distance, 0.0)
    start = _free_start(driver, follower, pivot, pair.module / pair.radius)
    if start is None:
        return None, None, None
    limit = math.pi * pair.module / pair.radius  # a pitch: further, the sectors' teeth slip out of mesh
    up = free_turn(driver, follower, pivot, +1, start, pair.lever, limit=limit)
    down = free_turn(driver, follower, pivot, -1, start, pair.lever, limit=limit)
    if up is None or down is None:
        return (math.pi * pair.module, math.inf), None, None
    play = ((up[0] - down[0]) * pair.radius, (up[1] - down[1]) * pair.radius)
    line = shapely.shortest_line(driver, turned(follower, pivot, down[0]))
    p_driver, p_follower = shapely.get_coordinates(line)
    back = turned(shapely.Point(p_follower), pivot, -down[0]).coords[0]
    return play, up, (tuple(p_driver), back)


def feeler_gap(pair: Placed, driver, follower, up: tuple[float, float], at) -> tuple[float, float]:
    """The gap (mm, a bracket) a feeler gauge meets at the marked flank: from the follower's edge
    point nearest ``at`` (world, follower at turn 0: where it touched turned clockwise) to the
    driver, with the follower at its anticlockwise stop (``up``: its bracket, rad)."""
    pivot = (pair.center_distance, 0.0)
    point = shapely.ops.nearest_points(follower.boundary, shapely.Point(at))[0]
    gap = float(shapely.distance(driver, turned(point, pivot, up[0])))
    slack = math.dist(point.coords[0], pivot) * abs(up[1] - up[0])  # how far it moves over the bracket
    return max(0.0, gap - slack), gap + slack


def tooth_mark(piece: shapely.Polygon, point: tuple[float, float], module: float) -> tuple[tuple[float, float], ...]:
    """A small triangle inside ``piece`` (its frame) pointing at ``point`` on a tooth's flank: on
    the line from the pivot, below the tooth's root."""
    x, y = point
    r = math.hypot(x, y)
    u = np.array([x, y]) / r
    v = np.array([-u[1], u[0]])
    room = piece.buffer(-0.3)
    for depth in 1.6 * module + 0.4 * np.arange(1, 12):
        apex = np.array([x, y]) - u * depth
        base = apex - 1.2 * u
        tri = [tuple(apex), tuple(base + 0.6 * v), tuple(base - 0.6 * v)]
        if room.contains(shapely.Polygon(tri)):
            return tuple((float(a), float(b)) for a, b in tri)
    return ()
