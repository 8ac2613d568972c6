"""Seed 002 (wheel-walker): the shoe of eqs. 1–6 as a part, verified by placing and rolling the
leg, and the vehicle speed with round gears against the paper's pair and the pair that rolls.

Oracles: the envelope of the normal lines (intersection of neighbours, no use of the profile
formula), the curvature of the sampled profile by finite differences, a rolling simulation
(ground contact advanced by the arc length rolled, measured on the polyline) for eq. 6, and the
closed forms for the speeds.
"""

import math

import numpy as np
import pytest
import shapely

from gearcad.bodies import shoe as S
from gearcad.pitch import walker as W

G = W.WalkerGeometry(L=75.0, a=100.0, b=50.0, c=322.0)
K = G.a - G.b + G.c
TOL = 0.00025


def test_profile_is_the_envelope_of_the_normal_lines():
    """Each contact lies on the line normal to Y2 at distance p = Y1·cos φ + Y2 from B1 (the
    projection of B1→K1 on Y2); the envelope of those lines — neighbours intersected — is the
    shoe, so Y2 is the surface normal (the paper's condition on eqs. 1–2)."""
    phi = np.linspace(-S.STANCE, S.STANCE, 41)
    d = 1e-6
    prof = S.shoe_profile(G, phi)
    for k, p in enumerate(phi):
        lines = []
        for q in (p - d, p + d):
            y1, y2 = 4 * G.b * math.cos(q) - G.a, G.a - 2 * G.b * (1 + math.cos(q) ** 2) + G.c
            n = np.array([-math.sin(q), -math.cos(q)])  # Y2's direction in the leg frame
            lines.append((n, y1 * math.cos(q) + y2))
        (n1, p1), (n2, p2) = lines
        point = np.linalg.solve(np.array([n1, n2]), np.array([p1, p2]))
        assert point == pytest.approx([prof.x[k], prof.y[k]], abs=1e-5)
    assert prof.rho[20] == pytest.approx(G.c) and prof.alpha[20] == pytest.approx(0.0)


def test_curvature_radius_by_finite_differences():
    phi = np.linspace(-S.STANCE, S.STANCE, 2001)
    prof = S.shoe_profile(G, phi)
    dx, dy = np.gradient(prof.x, phi), np.gradient(prof.y, phi)
    ddx, ddy = np.gradient(dx, phi), np.gradient(dy, phi)
    radius = (dx * dx + dy * dy) ** 1.5 / np.abs(dx * ddy - dy * ddx)
    np.testing.assert_allclose(radius[5:-5], prof.curvature_radius[5:-5], rtol=1e-5)
    np.testing.assert_allclose(prof.curvature_radius, K - 3 * G.b * np.cos(2 * phi))


def test_leg_placed_at_every_hub_angle():
    check = S.stance_check(G, np.linspace(-S.STANCE, S.STANCE, 181))
    assert check["holds"], check
    assert check["hub_height"] == K == 372.0  # eq. 5


