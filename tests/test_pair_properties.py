"""Invariants of conjugate synthesis over random valid designs (hypothesis)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearcad.pitch import shapes
from gearcad.pitch.curve import TWO_PI, perimeter
from gearcad.pitch.kinematics import kinematics
from gearcad.pitch.pair import conjugate_pair

FAST = settings(max_examples=25, deadline=None)


@FAST
@given(
    a=st.floats(5, 100),
    ecc=st.floats(0.0, 0.9),
    pivot=st.sampled_from(["focus", "centre"]),
    mate_lobes=st.integers(1, 4),
)
def test_random_ellipses_close_and_roll(a, ecc, pivot, mate_lobes):
    b = a * math.sqrt(1 - ecc * ecc)
    curve = shapes.ellipse_focus(a, b) if pivot == "focus" else shapes.ellipse_centre(a, b)
    pair = conjugate_pair(curve, mate_lobes=mate_lobes)
    assert pair.closure_error < 1e-9
    assert pair.rolling_residual < 1e-9 * max(1.0, a)
    # pure rolling ⇒ equal arc lengths: the mate's perimeter is n2/n1 of the driver's
    assert perimeter(pair.gear2) == pytest.approx(perimeter(pair.gear1) * mate_lobes / curve.lobes, rel=1e-10)


@FAST
@given(radius=st.floats(1, 200), n1=st.integers(1, 5), n2=st.integers(1, 5))
def test_circles_give_the_textbook_centre_distance(radius, n1, n2):
    curve = shapes.circle(radius)
    curve = type(curve)(curve.name, curve.r, curve.dr, curve.d2r, lobes=n1)
    pair = conjugate_pair(curve, mate_lobes=n2)
    assert pair.center_distance == pytest.approx(radius * (1 + n2 / n1), rel=1e-12)
    np.testing.assert_allclose(pair.gear2.r(np.linspace(0, TWO_PI, 9)), radius * n2 / n1, rtol=1e-12)


@FAST
@given(
    lobes=st.integers(1, 3),
    mate_lobes=st.integers(1, 3),
    c1=st.floats(-0.3, 0.3),
    s1=st.floats(-0.3, 0.3),
    c2=st.floats(-0.1, 0.1),
    e=st.floats(10, 200),
)
def test_ratio_law_synthesis(lobes, mate_lobes, c1, s1, c2, e):
    mean = lobes / mate_lobes
    terms = [(lobes, c1 * mean, s1 * mean), (2 * lobes, c2 * mean, 0.0)]
    k, dk, d2k = shapes.harmonic_ratio(mean, terms)
    curve = shapes.from_ratio("law", k, dk, d2k, e, lobes=lobes)
    pair = conjugate_pair(curve, mate_lobes=mate_lobes, center_distance=e)
    assert pair.closure_error < 1e-9 and pair.rolling_residual < 1e-9 * e
    phi = np.linspace(0, TWO_PI, 37)
    # the law is what the pair transmits, and the mate is r2 = E/(1 + k)
    np.testing.assert_allclose(kinematics(pair, angle=phi).ratio, k(phi), rtol=1e-9)
    np.testing.assert_allclose(pair.gear2.r(np.pi - pair.angle_map(phi)), e / (1 + k(phi)), rtol=1e-11)


@FAST
@given(a=st.floats(5, 60), ecc=st.floats(0.05, 0.85), driver=st.sampled_from([1, 2]))
def test_acceleration_is_the_time_derivative_of_speed(a, ecc, driver):
    """ε from the chain rule against a central difference of ω in time (independent)."""
    curve = shapes.ellipse_focus(a, a * math.sqrt(1 - ecc * ecc))
    pair = conjugate_pair(curve, mate_lobes=1)
    omega, dt = 3.0, 1e-6
    psi = np.linspace(0.1, 6.1, 11)
    kin = kinematics(pair, driver=driver, speed=omega, angle=psi)
    ahead = kinematics(pair, driver=driver, speed=omega, angle=psi + omega * dt).speed
    behind = kinematics(pair, driver=driver, speed=omega, angle=psi - omega * dt).speed
    np.testing.assert_allclose(
        kin.acceleration, (ahead - behind) / (2 * dt), rtol=1e-5, atol=1e-6 * np.max(np.abs(kin.acceleration))
    )
