"""Seed 002 (Skoybeda, Komyak, Zhukovets): the wheel-walker drive pair."""

import math

import numpy as np
import pytest

from gearcad.pitch import walker as W
from gearcad.pitch.curve import TWO_PI, convexity, corners, perimeter
from gearcad.pitch.kinematics import kinematics
from gearcad.pitch.pair import angle_map, conjugate_pair

G = W.WalkerGeometry(L=75.0, a=100.0, b=50.0, c=322.0)
K = G.a - G.b + G.c


def test_paper_method_reproduces_published_i(seed_tables):
    data = seed_tables["wheel_walker_002"]
    i, iterations = W.paper_ratio_constant(G)
    assert round(i, 6) == data["i_published"]
    assert iterations < 20


def test_paper_table1(seed_tables):
    """Eqs. 10 and 12 with the published i, at the printed two decimals."""
    data = seed_tables["wheel_walker_002"]
    i = data["i_published"]
    for phi_deg, r_h, theta_deg, r in data["table1"]["rows"]:
        assert theta_deg == 4 * phi_deg
        assert round(float(W.paper_wheel_radius(math.radians(phi_deg), i, G)), 2) == r_h
        assert round(float(W.paper_pinion_radius(math.radians(theta_deg), i, G)), 2) == r
        assert r + r_h == pytest.approx(G.L, abs=0.011)


def test_shoe_functions_give_the_papers_closed_forms():
    """Eqs. 5 and 6 follow from eqs. 1–4: Y01 = a − b + c, dX01/dφ = K + 3b·cos 2φ."""
    phi = np.linspace(-math.pi, math.pi, 101)
    f = W.shoe_functions(phi, G)
    np.testing.assert_allclose(f["Y01"], K, rtol=1e-13)
    np.testing.assert_allclose(f["dX01"], K + 3 * G.b * np.cos(2 * phi), rtol=1e-13)


def test_rolling_pair_i_from_closure_closed_form():
    """Rolling needs ∫ r_H/r dφ = 2π per quarter: i(π/2 + 3b/K) = 2π."""
    law = W.ratio_law(G)
    assert law.i == pytest.approx(TWO_PI / (math.pi / 2 + 3 * G.b / K), rel=1e-14)
    assert law.i == pytest.approx(3.182936, abs=5e-7)
    pair = conjugate_pair(W.wheel_curve(law), mate_lobes=1, center_distance=G.L)
    assert pair.closure_error < 1e-9 and pair.rolling_residual < 1e-9
    # arc lengths: one wheel turn rolls four pinion perimeters
    assert perimeter(pair.gear1) == pytest.approx(4 * perimeter(pair.gear2), rel=1e-12)


def test_paper_pinion_does_not_roll():
    """With the paper's i the pinion would turn i(π/2 + 3b/K) per quarter, not 2π, and
    with θ = 4φ it slides by r_H − 4r = 5r_H − 4L per rad of wheel."""
    i_paper = W.paper_ratio_constant(G)[0]
    paper_wheel = W.wheel_curve(W.RatioLaw(G, i_paper, 0.0, (0.0, 0.0, 0.0)))
    turn = angle_map(paper_wheel, G.L).turn / 4
    assert turn == pytest.approx(i_paper * (math.pi / 2 + 3 * G.b / K), rel=1e-12)
    assert math.degrees(turn) - 360 == pytest.approx(2.798, abs=1e-3)
    pinion = W.paper_pinion(i_paper, G)
    phi = np.linspace(0, TWO_PI, 2001)
    np.testing.assert_allclose(paper_wheel.r(phi) + pinion.r(np.pi - 4 * phi), G.L, atol=1e-12)
    slip = np.max(np.abs(paper_wheel.r(phi) - 4 * pinion.r(np.pi - 4 * phi)))
    r_h_min = W.paper_wheel_radius(math.pi / 4, i_paper, G)
    assert slip == pytest.approx(4 * G.L - 5 * r_h_min, rel=1e-9)


def test_rolling_pair_moves_the_vehicle_at_constant_speed():
    """v = ω_H·dX01/dφ must equal ω·K/i for every pinion angle (the paper's aim)."""
    law = W.ratio_law(G)
    pair = conjugate_pair(W.wheel_curve(law), mate_lobes=1, center_distance=G.L)
    omega = 2.0
    kin = kinematics(pair, driver=2, speed=omega, angle=np.linspace(0, TWO_PI, 257))
    quarter = (kin.follower_angle + math.pi / 4) % (math.pi / 2) - math.pi / 4
    v = kin.speed * W.shoe_functions(quarter, G)["dX01"]
    np.testing.assert_allclose(v, omega * K / law.i, rtol=1e-10)


def test_seam_corners_detected_and_blend_removes_them():
    law = W.ratio_law(G)
    wheel = W.wheel_curve(law)
    pair = conjugate_pair(wheel, mate_lobes=1, center_distance=G.L)
    wheel_corners = corners(wheel)
    assert [round(math.degrees(c.phi)) for c in wheel_corners] == [45, 135, 225, 315]
    assert all(not c.convex for c in wheel_corners)  # notches: r_H is smallest at the seams
    pinion_corners = corners(pair.gear2)
    assert len(pinion_corners) == 1 and pinion_corners[0].convex
    # the tangent turn at a notch, from the one-sided slopes of eq. 10 (closed form)
    r = W.paper_wheel_radius(math.pi / 4, law.i, G)
    slope = abs(float(law.dk(np.array([math.pi / 4 - 1e-12]))[0])) * G.L / (1 + law.i) ** 2
    assert abs(wheel_corners[0].turn) == pytest.approx(2 * math.atan2(slope, r), rel=1e-6)
    assert not convexity(wheel).convex

    blended = W.ratio_law(G, blend_width=math.radians(6))
    smooth = conjugate_pair(W.wheel_curve(blended), mate_lobes=1, center_distance=G.L)
    assert corners(smooth.gear1) == [] and corners(smooth.gear2) == []
    assert smooth.closure_error < 1e-9 and smooth.rolling_residual < 1e-9
    phi = np.linspace(0, TWO_PI, 20001)
    deviation = np.max(np.abs(blended.k(phi) - law.k(phi)) / law.k(phi))
    assert 0 < deviation < 0.05


@pytest.mark.parametrize("width_deg", [1.0, 6.0, 20.0])
def test_blend_is_c2_and_its_closure_integral_is_exact(width_deg):
    law = W.ratio_law(G, blend_width=math.radians(width_deg))
    for edge in law.breaks:
        for order in range(3):
            # the quartic's third derivative is ~24·C·h, up to 1e5 for a 1° blend: probe close
            left, right = law.shape(np.array([edge - 1e-13, edge + 1e-13]), order)
            assert left == pytest.approx(right, abs=1e-6)
        # ... and the corner the blend replaces is a real jump of dG/dφ = ∓2 at the seam
    jump = W.ratio_law(G).shape(np.array([math.pi / 4 - 1e-9, math.pi / 4 + 1e-9]), 1)
    assert jump[0] == pytest.approx(-2, abs=1e-6) and jump[1] == pytest.approx(2, abs=1e-6)
    # the closed-form i closes the law: ∫ k over a turn = 8π, checked by dense trapezoid
    phi = np.linspace(0, TWO_PI, 400001)
    total = np.trapezoid(law.k(phi), phi)
    assert total == pytest.approx(4 * TWO_PI, rel=1e-9)
