"""The exact turn before two polygons touch (gearcad/geometry/sweep.py), against a closed form
and against shapely's own intersection test on either side of the turn found."""

import math

import numpy as np
import pytest
import shapely
from shapely import affinity

from gearcad.geometry.sweep import free_turns


def test_a_spike_turning_onto_a_wall_stops_where_its_circle_meets_the_wall():
    """A vertex 2 mm from the pivot, pointing down, turned anticlockwise onto the wall x = 1:
    cos θ = 1/2, θ = −π/3, a turn of π/6; clockwise it would turn 7π/6 first, past the limit."""
    spike = shapely.Polygon([(-0.3, 0.0), (0.0, -2.0), (0.3, 0.0), (0.0, 0.5)])
    wall = shapely.box(1.0, -10.0, 3.0, 10.0)
    up, down = free_turns(np.array([wall]), np.array([spike]), np.zeros((1, 2)), 2.0)
    assert up[0] == pytest.approx(math.pi / 6, abs=1e-12)
    assert down[0] == 2.0
    # the wall turned instead (the spike still): the same turn the other way
    up, down = free_turns(np.array([spike]), np.array([wall]), np.zeros((1, 2)), 2.0)
    assert down[0] == pytest.approx(math.pi / 6, abs=1e-12) and up[0] == 2.0


def _star(rng, centre, radius, n):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = radius * (1 + 0.4 * rng.random(n))
    return shapely.Polygon(np.column_stack([centre[0] + r * np.cos(a), centre[1] + r * np.sin(a)]))


def test_the_turn_found_is_apart_just_short_of_it_and_touching_just_past():
    """Random star polygons (holes and all their vertices' circles): turned by the turn found less
    a millionth they are apart, by 1e-7 rad more they meet, at a dense sample short of it apart."""
    rng = np.random.default_rng(7)
    still, turning, pivots = [], [], []
    while len(still) < 40:
        a = _star(rng, (0.0, 0.0), 1.0, 40).difference(shapely.Point(0, 0).buffer(0.3))
        b = _star(rng, (2.3 + 0.5 * rng.random(), 0.2 * rng.standard_normal()), 0.9, 35)
        if not a.intersects(b):
            still.append(a)
            turning.append(b)
            pivots.append((2.6 + 0.3 * rng.standard_normal(), 0.3 * rng.standard_normal()))
    limit = math.pi / 2
    up, down = free_turns(np.array(still), np.array(turning), np.array(pivots), limit)
    assert np.any(up < limit) and np.any(down < limit)
    for a, b, pivot, *turns in zip(still, turning, pivots, up, down):
        for sense, turn in zip((1, -1), turns):

            def at(t):
                return affinity.rotate(b, sense * t, origin=pivot, use_radians=True)

            assert not any(at(t).intersects(a) for t in np.linspace(0, turn * (1 - 1e-6), 50))
            assert turn >= limit or at(turn + 1e-7).intersects(a)


def test_parts_that_touch_or_overlap_as_placed_turn_free_neither_way():
    """A tip 1 nm into a plate (an overlap of 1e-13 mm², under what a band counts as touching),
    or resting on it: no vertex meets an edge the way it goes deeper, so the sweep alone gave the
    far side's exit (1.03 rad) where 1e-4 rad already bites (a review's finding): 0 both ways."""
    plate = shapely.box(-5, -5, 5, 0)
    for tip_y, pivot in ((-1e-6, (3.0, 3.0)), (0.0, (-3.0, 3.0))):
        tip = shapely.Polygon([(-0.5, 3), (0, tip_y), (0.5, 3)])
        up, down = free_turns(np.array([plate]), np.array([tip]), np.array([pivot]), math.pi / 2)
        assert up[0] == 0.0 and down[0] == 0.0


def test_repeated_vertices_and_nested_collections():
    """A ring with each vertex written three times (edges of length 0, which once made the bands
    of radius a nanometre wide: 15 GiB), and a polygon inside a collection inside a collection:
    the same turn as the plain polygon."""
    ring = [(2 + math.cos(t), math.sin(t)) for t in np.linspace(0, 2 * math.pi, 12, endpoint=False)]
    wall = shapely.box(-10.0, 2.0, 10.0, 5.0)
    plain = shapely.Polygon(ring)
    tripled = shapely.Polygon([p for p in ring for _ in range(3)])
    nested = shapely.GeometryCollection([shapely.MultiPolygon([wall, shapely.box(20, 20, 21, 21)])])
    up, down = free_turns(np.array([wall, wall, nested]), np.array([plain, tripled, plain]), np.zeros((3, 2)), 3.0)
    # the vertex (2.5, √3/2) turned by 30°: y = 2.5·sin 30° + (√3/2)·cos 30° = 2, the wall (the
    # others reach it later); clockwise the ring turns away from it, to the limit
    assert up == pytest.approx([math.pi / 6] * 3, abs=1e-12)
    assert list(down) == [3.0] * 3
