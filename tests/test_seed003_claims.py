"""Seed 003 (bodies on three rollers): the kinematics formulas and the statements of the text,
each against an independent computation — symbolic differentiation of eq. 6 (sympy), central
differences of the centre's path, closed-form curvature limits, and polygon tests of the contour
written out here from the corrected eq. 3."""

import json
import math

import numpy as np
import pytest
import shapely
from scipy.optimize import brentq, minimize_scalar

from gearcad.bodies import claims as C
from gearcad.bodies import limits as LM

W = 3 * math.pi  # the paper's example: 90 rpm
TWO_PI = 2 * math.pi


# ------------------------------------------------------------------ eqs. 9 and 10, symbolically


def _symbolic_moduli():
    sp = pytest.importorskip("sympy")
    t, w, a, x1, y1 = sp.symbols("t w a x1 y1", real=True)
    m = sp.Symbol("m", positive=True)
    x = (x1 - a * sp.sin(m * w * t)) * sp.cos(w * t) - y1 * sp.sin(w * t)  # eq. 6
    y = (x1 - a * sp.sin(m * w * t)) * sp.sin(w * t) + y1 * sp.cos(w * t)
    v2 = sp.diff(x, t) ** 2 + sp.diff(y, t) ** 2
    a2 = sp.diff(x, t, 2) ** 2 + sp.diff(y, t, 2) ** 2
    return sp.lambdify((x1, y1, a, m, w, t), v2, "numpy"), sp.lambdify((x1, y1, a, m, w, t), a2, "numpy")


@pytest.fixture(scope="module")
def moduli():
    return _symbolic_moduli()


CASES = [(0.3, -0.7, 0.05, 3, 2.0), (1.0, 0.0, 0.01, 3, W), (-0.6, 0.8, 0.02, 6, 1.3), (0.0, 1.0, 0.1, 9, 0.7)]


@pytest.mark.parametrize("x1,y1,a,m,w", CASES)
def test_eq9_speed_modulus_holds(moduli, x1, y1, a, m, w):
    t = np.linspace(0, TWO_PI / w, 997)
    v2, _ = moduli
    np.testing.assert_allclose(C.paper_speed_modulus(x1, y1, a=a, m=m, w=w, t=t), np.sqrt(v2(x1, y1, a, m, w, t)))


@pytest.mark.parametrize("x1,y1,a,m,w", CASES)
def test_eq10_acceleration_modulus_has_the_wrong_sign_on_its_cross_term(moduli, x1, y1, a, m, w):
    t = np.linspace(0, TWO_PI / w, 997)
    _, a2 = moduli
    exact = np.sqrt(a2(x1, y1, a, m, w, t))
    np.testing.assert_allclose(C.acceleration_modulus(x1, y1, a=a, m=m, w=w, t=t), exact, rtol=1e-12)
    printed = C.paper_acceleration_modulus(x1, y1, a=a, m=m, w=w, t=t)
    # off the centre, the printed form is wrong by a visible amount wherever it is defined
    assert np.nanmax(np.abs(printed - exact)) > 0.05 * exact.max()


def test_eq10_holds_at_the_centre_where_the_cross_term_vanishes(moduli):
    t = np.linspace(0, 1, 101)
    _, a2 = moduli
    exact = np.sqrt(a2(0.0, 0.0, 0.01, 3, W, t))
    np.testing.assert_allclose(C.paper_acceleration_modulus(0.0, 0.0, a=0.01, m=3, w=W, t=t), exact, rtol=1e-12)


def test_kinematics_checks_report_eq10_and_the_vmax_instants():
    checks = {c["claim"]: c for c in C.kinematics_checks(a=0.01, m=3, w=W)}
    assert checks["eq. 9: |V| of a body point"]["holds"]
    assert not checks["eq. 10: |A| of a body point"]["holds"]
    assert not checks["instants of the centre's largest speed a·m·w"]["holds"]
    assert checks["instants of the centre's largest acceleration a·w²(m² + 1)"]["holds"]
    assert all(c["code"] in ("paper-formula", "paper-claim") for c in checks.values())


# ------------------------------------------------------------------ instants of the extremes


