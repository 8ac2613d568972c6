"""The carrier-less noncircular planetary's kinematics (gearcad.trains.nc_planetary): the makers'
table (issue 38) reproduced by two computations that share only the curve, the circular set by the
method of stopping, and the exact closure of the two example sets."""

import math

import numpy as np
import pytest

from gearcad.errors import DesignError
from gearcad.mechanisms import nc_planetary
from gearcad.trains.carrier import solve_train
from gearcad.trains.nc_planetary import (
    Lobed,
    by_arc_length,
    by_sun_angle,
    close_ring,
    convex_limit,
    matched_sun,
    poses,
)
from gearcad.trains.nc_set import phasing, planet_gap, planetary_set

# The published table: (n, e, natural ring lobe count, orbit-radius change in %).
PUBLISHED = [
    (4, 0.03, 12.007, 0.1),
    (4, 0.06, 12.021, 0.35),
    (4, 0.09, 12.070, 0.75),
    (3, 0.03, 9.002, 0.1),
    (3, 0.06, 9.015, 0.35),
    (3, 0.09, 9.039, 0.75),
]


@pytest.mark.parametrize(("n", "e", "n_r", "change"), PUBLISHED)
def test_the_makers_table_two_ways(n, e, n_r, change):
    """n_r within ±0.005 of the published figure, the orbit-radius change rounding to it (the
    table's changes are multiples of 0.05 %), the two computations agreeing to 1e-6."""
    curve = Lobed(1.0, n, e)
    kennedy = by_sun_angle(curve, steps=200)
    rolled = by_arc_length(curve)
    assert kennedy.natural_lobes == pytest.approx(rolled.natural_lobes, abs=1e-6)
    assert kennedy.orbit_change == pytest.approx(rolled.orbit_change, abs=1e-6)
    assert abs(rolled.natural_lobes - n_r) <= 0.005
    assert round(rolled.orbit_change * 100 / 0.05) * 0.05 == pytest.approx(change)


def test_the_orbit_change_is_e_squared_to_leading_order():
    """Perturbation of the rolling: ψ ≈ θ + π/n + (2e/n)·sin nθ makes |C| ≈ 2R(1 + e²·sin² nθ/…),
    a change of e² (to O(e³)) whatever n — an independent closed form for small e."""
    for n in (3, 4, 5):
        change = by_arc_length(Lobed(1.0, n, 0.005)).orbit_change
        assert change == pytest.approx(0.005**2, rel=0.05)


@pytest.mark.parametrize("n", [3, 4])
def test_circles_are_the_circular_planetary_by_the_method_of_stopping(n):
    """e = 0: sun, planet radius R, ring 3R; the sun held and the carrier turning at 1 rad/s
    counter-clockwise (the seed's −1), the ring turns at 1 + 1/3 (carrier.solve_train)."""
    train = solve_train(
        (1.0, 1.0, 3.0), ("external", "internal"), omega1=0.0, epsilon1=0.0, carrier=-1.0, carrier_eps=0.0
    )
    lobe = 2 * math.pi / n
    for data in (by_arc_length(Lobed(1.0, n, 0.0)), by_sun_angle(Lobed(1.0, n, 0.0), steps=20)):
        assert data.ring_turn / lobe == pytest.approx(train.omega[2], abs=1e-12)
        assert data.natural_lobes == pytest.approx(3 * n, abs=1e-12)
        assert data.orbit_min == pytest.approx(2.0, abs=1e-12)
        assert data.orbit_max == pytest.approx(2.0, abs=1e-12)


def test_poses_roll_without_slip_and_touch_tangentially():
    """The pose itself: the planet's point ψ lands on the sun's point θ with opposite tangents,
    and the arc rolled on each is the same (checked by trapezoid sums, not the Fourier series)."""
    curve = Lobed(1.0, 4, 0.05)
    theta = np.linspace(0.0, 0.6, 7)
    pose = poses(curve, curve, theta)
    q = curve.point(pose.psi)
    cb, sb = np.cos(pose.beta), np.sin(pose.beta)
    landed = pose.centre + np.stack([cb * q[:, 0] - sb * q[:, 1], sb * q[:, 0] + cb * q[:, 1]], -1)
    assert np.max(np.abs(landed - curve.point(theta))) < 1e-12
    turn = curve.tangent_angle(pose.psi) + pose.beta - curve.tangent_angle(theta)
    assert np.max(np.abs(np.mod(turn - np.pi + np.pi, 2 * np.pi) - np.pi)) < 1e-12
    for t, psi in zip(theta[1:], pose.psi[1:]):
        x = np.linspace(0.0, t, 20001)
        y = np.linspace(psi, math.pi / 4, 20001)
        assert np.trapezoid(curve.speed(x), x) == pytest.approx(np.trapezoid(curve.speed(y), y), abs=1e-8)


