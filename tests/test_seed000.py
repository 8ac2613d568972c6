"""Seed 000 (wheel driven through an inclined rack): eq. 10 over the whole allowed range, and the
paper's second method (eqs. 12–13, velocity projections and the rack's instantaneous centre) as
an independent check of eqs. 8 and 11.

The oracles are built here: the rack's β by scanning H·cos β − L·sin β = R − r for all its roots
and keeping the common tangent that lies above both wheels (checked by distances), and the
rates by differentiating the closed-contour motion law numerically.
"""

import itertools
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcad.trains import rack_drive as RD


def _tangent_roots(d: RD.RackDrive) -> list[float]:
    """Every β in (−π, π] with H·cos β − L·sin β = R − r, by sign changes on a grid + Brent."""

    def f(b):
        return d.H * math.cos(b) - d.L * math.sin(b) - (d.R - d.r)

    grid = np.linspace(-math.pi, math.pi, 3601) + 0.0123  # offset: no root sits on a grid point here
    vals = [f(b) for b in grid]
    roots = [brentq(f, grid[i], grid[i + 1], xtol=1e-15) for i in range(len(grid) - 1) if vals[i] * vals[i + 1] < 0]
    return [math.remainder(b, 2 * math.pi) for b in roots]


def _the_rack(d: RD.RackDrive, roots) -> list[float]:
    """Eq. 1 needs l = L·cos β + H·sin β > 0 (a length from A to B): of the two common tangents
    with the wheels on the same side, this picks the one drawn."""
    return [b for b in roots if d.L * math.cos(b) + d.H * math.sin(b) > 0]


def _tangent(d: RD.RackDrive, beta: float) -> bool:
    """The line through A = R·n with direction u is at distance r from wheel 1's centre, and
    both centres lie on the same side of it (an external common tangent)."""
    u, n = np.array([math.cos(beta), math.sin(beta)]), np.array([-math.sin(beta), math.cos(beta)])
    A, C1 = d.R * n, np.array([d.L, d.H])
    side1, side2 = n @ (C1 - A), n @ (np.zeros(2) - A)
    return math.isclose(abs(u[0] * (C1 - A)[1] - u[1] * (C1 - A)[0]), d.r, abs_tol=1e-9) and side1 < 0 and side2 < 0


def _allowed(d: RD.RackDrive) -> bool:
    """The paper's range: the rack reaches both wheels and is not past vertical (cos β > 0; the
    closed-contour law stops there).  With H > 0 and R > r this reaches past the driver, to
    L > −(R − r); with R < r it ends at L = r − R > 0."""
    if abs(d.R - d.r) >= math.hypot(d.L, d.H):
        return False
    (beta,) = _the_rack(d, _tangent_roots(d))
    return math.cos(beta) > 0


GRID = [
    d
    for d in (
        RD.RackDrive(r, R, L, H)
        for r, R, L, H in itertools.product(
            (20.0, 60.0), (15.0, 20.0, 60.0), (-30.0, -10.0, 120.0, 300.0), (-40.0, 90.0, 150.0)
        )
    )
    if _allowed(d)
]


