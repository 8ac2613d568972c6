"""Seed 001, second scheme: gear 2 as a compound ring (external teeth to gear 1, internal teeth to
gear 3, each with its own pitch radius).  The method of stopping against a velocity analysis in
the fixed frame (contact points, carried centres), accelerations against central differences of
that analysis in time, and the seed's formula as the equal-radii case."""

import math

import numpy as np
import pytest

from gearcad.trains import carrier as CT
from gearcad.trains import compound as CP

RINGS = [
    CP.CompoundRing(r1=20.0, r2_outer=36.0, r2_inner=28.0, r3=12.0),
    CP.CompoundRing(r1=15.0, r2_outer=30.0, r2_inner=24.0, r3=18.0, inner_angle=1.1),
    CP.CompoundRing(r1=40.0, r2_outer=25.0, r2_inner=18.0, r3=6.0, inner_angle=-2.5),
]


@pytest.mark.parametrize("ring", RINGS)
@pytest.mark.parametrize("carrier_angle", [0.0, 0.3, 2.0])
def test_method_of_stopping_against_fixed_frame_velocities(ring, carrier_angle):
    for omega1, carrier in ((2.0, 1.5), (-3.0, 0.4), (0.0, -1.0)):
        stopped = CP.solve_chain(ring.meshes, omega1=omega1, epsilon1=0.0, carrier=carrier, carrier_eps=0.0)
        fixed = CP.chain_by_velocities(ring.meshes, omega1=omega1, carrier=carrier, carrier_angle=carrier_angle)
        np.testing.assert_allclose(stopped.omega, fixed, rtol=1e-12, atol=1e-12)
        assert stopped.omega[2] == pytest.approx(ring.omega3_closed_form(omega1=omega1, carrier=carrier))


def test_accelerations_by_central_differences_in_time():
    """ω1(t) = ω1 + ε1·t, ω(t) = ω + ε·t, the carrier turning clockwise by ωt + εt²/2: the
    fixed-frame ω3 at t ± h, differenced, is ε3."""
    ring = RINGS[1]
    w1, e1, w, e, h = 2.0, 0.7, 1.5, -0.3, 1e-5
    angle0 = 0.4

    def omega_at(t):
        angle = angle0 - (w * t + e * t * t / 2)
        return CP.chain_by_velocities(ring.meshes, omega1=w1 + e1 * t, carrier=w + e * t, carrier_angle=angle)

    numeric = (omega_at(h) - omega_at(-h)) / (2 * h)
    stopped = CP.solve_chain(ring.meshes, omega1=w1, epsilon1=e1, carrier=w, carrier_eps=e)
    np.testing.assert_allclose(stopped.epsilon, numeric, rtol=1e-7)


def test_equal_radii_give_the_seeds_formula():
    for r2 in (25.0, 40.0, 90.0):
        ring = CP.CompoundRing(r1=20.0, r2_outer=r2, r2_inner=r2, r3=10.0)
        got = CP.solve_chain(ring.meshes, omega1=2.0, epsilon1=0.0, carrier=1.5, carrier_eps=0.0).omega[2]
        assert got == pytest.approx(CP.seed_internal_formula(20.0, 10.0, omega1=2.0, carrier=1.5), rel=1e-14)
        assert got == pytest.approx(CT.three_gear_internal(20.0, 10.0, omega1=2.0, carrier=1.5), rel=1e-14)
        simple = CT.solve_train(
            [20.0, r2, 10.0], ["external", "internal"], omega1=2.0, epsilon1=0, carrier=1.5, carrier_eps=0
        )
        assert got == pytest.approx(simple.omega[2], rel=1e-14)


def test_unequal_radii_scale_the_relative_speed_by_r2_inner_over_r2_outer():
    equal = CP.CompoundRing(20.0, 36.0, 36.0, 12.0)
    ring = CP.CompoundRing(20.0, 36.0, 28.0, 12.0)
    w, w1 = 1.5, 2.0
    rel_equal = CP.solve_chain(equal.meshes, omega1=w1, epsilon1=0, carrier=w, carrier_eps=0).relative[2]
    rel = CP.solve_chain(ring.meshes, omega1=w1, epsilon1=0, carrier=w, carrier_eps=0).relative[2]
    assert rel / rel_equal == pytest.approx(28.0 / 36.0)
    # the seed's formula (one r2) is then wrong for the real part
    assert (
        abs(ring.omega3_closed_form(omega1=w1, carrier=w) - CP.seed_internal_formula(20, 12, omega1=w1, carrier=w))
        > 0.1
    )


def test_locked_train_turns_with_the_carrier():
    """Gear 1 turning with the carrier (ω1 = −ω: Ω1 = 0) locks the train: every gear turns at −ω."""
    for ring in RINGS:
        data = CP.solve_chain(ring.meshes, omega1=-1.25, epsilon1=0, carrier=1.25, carrier_eps=0)
        np.testing.assert_allclose(data.omega, -1.25)
        np.testing.assert_allclose(CP.chain_by_velocities(ring.meshes, omega1=-1.25, carrier=1.25), -1.25, atol=1e-14)


def test_geometry_and_validation():
    ring = RINGS[1]
    centres = CP.chain_centres(ring.meshes, carrier_angle=0.0)
    assert np.hypot(*centres[1]) == pytest.approx(ring.r1 + ring.r2_outer)
    assert np.hypot(*(centres[2] - centres[1])) == pytest.approx(ring.r2_inner - ring.r3)
    assert math.atan2(*(centres[2] - centres[1])[::-1]) == pytest.approx(1.1)
    assert ring.wall(1.0, 1.0) == pytest.approx(30.0 - 1.25 - (24.0 + 1.25))
    with pytest.raises(ValueError, match="internal mesh"):
        CP.Mesh("internal", 10.0, 12.0)
    with pytest.raises(ValueError, match="kind"):
        CP.Mesh("bevel", 10.0, 12.0)