def test_the_convexity_limit_is_where_the_valley_flattens():
    for n in (3, 4):
        limit = convex_limit(n)
        valley = math.pi / n
        assert Lobed(1.0, n, limit * (1 - 1e-9)).curvature(valley) > 0
        assert Lobed(1.0, n, limit * (1 + 1e-9)).curvature(valley) < 0


@pytest.mark.parametrize(("n", "e", "ring"), [(4, 0.05, 12), (3, 0.08, 9)])
def test_the_example_sets_close_exactly(n, e, ring):
    """The sun's e solved so the ring has exactly 3n lobes: closure ≤ 1e-9 rad by the solver's
    method and again by the Kennedy integration; the sun's lobe as long as the planet's."""
    planet = Lobed(1.0, n, e)
    sun, residual = close_ring(planet, ring)
    assert residual <= 1e-9
    check = by_sun_angle(sun, planet, steps=200)
    assert abs(ring * abs(check.sweep) - 2 * math.pi) <= 1e-6  # RK4 at 200 steps: ~1e-8
    assert 0 < sun.e < convex_limit(n)
    x = np.linspace(0.0, 2 * math.pi / n, 40001)
    assert np.trapezoid(sun.speed(x), x) == pytest.approx(np.trapezoid(planet.speed(x), x), rel=1e-10)


def test_a_ring_that_cannot_close_is_refused_naming_the_key():
    with pytest.raises(DesignError, match=r"^e = [0-9.]+: no sun eccentricity .* closes the ring at 15 lobes"):
        close_ring(Lobed(1.0, 4, 0.05), 15)


def test_a_matched_sun_of_the_planets_own_e_is_the_planet():
    planet = Lobed(1.0, 3, 0.08)
    assert matched_sun(planet, 0.08).radius == pytest.approx(1.0, abs=1e-14)


@pytest.fixture(scope="module")
def square():
    planet = Lobed(1.0, 4, 0.05)
    sun, _ = close_ring(planet, 12)
    return planetary_set(sun, planet, 4, 12)


def test_the_ring_closes_lobe_after_lobe_and_turns_as_rolled(square):
    """γ advances by exactly −2π/12 per sun lobe (the ring closes after 12 of its lobes), the
    ring's radius repeats with its period, and φ_r at a lobe's end is the rolled sweep's."""
    lobe = square.lobe
    assert square.ring_angle(lobe) == pytest.approx(-2 * math.pi / 12, abs=1e-12)
    gamma = np.linspace(0.0, 2 * math.pi / 12, 7)
    assert np.max(np.abs(square.ring_radius_at(gamma) - square.ring_radius_at(gamma + 5 * 2 * math.pi / 12))) < 1e-12
    assert square.ring_turn(3 * lobe) == pytest.approx(3 * square.data.ring_turn, abs=1e-12)
    # the ring's rate by the Kennedy integration, at a lobe's end
    assert square.ring_turn(lobe) == pytest.approx(
        by_sun_angle(square.sun, square.planet, steps=100).ring_turn, abs=1e-6
    )


def test_the_ring_held_moves_every_planet_as_the_first(square):
    """Ring held: each planet's centre at the same distance from O, evenly spaced, and the sun
    turned back by φ_r; the planets' orbit (carrier) angle is γ."""
    state = square.ring_held(0.37)
    radii = np.hypot(state["centres"][:, 0], state["centres"][:, 1])
    assert np.ptp(radii) < 1e-12
    angles = np.unwrap(np.arctan2(state["centres"][:, 1], state["centres"][:, 0]))
    assert np.allclose(np.diff(angles), 2 * math.pi / 4, atol=1e-12)
    assert state["sun"] == pytest.approx(-float(square.ring_turn(0.37)), abs=1e-15)


