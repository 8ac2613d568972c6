"""The geometry intermediate (gearcad.geometry.outline) and the bulge arithmetic
(gearcad.geometry.bulge): frozen outlines, one placement, one converter, arcs by closed forms."""

import math

import numpy as np
import pytest

from gearcad.geometry import bulge as B
from gearcad.geometry.arcfit import ArcRing
from gearcad.geometry.outline import Outline, place, place_each

SQUARE = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
HOLE = np.array([[0.5, 0.5], [0.5, 1.5], [1.5, 1.5], [1.5, 0.5]])


def test_an_outline_is_frozen_and_owns_its_rings():
    given = SQUARE.copy()
    outline = Outline((given, HOLE))
    with pytest.raises(ValueError, match="read-only"):
        outline.outer[0, 0] = 9.0
    given[0, 0] = 9.0  # the caller's array stays the caller's: the outline does not change
    assert outline.outer[0, 0] == 0.0 and outline.outer.dtype == np.float64
    assert outline.area == pytest.approx(4.0 - 1.0, abs=1e-15)
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        Outline((np.zeros(6),))


def test_place_turns_about_the_pivot_then_moves():
    # a quarter turn takes (1, 0) to (0, 1), then the offset moves it
    np.testing.assert_allclose(place(np.array([[1.0, 0.0]]), math.pi / 2, (3.0, 4.0)), [[3.0, 5.0]], atol=1e-15)
    np.testing.assert_array_equal(place(SQUARE), SQUARE)


def test_many_placements_at_once_turn_each_point_by_its_owners_angle():
    # points on circles (radius r, polar angle a), each owned by one of three placements: turned
    # by θ and moved by (ox, oy), a point lands at (ox + r·cos(a + θ), oy + r·sin(a + θ))
    r, a = np.array([1.0, 2.0, 0.5, 3.0, 1.5]), np.array([0.0, 1.0, 2.0, -1.0, 3.0])
    owner = np.array([0, 0, 2, 1, 2])
    theta, offset = np.array([0.3, -2.0, math.pi]), np.array([[1.0, 0.0], [0.0, -5.0], [10.0, 10.0]])
    points = np.column_stack([r * np.cos(a), r * np.sin(a)])
    expected = offset[owner] + np.column_stack([r * np.cos(a + theta[owner]), r * np.sin(a + theta[owner])])
    np.testing.assert_allclose(place_each(points, owner, theta, offset), expected, atol=1e-14)


def test_the_polygon_is_the_outline_placed():
    polygon = Outline((SQUARE, HOLE)).polygon(math.pi, (10.0, 0.0))
    assert polygon.area == pytest.approx(3.0, abs=1e-12) and len(polygon.interiors) == 1
    # turned half a turn about the origin, then moved: the square spans x 8…10, y −2…0
    np.testing.assert_allclose(polygon.bounds, (8.0, -2.0, 10.0, 0.0), atol=1e-12)


def test_segments_read_arcs_and_plain_rings_alike():
    v, b = B.segments(ArcRing(SQUARE, np.array([0.0, 1.0, 0.0, 0.0])))
    assert b.tolist() == [0.0, 1.0, 0.0, 0.0] and v.shape == (4, 2)
    assert B.segments(SQUARE)[1].tolist() == [0.0] * 4


@pytest.mark.parametrize("turn", [math.pi / 2, math.pi, -math.pi / 3, 1.9 * math.pi])
def test_an_arc_of_known_sweep_has_its_radius_and_centre(turn):
    """An arc of sweep θ on the unit circle from angle 0: bulge tan(θ/4), centre the origin."""
    a, b = np.array([[1.0, 0.0]]), np.array([[math.cos(turn), math.sin(turn)]])
    sweep = B.sweep(np.array([math.tan(turn / 4)]))
    assert sweep[0] == pytest.approx(turn, rel=1e-14)
    centre, radius = B.centres(a, b, sweep)
    np.testing.assert_allclose(radius, [1.0], rtol=1e-12)
    np.testing.assert_allclose(centre, [[0.0, 0.0]], atol=1e-12)
