"""The pitch-curve core against closed forms and independent methods."""

import math
import tracemalloc

import numpy as np
import pytest
from scipy.special import ellipe

from gearcad.errors import DesignError
from gearcad.pitch import chebyshev, shapes
from gearcad.pitch.curve import (
    TWO_PI,
    PitchCurve,
    arc_length_map,
    convexity,
    corners,
    curvature,
    perimeter,
    radius_range,
)
from gearcad.pitch.discretize import chord_deviation, polyline, polyline_angles


def test_chebyshev_integral_derivative_inverse():
    f = chebyshev.fit(np.exp, [0.0, 1.0, 3.0], rel_tol=1e-14)
    x = np.linspace(0, 3, 101)
    np.testing.assert_allclose(f(x), np.exp(x), rtol=1e-14)
    np.testing.assert_allclose(f.integral()(x), np.exp(x) - 1, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(f.derivative()(x), np.exp(x), rtol=1e-11)
    inv = f.inverse(rel_tol=1e-14)
    y = np.linspace(1, math.exp(3), 77)
    np.testing.assert_allclose(inv(y), np.log(y), atol=1e-13)


def test_chebyshev_splits_sharp_functions():
    def peak(x):  # height 10 000, width ~0.014 rad
        return 1 / (1.0001 - np.cos(x))

    f = chebyshev.fit(peak, [-math.pi, math.pi], rel_tol=1e-13)
    assert len(f.coefs) > 1 and max(len(c) for c in f.coefs) <= 128
    x = np.linspace(-math.pi, math.pi, 999)
    np.testing.assert_allclose(f(x), peak(x), rtol=1e-11)


def test_inverse_rejects_non_monotone_maps():
    f = chebyshev.fit(np.sin, [0.0, 3.0], rel_tol=1e-14)
    with pytest.raises(DesignError, match="not increasing"):
        f.inverse(rel_tol=1e-14)


@pytest.mark.parametrize("a,b", [(25, 15), (10, 9.99), (40, 4)])
def test_ellipse_perimeter_against_complete_elliptic_integral(a, b):
    e2 = 1 - (b / a) ** 2
    exact = 4 * a * ellipe(e2)
    assert perimeter(shapes.ellipse_centre(a, b)) == pytest.approx(exact, rel=1e-13)
    assert perimeter(shapes.ellipse_focus(a, b)) == pytest.approx(exact, rel=1e-13)


def test_arc_length_inverse_round_trip():
    s = arc_length_map(shapes.ellipse_focus(25, 15))
    phi = np.linspace(0, TWO_PI, 50)
    np.testing.assert_allclose(s.inverse(rel_tol=1e-14)(s(phi)), phi, atol=1e-12)


def test_closed_form_derivatives_against_finite_differences():
    h = 1e-5
    phi = np.linspace(0.1, 6.0, 13)
    curves = [
        shapes.ellipse_focus(25, 15),
        shapes.ellipse_centre(25, 15),
        shapes.oval(30, 12),
        shapes.from_ratio("law", *shapes.harmonic_ratio(1.0, [(1, 0.3, 0.1), (2, 0.05, 0)]), 40.0),
    ]
    for c in curves:
        np.testing.assert_allclose(c.dr(phi), (c.r(phi + h) - c.r(phi - h)) / (2 * h), rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(c.d2r(phi), (c.dr(phi + h) - c.dr(phi - h)) / (2 * h), rtol=1e-6, atol=1e-6)


def test_circle_curvature_and_convexity():
    c = shapes.circle(20)
    np.testing.assert_allclose(curvature(c, np.linspace(0, 6, 7)), 1 / 20)
    data = convexity(c)
    assert data.convex and data.min_curvature_radius == pytest.approx(20)
    assert radius_range(c) == (20, 20)


def test_ellipse_extreme_radii_and_curvature():
    a, b = 25.0, 15.0
    c = math.sqrt(a * a - b * b)
    assert radius_range(shapes.ellipse_focus(a, b)) == pytest.approx((a - c, a + c), rel=1e-12)
    assert radius_range(shapes.ellipse_centre(a, b)) == pytest.approx((b, a), rel=1e-12)
    # smallest radius of curvature of an ellipse is b²/a at the ends of the major axis
    assert convexity(shapes.ellipse_centre(a, b)).min_curvature_radius == pytest.approx(b * b / a, rel=1e-9)


def _trefoil(depth):
    """r = 1 + depth·cos 3φ: convex for depth ≤ 1/10, concave near φ = 60° beyond."""
    return PitchCurve(
        "trefoil",
        r=lambda p: 1 + depth * np.cos(3 * np.asarray(p)),
        dr=lambda p: -3 * depth * np.sin(3 * np.asarray(p)),
        d2r=lambda p: -9 * depth * np.cos(3 * np.asarray(p)),
        lobes=3,
    )


def test_convexity_threshold_of_a_trefoil():
    # at φ = 60°: r = 1 − d, r' = 0, r'' = 9d, so r² − r·r'' = (1 − d)(1 − 10d): zero at d = 1/10
    assert convexity(_trefoil(0.0999)).convex
    bad = convexity(_trefoil(0.2))
    assert not bad.convex
    centres = [0.5 * (lo + hi) for lo, hi in bad.concave_intervals]
    assert any(abs(math.degrees(c) - 60) < 1 for c in centres)
    assert bad.min_margin == pytest.approx((0.8 * 0.8 - 0.8 * 1.8) / 0.64, rel=1e-6)


def test_corner_detection_on_a_v_shaped_curve():
    """r = 10 + |sin φ| has corners at 0 and π (tangent turns by 2·atan(1/10))."""
    c = PitchCurve(
        "v",
        r=lambda p: 10 + np.abs(np.sin(p)),
        dr=lambda p: np.sign(np.sin(p)) * np.cos(p),
        d2r=lambda p: -np.abs(np.sin(p)),
        lobes=2,
        breaks=(0.0, math.pi),
    )
    found = corners(c)
    assert [round(x.phi, 9) for x in found] == [0.0, round(math.pi, 9)]
    assert all(not x.convex for x in found)
    assert abs(found[0].turn) == pytest.approx(2 * math.atan(0.1), rel=1e-6)
    assert corners(shapes.ellipse_focus(25, 15)) == []


def test_from_samples_reproduces_a_trigonometric_polynomial():
    exact = shapes.from_ratio("law", *shapes.harmonic_ratio(1.0, [(2, 0.2, 0.1), (4, 0.03, 0)]), 40.0)

    # r of a ratio law is not a trig polynomial; sample a genuine one instead
    def r(p):
        return 20 + 2 * np.cos(2 * p) - np.sin(3 * p) + 0.5 * np.cos(5 * p)

    curve = shapes.from_samples("s", r(np.linspace(0, TWO_PI, 16, endpoint=False)))
    phi = np.linspace(0, TWO_PI, 33)
    np.testing.assert_allclose(curve.r(phi), r(phi), atol=1e-12)
    np.testing.assert_allclose(
        curve.dr(phi), -4 * np.sin(2 * phi) - 3 * np.cos(3 * phi) - 2.5 * np.sin(5 * phi), atol=1e-11
    )
    assert exact.lobes == 1


def test_from_samples_of_many_radii_is_evaluated_in_bounded_memory():
    """A sweep found 500 radii and a 10-tooth cut asking for 386 046 angles at once: the
    (angles × orders) arrays took 739 MB each, past the 2 GiB budget.  By Horner's rule the
    series still interpolates the radii exactly (trigonometric interpolation)."""
    radii = 20 + np.random.default_rng(7).random(2001)  # noise: all 1001 orders matter
    curve = shapes.from_samples("noisy", radii)
    phi = np.linspace(0, TWO_PI, 2001 * 10, endpoint=False)
    tracemalloc.start()
    r = curve.r(phi)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 40e6  # unblocked: 20 010 × 1001 × 8 B = 160 MB per array
    np.testing.assert_allclose(r[::10], radii, atol=1e-11)


@pytest.mark.parametrize("tol", [0.1, 0.01, 0.001])
def test_polyline_within_tolerance_and_not_wasteful(tol):
    curve = shapes.ellipse_focus(25, 15)
    phi = polyline_angles(curve, tol)
    dense = np.linspace(phi[:-1], phi[1:], 17, axis=1)
    # true deviation: the curve between two vertices against their chord, sampled densely
    pts = curve.r(dense)[..., None] * np.stack([np.cos(dense), np.sin(dense)], -1)
    a, b = pts[:, :1], pts[:, -1:]
    d = b - a
    dist = np.abs(d[..., 0] * (pts[..., 1] - a[..., 1]) - d[..., 1] * (pts[..., 0] - a[..., 0])) / np.hypot(
        d[..., 0], d[..., 1]
    )
    assert dist.max() <= tol
    assert chord_deviation(curve, phi).max() > 0.5 * tol  # not over-sampled by a fixed count
    assert len(polyline(curve, tol)) == len(phi) - 1


def test_noise_in_sampled_radii_is_dropped_within_the_allowance():
    """Radii of a smooth curve (orders up to 5) with a micrometre-scale grain on 3600 samples: with
    0.01 mm allowed the grain's ~1800 orders are dropped — the curve is within 0.01 mm of the
    smooth one and holds no order above 5 — and without the allowance the order cap refuses it."""

    def smooth(p):
        return 20 + 2 * np.cos(2 * p) - np.sin(3 * p) + 0.5 * np.cos(5 * p)

    phi = np.linspace(0, TWO_PI, 3600, endpoint=False)
    grain = 1e-3 * np.random.default_rng(3).uniform(-1, 1, len(phi))
    curve = shapes.from_samples("scan", smooth(phi) + grain, negligible=0.01, max_order=5, key="gear1.radii")
    dense = np.linspace(0, TWO_PI, 20000, endpoint=False)
    assert np.max(np.abs(curve.r(dense) - smooth(dense))) <= 0.01
    with pytest.raises(DesignError, match=r"^gear1\.radii: .* order 1800 per turn \(at most order 5\)"):
        shapes.from_samples("scan", smooth(phi) + grain, max_order=5, key="gear1.radii")


def test_a_profile_of_noisy_radii_is_refused_at_once():
    """2000 radii with half a millimetre of noise once took 40 s to refuse (20 000 took 300 s)."""
    import time

    from gearcad.fitting import design
    from gearcad.profiles import parse_profile

    radii = (20 + 0.5 * np.random.default_rng(5).uniform(-1, 1, 2000)).tolist()
    params = parse_profile(
        {"gear1": {"curve": "samples", "radii": radii}, "gear2": {"lobes": 1}, "teeth": {"count": 40}}
    )
    start = time.process_time()
    with pytest.raises(DesignError, match=r"^gear1\.radii: the radii vary on a finer scale"):
        design(params)
    assert time.process_time() - start < 20  # CPU seconds, a bound, not a benchmark: refused before any cut


def test_dropped_noise_never_moves_the_curve_more_than_allowed():
    """The dropped orders are bounded everywhere, not only on the grid they are measured on:
    300 radii with 0.02 mm of noise, 0.05 mm allowed, compared on 300 000 angles."""
    phi = np.linspace(0, TWO_PI, 300_000, endpoint=False)
    for seed in range(10):
        radii = 20 + 0.02 * np.random.default_rng(seed).uniform(-1, 1, 300)
        full, thinned = shapes.from_samples("a", radii), shapes.from_samples("b", radii, negligible=0.05)
        assert np.max(np.abs(full.r(phi) - thinned.r(phi))) <= 0.05


@pytest.mark.parametrize(
    ("curve", "declared", "found"),
    [
        (shapes.ellipse_centre(25.0, 20.0), 1, 2),
        (shapes.ellipse_focus(25.0, 20.0), 2, 1),
        (shapes.oval(25.0, 20.0), 4, 2),
    ],
)
def test_radii_with_other_lobes_than_declared_are_refused_naming_the_key(tmp_path, capsys, curve, declared, found):
    """An ellipse about its centre repeats twice a turn, about a focus once (issue 24, item 16):
    declared otherwise, the build stops in one line naming gear1.lobes and what the radii hold
    (was: accepted as another pair, or "perimeter … is not 12 × π·m")."""
    from gearcad.cli import main

    radii = curve.r(np.linspace(0, TWO_PI, 90, endpoint=False))
    path = tmp_path / "s.toml"
    path.write_text(
        f"[gear1]\ncurve = 'samples'\nlobes = {declared}\nradii = {[round(float(r), 9) for r in radii]}\n"
        f"[gear2]\nlobes = {declared}\n[teeth]\ncount = 12\n",
        encoding="utf-8",
    )
    out = tmp_path / "out"
    assert main(["build", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and not out.exists()
    assert f"gear1.lobes = {declared}:" in err and f"set gear1.lobes = {found}" in err
    assert shapes.from_samples("same", radii, lobes=found).lobes == found  # the right count passes