def test_rolling_the_leg_gives_eq_6():
    """Roll the shoe: the ground contact moves back by the arc length rolled (polyline length of
    the sampled sole), the hub sits at the placed offset from it; dX/dφ = K + 3b·cos 2φ."""
    phi = np.linspace(-S.STANCE, S.STANCE, 4001)
    prof = S.shoe_profile(G, phi)
    steps = np.hypot(np.diff(prof.x), np.diff(prof.y))
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    arc -= arc[len(arc) // 2]  # from the contact at φ = 0
    ground = -arc  # turning counter-clockwise it rolls towards −x
    pin = S.crank_pin(G, phi)
    placed_x = np.cos(phi) * prof.x - np.sin(phi) * prof.y + pin[:, 0]  # contact relative to the hub
    hub = ground - placed_x
    speed = -np.gradient(hub, phi)
    np.testing.assert_allclose(speed[2:-2], (K + 3 * G.b * np.cos(2 * phi))[2:-2], rtol=2e-6)


def test_shoe_ring_is_a_part_outline():
    ring = S.shoe_ring(G, tolerance=TOL, post_width=20.0)
    lr = shapely.LinearRing(ring)
    assert lr.is_simple and lr.is_ccw and shapely.Polygon(ring).is_valid
    assert ring[:, 1].min() == pytest.approx(-G.c, abs=TOL)  # the sole's bottom, c below B1
    exact = S.shoe_profile(G, np.linspace(-S.STANCE, S.STANCE, 20001))
    distances = shapely.distance(lr, shapely.points(exact.x, exact.y))
    assert distances.max() <= TOL * 1.0001
    placed = S.ring_stance_check(G, ring)
    assert placed["hub_height_mm"] <= TOL * 1.0001
    assert placed["contact_across_mm"] <= placed["chord_mm"]
    with pytest.raises(ValueError, match="post_width"):
        S.shoe_ring(G, tolerance=TOL, post_width=500.0)


def test_speed_with_round_gears_the_papers_pair_and_the_rolling_pair():
    i_paper = 3.207678
    law = W.ratio_law(G)
    out = S.speed_comparison(G, i_paper=i_paper, law=law)
    phi = np.radians(out["phi_deg"])
    round_v = (K + 3 * G.b * np.cos(2 * phi)) / 4
    np.testing.assert_allclose(out["round"]["v"], round_v)
    assert (out["round"]["min"], out["round"]["max"]) == pytest.approx((K / 4, (K + 3 * G.b) / 4))
    # contact on the line of centres forces θ = 4φ: the paper's pair moves like round gears
    assert out["paper_as_built"]["v"] == out["round"]["v"]
    # as intended its speed is constant, but the pinion turns i(π/2 + 3b/K) per quarter
    assert out["paper_as_intended"]["variation"] < 1e-12
    assert out["paper_as_intended"]["pinion_turn_per_quarter_deg"] == pytest.approx(
        math.degrees(i_paper * (math.pi / 2 + 3 * G.b / K)), rel=1e-9
    )
    # the rolling pair: constant K/i, i = 2π/(π/2 + 3b/K), four pinion turns per wheel turn
    i_true = 2 * math.pi / (math.pi / 2 + 3 * G.b / K)
    np.testing.assert_allclose(out["rolling"]["v"], K / i_true, rtol=1e-12)
    assert out["rolling"]["pinion_turn_per_quarter_deg"] == pytest.approx(360.0, abs=1e-6)
    mean = (K * math.pi / 2 + 3 * G.b) / (2 * math.pi)  # distance / time over a quarter
    for name in ("round", "rolling"):
        assert out[name]["mean"] == pytest.approx(mean, rel=1e-9)
    assert out["round"]["variation"] == pytest.approx(3 * G.b / 4 / mean, rel=1e-9)  # 32.1 %
    blended = S.speed_comparison(G, i_paper=i_paper, law=W.ratio_law(G, blend_width=math.radians(12)))
    assert 0.03 < blended["rolling"]["variation"] < 0.032  # the README's 3.08 % for a 12° blend


def test_walker_charts(built):
    """The paper's pitch curves against the pair that rolls, and the three charts the walker's
    build draws of them (speed, pitch curves, the shoe standing), read back from the session's
    build of profiles/walker.toml (this geometry: L, a, b, c as in :data:`G`)."""
    from gearcad.pitch import walker_polar
    from gearcad.pitch.pair import conjugate_pair

    i_paper = 3.207678
    paper = walker_polar.paper_polar(G, i_paper)
    # the paper's wheel is four copies of its quarter law: largest radius at 0°, 90°, …
    r = np.array(paper["wheel_r"])
    assert r[0] == pytest.approx(61.37, abs=0.005) and r[180] == pytest.approx(61.37, abs=0.005)
    assert r[90] == pytest.approx(57.18, abs=0.005)  # Table 1 at φ = ±45°
    pair = conjugate_pair(
        W.wheel_curve(W.ratio_law(G, blend_width=math.radians(12))), mate_lobes=1, center_distance=G.L
    )
    rolling = walker_polar.pair_polar(pair)
    # at the start the wheel's largest radius meets the pinion's smallest: they sum to L
    assert rolling["wheel_r"][0] + rolling["pinion_r"][360] == pytest.approx(G.L, abs=1e-9)
    for name in ("vehicle_speed.png", "paper_pitch_curves.png", "shoe.png"):
        data = (built / "walker" / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20000, name