def test_instants_of_largest_centre_speed_by_central_differences():
    """Centre path from eq. 6 (x1 = y1 = 0), speed by central differences on a fine grid: its
    maxima sit at t = πk/(wm); the paper's odd k land on the minima, speed a·w."""
    a, m, w = 0.01, 3, W
    h = 1e-7

    def centre(t):
        s = a * np.sin(m * w * t)
        return np.column_stack([-s * np.cos(w * t), -s * np.sin(w * t)])

    def speed(t):
        return np.hypot(*((centre(t + h) - centre(t - h)) / (2 * h)).T)

    t = np.linspace(0, TWO_PI / w, 200001)
    v = speed(t)
    peaks = t[1:-1][(v[1:-1] > v[:-2]) & (v[1:-1] >= v[2:])]
    k = np.arange(1, 2 * m)
    np.testing.assert_allclose(peaks, C.vmax_instants(m, w, k), atol=2 * (t[1] - t[0]))
    at_paper = speed(C.paper_vmax_instants(m, w, np.arange(0, 4 * m)))
    np.testing.assert_allclose(at_paper[0::2], a * m * w, rtol=1e-6)
    np.testing.assert_allclose(at_paper[1::2], a * w, rtol=1e-6)  # the smallest speed
    t = t[::10]
    acc = np.hypot(*((centre(t + 1e-4) - 2 * centre(t) + centre(t - 1e-4)) / 1e-8).T)
    apeaks = t[1:-1][(acc[1:-1] > acc[:-2]) & (acc[1:-1] >= acc[2:])]
    np.testing.assert_allclose(apeaks, C.amax_instants(m, w, np.arange(0, 2 * m)), atol=2 * (t[1] - t[0]))


# ------------------------------------------------------------------ amplitude laws


def test_eq4_regression_reproduced_independently(seed_tables):
    from scipy.stats import linregress  # here: scipy.stats takes 0.8 s to import, in every test process

    rows = seed_tables["roller_bodies_003"]["largest_oval_amplitude_by_eye"]["rows"]
    fit = linregress(np.log([r[0] for r in rows]), np.log([r[1] for r in rows]))
    assert math.exp(fit.intercept) == pytest.approx(1.74, abs=0.005)
    assert fit.slope == pytest.approx(-2.07, abs=0.005)
    assert fit.rvalue**2 == pytest.approx(0.97, abs=0.005)
    coefficient, exponent, r2 = C.power_law_fit([r[0] for r in rows], [r[1] for r in rows])
    assert (coefficient, exponent, r2) == pytest.approx((math.exp(fit.intercept), fit.slope, fit.rvalue**2))


def test_sqrt3_over_m2_is_7_to_20_percent_above_eq4_not_12_to_25():
    m = np.array([3, 15])
    excess = np.sqrt(3) / m**2 / (1.74 * m**-2.07) - 1
    np.testing.assert_allclose(C.approximation_gap((3, 15)), excess)
    assert excess[0] == pytest.approx(0.0750, abs=5e-4) and excess[1] == pytest.approx(0.2032, abs=5e-4)
    check = {c["claim"][:5]: c for c in C.amplitude_law_checks()}["√3/m²"]
    assert not check["holds"]


def test_a1_in_units_of_the_roller_spacing_is_one_over_m_squared():
    """The roller centres are 120° apart on the unit circle; their spacing is measured, not
    assumed, and the amplitude √3/m² is divided by it."""
    centres = np.array([[math.sin(k * TWO_PI / 3), math.cos(k * TWO_PI / 3)] for k in range(3)])
    spacing = float(np.hypot(*(centres[1] - centres[0])))
    m = np.array([3, 6, 9, 12, 15])
    a1 = np.sqrt(3) / m**2 / spacing
    np.testing.assert_allclose(C.a1_from_law(m), a1)
    np.testing.assert_allclose(a1 * m**2, 1.0)
    assert np.all(C.paper_a1(m) / a1 == pytest.approx(3.0))


# ------------------------------------------------------------------ amplitude limits against r


def _curvature_numerator(direction, a, m, tau):
    """x'y'' − y'x'' of the roller path, worked out by hand: −1 − a·m·q(τ)."""
    if direction == "vertical":
        q = m * np.sin(m * tau) * np.cos(tau) - np.cos(m * tau) * np.sin(tau)
    else:
        q = np.cos(m * tau) * np.cos(tau) + m * np.sin(m * tau) * np.sin(tau)
    return -1 - a * m * q