@pytest.mark.parametrize("d", GRID, ids=lambda d: f"r{d.r:g}-R{d.R:g}-L{d.L:g}-H{d.H:g}")
def test_eq10_printed_root_is_the_racks_only_where_L_times_R_minus_r_times_H_is_positive(d):
    roots = _tangent_roots(d)
    assert len(roots) == 2 and all(_tangent(d, b) for b in roots)
    (rack,) = _the_rack(d, roots)
    (other,) = [b for b in roots if b != rack]
    beta = float(RD.inclination(d))
    assert math.remainder(beta - rack, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    printed = float(RD.paper_inclination_at(d)[0])
    if d.R == d.r:
        assert math.isnan(printed)
    elif d.L * (d.R - d.r) * d.H > 0:
        assert printed == pytest.approx(beta, abs=1e-12)
    else:
        # the other root of the quadratic in sin β: the common tangent that eq. 1 gives l < 0
        assert abs(printed - beta) > 1e-3
        assert math.sin(printed) == pytest.approx(math.sin(other), abs=1e-12)
    assert bool(RD.paper_root_is_right(d)) == (d.L * (d.R - d.r) * d.H > 0)


def test_eq10_check_over_the_profiles_travel_and_with_a_larger_driver():
    profile = RD.RackDrive(20.0, 60.0, 300.0, 150.0)
    travel = np.linspace(100.0, 300.0, 201)
    assert RD.eq10_check(profile, travel)["holds"]
    assert RD.paper_inclination(profile) == pytest.approx(float(RD.paper_inclination_at(profile)[0]), abs=1e-15)
    swapped = RD.RackDrive(60.0, 20.0, 300.0, 150.0)  # R < r
    check = RD.eq10_check(swapped, travel)
    assert not check["holds"] and check["code"] == "paper-root"
    assert check["wrong_for_L"] == [100.0, 300.0] and "lower common tangent" in check["message"]
    past = RD.eq10_check(profile, np.linspace(-100.0, 300.0, 401))  # the wheel rolls under the driver
    assert not past["holds"] and past["undefined"] and past["wrong_for_L"] == [-100.0, 0.0]


@pytest.mark.parametrize(
    "d", [RD.RackDrive(20.0, 60.0, 300.0, 150.0), RD.RackDrive(60.0, 20.0, 300.0, 150.0)], ids=["R>r", "R<r"]
)
def test_projections_give_eqs_8_and_11_and_the_motion_law_derivative(d):
    """ω2 and ω3 by the paper's eqs. 12–13 (velocity projections and the instantaneous centre),
    against eqs. 8 and 11 and against central differences of the closed-contour law."""
    w1, h = 2.0, 1e-5
    phi1 = np.linspace(0.5, 6.0, 6)  # the R < r drive's rack stands vertical at φ1 = 6.73
    grid = np.sort(np.concatenate([phi1 - w1 * h, phi1, phi1 + w1 * h]))
    phi2 = RD.law_by_contour(d, grid)
    L = d.L - d.R * phi2
    beta = RD.inclination(d, L)
    numeric_w2 = (phi2[2::3] - phi2[0::3]) / (2 * h)
    numeric_w3 = (beta[2::3] - beta[0::3]) / (2 * h)
    proj = RD.velocity_projections(d, L[1::3], omega1=w1)
    np.testing.assert_allclose(proj.omega2, numeric_w2, rtol=1e-6)
    np.testing.assert_allclose(proj.omega3, numeric_w3, rtol=1e-5)
    w2, w3, _ = RD.rates(d, L[1::3], omega1=w1)
    np.testing.assert_allclose(proj.omega2, w2, rtol=1e-13)
    np.testing.assert_allclose(proj.omega3, w3, rtol=1e-12)
    # the instantaneous centre: both tangent points move perpendicular to their arms from it
    for P, A, B, w3k in zip(proj.centre, proj.A, proj.B, proj.omega3):
        for X in (A, B):
            v = w3k * np.array([-(X - P)[1], (X - P)[0]])
            assert np.hypot(*v) > 0
        # B moves with wheel 1 along the rack: |v_B| = ω1·r = ω3·|PB|
        assert abs(w3k) * np.hypot(*(B - P)) == pytest.approx(w1 * d.r, rel=1e-12)
    assert RD.projection_check(d, L, omega1=w1)["holds"]


def test_projections_of_a_horizontal_rack():
    flat = RD.RackDrive(r=20.0, R=60.0, L=300.0, H=40.0)
    proj = RD.velocity_projections(flat, [300.0], omega1=1.0)
    assert proj.omega2[0] == pytest.approx(20 / 120)  # r/2R
    assert RD.projection_check(flat, [300.0, 250.0], omega1=1.0)["holds"]
