"""Kerf with any bore: the beam rounds a hole's sharp corners with its radius (passes), fills a
space narrower than itself (refused, saying what and where); the cut paths as written stay
simple and within the tolerance of the exact offset.  (scripts/kerf_matrix.py runs every example
profile with both bores at four kerfs.)"""

import math
import re

import numpy as np
import pytest
import shapely

from gearcad.errors import DesignError
from gearcad.fitting import design
from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.kerf import kerf_fault, kerf_path
from gearcad.geometry.outline import Outline
from gearcad.geometry.rings import bore_ring, circle_ring
from gearcad.geometry.verify import is_simple, max_distance
from gearcad.profiles import load_profile

from .conftest import QUICK, ROOT, drawn

FINE = 0.00025


def _disc(hole: np.ndarray | None, outer: np.ndarray | None = None) -> Outline:
    outer = circle_ring(20.0, FINE) if outer is None else outer
    return Outline((outer,) if hole is None else (outer, hole))


@pytest.mark.parametrize("kerf", [0.1, 0.3])
def test_keyway_corners_are_rounded_by_the_beam_radius(kerf):
    """Closed form: a 90° corner cut by a beam of radius r keeps r·(√2 − 1) of material at its
    apex (the beam's circle touches both sides); the check passes it."""
    fine = _disc(bore_ring(8.0, FINE, keyway_width=2.0, keyway_depth=1.0))
    path = kerf_path(fine, kerf / 2, FINE)
    assert not kerf_fault(fine, path, kerf / 2, FINE)
    made = shapely.Polygon(path.rings[0], path.rings[1:]).buffer(-kerf / 2, quad_segs=256)
    for corner in [(5.0, 1.0), (5.0, -1.0)]:
        left = shapely.distance(shapely.Point(corner), made.interiors[0])
        assert left == pytest.approx(kerf / 2 * (math.sqrt(2) - 1), rel=1e-3)


def test_d_flat_corner_and_round_rest_of_the_bore():
    """The D-flat's corners (146° inside the hole for Ø6, flat 2.5) leave r(1/sin 73.2° − 1)."""
    kerf = 0.2
    fine = _disc(bore_ring(6.0, FINE, flat=2.5))
    path = kerf_path(fine, kerf / 2, FINE)
    assert not kerf_fault(fine, path, kerf / 2, FINE)
    made = shapely.Polygon(path.rings[0], path.rings[1:]).buffer(-kerf / 2, quad_segs=256)
    half = (math.pi - math.acos(2.5 / 3)) / 2
    left = shapely.distance(shapely.Point(2.5, math.sqrt(9 - 2.5**2)), made.interiors[0])
    assert left == pytest.approx(kerf / 2 * (1 / math.sin(half) - 1), rel=2e-2, abs=2 * FINE)


def test_a_space_narrower_than_the_kerf_is_refused_saying_where():
    """A notch 0.1 mm wide and 2 mm deep at 90°: a 0.3 mm beam cannot enter it."""
    disc = shapely.Polygon(circle_ring(20.0, FINE))
    notch = shapely.box(-0.05, 18.0, 0.05, 21.0)
    outer = np.asarray(shapely.geometry.polygon.orient(disc.difference(notch), 1.0).exterior.coords)[:-1]
    fine = _disc(None, outer)
    (fault,) = kerf_fault(fine, kerf_path(fine, 0.15, FINE), 0.15, FINE)
    assert fault.what == "tooth space"
    assert fault.angle_deg == pytest.approx(90.0, abs=0.5) and 17.9 < fault.radius < 18.2
    assert "fills a tooth space at 89.8° and 18.00 mm" in fault.describe("gear")
    assert not kerf_fault(fine, kerf_path(fine, 0.04, FINE), 0.04, FINE)  # a thinner beam enters


def test_a_hole_the_beam_closes_is_refused():
    slot = np.array([[3.0, 0.05], [3.0, -0.05], [-3.0, -0.05], [-3.0, 0.05]])[::-1]
    fine = _disc(slot)
    assert [f.what for f in kerf_fault(fine, kerf_path(fine, 0.15, FINE), 0.15, FINE)] == ["hole"]


@pytest.mark.parametrize(
    "profile,bore,kerf",
    [
        ("spur_pair", {"bore.diameter": 8.0, "bore.keyway_width": 2.0, "bore.keyway_depth": 1.0}, 0.15),
        ("walker", {"bore.diameter": 6.0, "bore.flat": 2.5}, 0.2),
    ],
    ids=["spur-keyway-0.15", "walker-dflat-0.2"],
)
def test_example_with_a_shaped_bore_builds_and_its_cut_paths_hold(profile, bore, kerf):
    """At the default tolerance, every part (the walker's shoe included): each written ring
    simple and within the tolerance of the part offset by half the kerf (shapely's buffer, 64
    segments a quarter).  The parts as drawn (:func:`~.conftest.drawn`): the fit's band, proven
    elsewhere, was 5 of the walker's 6 CPU-s here."""
    params = load_profile(ROOT / "profiles" / f"{profile}.toml", {**QUICK, **bore, "output.kerf": kerf})
    d = drawn(params)
    tol = params.output.tolerance
    for part in d.parts():
        exact = shapely.Polygon(part.fine.rings[0], part.fine.rings[1:]).buffer(kerf / 2, quad_segs=64)
        rings = [np.asarray(r.coords)[:-1] for r in (exact.exterior, *exact.interiors)]
        for ring in part.cut:
            points = arc_points(ring, tol / 20)
            assert is_simple(points), part.name
            assert min(max_distance(points, r) for r in rings) <= tol, part.name
    assert len(d.part(d.parts()[0].name).cut) == 2  # outline and the shaped bore


def test_kerf_that_fills_the_teeth_names_part_and_place():
    """At 1.9 mm the beam fills the tooth spaces of module 1 (2.25 mm deep, 0.7 mm wide at the
    root) and the 1 mm pilot hole."""
    over = {**QUICK, "output.kerf": 1.9, "teeth.module": 1.0, "output.tolerance": 0.01}
    with pytest.raises(DesignError) as exc:
        design(load_profile(ROOT / "profiles" / "spur_pair.toml", over))
    message = str(exc.value)
    assert re.search(r"pinion: the beam fills a tooth space at [0-9.]+° and [0-9.]+ mm from the pivot", message)
    assert re.search(r"pinion: the beam fills a hole at [0-9.]+° and 0.50 mm", message)
    assert re.search(r"largest kerf every part takes is 0\.[0-9]+ mm", message)