def _convex_limit_closed_form(direction, m):
    """The path is convex while 1 + a·m·q(τ) > 0: a = 1/(m·max(−q)), max by grid + refinement."""
    tau = np.linspace(0, TWO_PI, 20001)
    neg_q = _curvature_numerator(direction, 1.0, m, tau) + 1  # = −m·q at a = 1
    k = int(np.argmax(neg_q))
    res = minimize_scalar(
        lambda s: -(_curvature_numerator(direction, 1.0, m, s) + 1),
        bracket=(tau[k - 1], tau[k], tau[k + 1]),
        tol=1e-14,
    )
    return 1.0 / -res.fun


@pytest.fixture(scope="module")
def table():
    return LM.amplitude_limit_table(ms=(3, 6, 9), radii=(0.0, 0.1, 0.4))


@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
def test_convex_limits_do_not_depend_on_r_and_match_the_closed_form(table, direction):
    for i, m in enumerate(table.m):
        exact = _convex_limit_closed_form(direction, m)
        for j, r in enumerate(table.r):
            if direction == "vertical" and m == 3 and r == 0.4:
                continue  # a cusp comes first, below
            assert table.convex[direction][i, j] == pytest.approx(exact, rel=1e-9), (m, r)


def test_convex_limits_exact_values():
    assert _convex_limit_closed_form("vertical", 3) == pytest.approx(2 / (9 * math.sqrt(3)), rel=1e-12)
    assert LM.amplitude_limit("vertical", 3, r=0.1, test="convex") == pytest.approx(2 / (9 * math.sqrt(3)), rel=1e-10)
    assert LM.amplitude_limit("horizontal", 3, r=0.1, test="convex") == pytest.approx(1 / 9, rel=1e-10)
    assert LM.amplitude_limit("horizontal", 15, r=0.1, test="convex") == pytest.approx(1 / 225, rel=1e-10)


def test_large_roller_reaches_a_cusp_before_a_concave_stretch(table):
    """Vertical, m = 3, r = 0.4: the offset's curvature radius ρ_P − r reaches zero (r·κ_P = 1)
    before κ_P does — the limit is where max κ_P = 1/r, found here from the hand-derived path."""
    tau = np.linspace(0, TWO_PI, 20001)

    def max_kappa(a):
        x1, y1 = np.cos(tau), -np.sin(tau) + a * 3 * np.cos(3 * tau)
        num = -_curvature_numerator("vertical", a, 3, tau)
        return float(np.max(num / np.hypot(x1, y1) ** 3))

    cusp = brentq(lambda a: max_kappa(a) - 1 / 0.4, 0.01, 0.128, xtol=1e-14)
    assert table.convex["vertical"][0, -1] == pytest.approx(cusp, rel=1e-5)  # r = 0.4
    assert cusp < _convex_limit_closed_form("vertical", 3)


def test_even_m_gives_the_same_body_for_both_directions(table):
    """For even m, P_vertical(τ + π/2) is P_horizontal(τ) turned by 90° (or with −a, turned by
    180° more): both directions have the same limits."""
    for i, m in enumerate(table.m):
        if m % 2 == 0:
            np.testing.assert_allclose(table.convex["horizontal"][i], table.convex["vertical"][i], rtol=1e-9)
            np.testing.assert_allclose(table.simple["horizontal"][i], table.simple["vertical"][i], rtol=1e-6)


def _contour(direction, a, m, r, tau):
    """Corrected eq. 3, written out here: P moved in by r along the unit normal."""
    f = a * np.sin(m * tau) if direction == "horizontal" else 0 * tau
    g = a * np.sin(m * tau) if direction == "vertical" else 0 * tau
    f1 = a * m * np.cos(m * tau) if direction == "horizontal" else 0 * tau
    g1 = a * m * np.cos(m * tau) if direction == "vertical" else 0 * tau
    nx, ny = np.sin(tau) - g1, np.cos(tau) + f1
    w = np.hypot(nx, ny)
    return np.column_stack([np.sin(tau) + f - r * nx / w, np.cos(tau) + g - r * ny / w])


@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
def test_simple_limits_fall_with_the_roller_radius_and_bound_the_loops(table, direction):
    tau = np.linspace(0, TWO_PI, 40000, endpoint=False)
    for i, m in enumerate(table.m[:2]):
        limits = table.simple[direction][i, 1:]
        assert np.all(np.diff(limits) < 0), (m, limits)  # larger rollers, smaller loop-free range
        for r, limit in zip(table.r[1:], limits):
            assert shapely.LinearRing(_contour(direction, 0.99 * limit, m, r, tau)).is_simple, (m, r)
            assert not shapely.LinearRing(_contour(direction, 1.02 * limit, m, r, tau)).is_simple, (m, r)