def test_the_planets_gap_bounds_the_circles_gap():
    """e = 0: planets of radius 1 on an orbit of 2, N = 4: the gap is 4·sin(π/4) − 2 exactly; the
    certified bound lies at most the tolerance under it and never over."""
    circle = Lobed(1.0, 4, 0.0)
    bound, least, _ = planet_gap(planetary_set(circle, circle, 4, 12))
    exact = 4 * math.sin(math.pi / 4) - 2
    assert bound <= exact + 1e-9
    assert bound >= exact - 6e-3
    assert least == pytest.approx(exact, abs=1e-4)


def test_the_phasing_rule():
    assert phasing(4, 12, 4) is None
    assert phasing(3, 9, 3) is None
    assert "use 3 or 6 planets" in phasing(6, 18, 4)
    assert "at least 3" in phasing(4, 12, 2)


# ----------------------------------------------------------------------------- the mechanism


@pytest.fixture(scope="module")
def square_draft():
    from .conftest import drafted

    return drafted("nc_square", nc_planetary.design)[1]


def test_the_square_set_is_closed_proved_and_phased(square_draft):
    """The example square set: closed to round-off and again by the Kennedy integration, both
    meshes without overlap at every position of a sun lobe, biting when nudged, with a play of
    most of the 0.2 mm backlash; sun, planets, ring carry 16, 16, 48 teeth of one module."""
    data = square_draft.data
    assert data["set"]["closure_residual"] <= 1e-9
    assert data["set"]["closure_by_sun_angle"] <= 1e-9
    teeth = data["teeth"]
    assert (teeth["sun"], teeth["planet"], teeth["ring"]) == (16, 16, 48)
    # the module from the planets' perimeter, by a trapezoid sum (independent of the arc frames)
    x = np.linspace(0.0, 2 * math.pi, 200001)
    perimeter = np.trapezoid(Lobed(20.0, 4, 0.05).speed(x), x)
    assert teeth["module"] == pytest.approx(perimeter / (math.pi * 16), rel=1e-9)
    for mesh in data["meshes"]:
        assert mesh["max_overlap"] <= mesh["allowed_overlap"]
        assert mesh["max_depth"] <= 2 * 0.01
        assert mesh["nudged_min_overlap"] > mesh["allowed_overlap"]
        assert 0.1 < mesh["least_play"] <= 0.2 + 4 * 0.01
    assert not square_draft.findings


def test_the_planets_sit_on_their_orbit_evenly(square_draft):
    """Four planet placements, centres at the orbit radius of θ = 0 (the sun's lobe on a planet's
    valley: the least, by symmetry, 2R(1 + …) within the orbit's range), a quarter turn apart."""
    planets = [pl for pl in square_draft.placements if pl.part == "planet"]
    centres = np.array([pl.offset for pl in planets])
    radii = np.hypot(centres[:, 0], centres[:, 1])
    data = square_draft.data["set"]
    assert np.ptp(radii) < 1e-9
    assert data["orbit_min"] - 1e-9 <= radii[0] <= data["orbit_max"] + 1e-9
    angles = np.unwrap(np.arctan2(centres[:, 1], centres[:, 0]))
    assert np.allclose(np.diff(angles), math.pi / 2, atol=1e-12)
    assert np.allclose(np.diff([pl.angle for pl in planets]), math.pi / 2, atol=1e-12)


def test_bad_sets_are_refused_in_one_line():
    from gearcad.errors import ProfileError
    from gearcad.profiles import validated
    from gearcad.profiles.nc_planetary import NcPlanetaryParams

    def params(**s):
        base = {"lobes": 4, "e": 0.05, "radius": 20.0, "planets": 4}
        return validated(NcPlanetaryParams, set={**base, **s}, teeth={"count": 24})

    with pytest.raises(ProfileError, match=r"^set.e = 0.06: must be below 1/\(n² \+ 1\) = 0.05882"):
        params(e=0.06)
    with pytest.raises(ProfileError, match=r"^set.planets = 3: must divide gcd\(set.lobes, ring lobes\)"):
        params(planets=3)
    with pytest.raises(ProfileError, match=r"^teeth.count = 26: must be a multiple of set.lobes = 4"):
        validated(NcPlanetaryParams, set={"lobes": 4, "e": 0.05, "radius": 20.0, "planets": 4}, teeth={"count": 26})