def test_the_bare_vertical_roller_path_never_crosses_itself_for_odd_m(table):
    """x = sin τ is shared only by τ and π − τ, whose y differ by 2cos τ when m is odd: no
    crossing for any a, so the r = 0 simple limit is reported as none (inf / None).  For even m
    the difference is 2cos τ + 2a·sin mτ, which does vanish: a finite limit."""
    assert math.isinf(table.simple["vertical"][0, 0]) and math.isinf(table.simple["vertical"][2, 0])
    assert math.isfinite(table.simple["vertical"][1, 0])
    assert table.as_dict()["simple"]["vertical"][0][0] is None


def test_roller_radius_claim_fails_with_numbers():
    check = LM.radius_claim_check("vertical", 0.1, 3)
    assert not check["holds"] and check["code"] == "paper-claim"
    rows = check["computed"]["rows"]
    tau = np.linspace(0, TWO_PI, 4096, endpoint=False)
    for row in (rows[0], rows[-1]):
        rho = np.hypot(*_contour("vertical", 0.1, 3, row["r"], tau).T)
        assert row["out_of_round"] == pytest.approx((rho.max() - rho.min()) / (rho.max() + rho.min()), rel=1e-9)
    # a parallel offset keeps ρmax − ρmin nearly fixed while the body shrinks: relative
    # out-of-roundness grows with r, so the shapes are not similar
    assert rows[-1]["out_of_round"] > 1.5 * rows[0]["out_of_round"]
    assert rows[0]["shape_distance"] == 0.0 and rows[-1]["shape_distance"] > 0.05


def test_nodal_points_at_a_0_2_only_for_the_larger_rollers():
    check = LM.nodal_points_check("vertical", 3, 0.2)
    tau = np.linspace(0, TWO_PI, 40000, endpoint=False)
    looped = [r for r in LM.PAPER_RADII if not shapely.LinearRing(_contour("vertical", 0.2, 3, r, tau)).is_simple]
    assert check["computed"]["looped_for_r"] == looped == [0.2, 0.3, 0.4]
    assert not check["holds"]


def test_shape_family_kinds_and_orientation():
    family = LM.shape_family("vertical", 3, [0.1, 0.2], [0.0, 0.4])
    kinds = {(f["amplitude"], f["r"]): f["kind"] for f in family}
    assert kinds == {(0.1, 0.0): "convex", (0.1, 0.4): "convex", (0.2, 0.0): "concave", (0.2, 0.4): "looped"}
    for f in family:
        pts = f["points"]
        assert np.allclose(pts[0], pts[-1])
        if f["kind"] != "looped":
            assert shapely.Polygon(pts).is_valid and shapely.LinearRing(pts).is_ccw


def _png_size(path):
    from PIL import Image

    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with Image.open(path) as im:
        return im.size


def test_charts_of_the_limits_against_r_and_the_shape_families(built):
    """The charts the roller body's build draws (profiles/roller_body_m3.toml, read back from the
    session's build), at the sizes their layouts give at 110 dpi: the limits against r one
    6.5 × 5 in panel per direction (both, as docs/papers.md promises) and 2.4 in of legend; the
    paper's Figs. 1–2 one 2.4 in square per roller radius (columns) and amplitude (rows)."""
    folder = built / "roller_body_m3"
    table = json.loads((folder / "report.json").read_text(encoding="utf-8"))["limits_vs_r"]
    assert list(table["convex"]) == ["horizontal", "vertical"]  # both directions: two panels
    assert _png_size(folder / "limits_vs_r.png") == (1694, 550)  # (2 × 6.5 + 2.4) × 5 in
    # horizontal, m = 3, r = 0: the bare path's convex limit in closed form, 1/9 (docs/papers.md)
    assert table["convex"]["horizontal"][0][table["r"].index(0.0)] == pytest.approx(1 / 9, rel=1e-9)
    # Figs. 1 (m = 3) and 2 (m = 6): three amplitudes each, the paper's five radii 0, 0.1, … 0.4
    for m in (3, 6):
        assert _png_size(folder / f"shape_family_m{m}.png") == (1320, 792), m  # 5 × 2.4 by 3 × 2.4 in
