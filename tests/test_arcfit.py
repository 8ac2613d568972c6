"""Arc fitting and thinning against closed forms: circles and ellipses sampled finely."""

import math

import numpy as np
import pytest

from gearcad.geometry.arcfit import arc_points, decimate, fit_arcs
from gearcad.pitch import shapes
from gearcad.pitch.discretize import polyline


def _ellipse(a, b, n):
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


def _ellipse_distance(points, a, b):
    """Distance of points near the ellipse x²/a² + y²/b² = 1 to it: the foot point's parameter t
    solved by Newton's method from (b²−a²)·sin t·cos t + x·a·sin t − y·b·cos t = 0 (the offset is
    normal to the curve), started at the points' own parametric angle.  For points far closer
    to the ellipse than its least radius of curvature b²/a the foot point is unique."""
    x, y = points[:, 0], points[:, 1]
    t = np.arctan2(a * y, b * x)
    for _ in range(50):
        s, c = np.sin(t), np.cos(t)
        f = (b * b - a * a) * s * c + x * a * s - y * b * c
        df = (b * b - a * a) * (c * c - s * s) + x * a * c + y * b * s
        assert np.all(df > 0)  # a minimum of the distance, not a maximum
        step = f / df
        t = t - step
        if np.abs(step).max() < 1e-15:
            break
    else:
        raise AssertionError("the foot points did not converge")
    return np.hypot(x - a * np.cos(t), y - b * np.sin(t))


def test_a_circle_needs_only_a_few_arcs():
    t = np.linspace(0, 2 * math.pi, 4000, endpoint=False)
    ring = 10 * np.column_stack([np.cos(t), np.sin(t)])
    arcs = fit_arcs(ring, 1e-4)
    # a circle is arcs, bar at most one leftover chord of the fine ring where the walk closes
    assert len(arcs.vertices) <= 40 and arcs.arcs >= len(arcs.vertices) - 1
    back = arc_points(arcs, 1e-7)
    assert np.abs(np.hypot(*back.T) - 10).max() < 1e-9  # the arcs are the circle itself


@pytest.mark.parametrize("tol", [1e-2, 1e-3])
def test_arcs_and_thinning_stay_within_tolerance_of_an_ellipse(tol):
    # as the product does: the curve sampled with chords within a quarter of the tolerance
    ring = polyline(shapes.ellipse_centre(25, 15), tol / 4)
    arcs = fit_arcs(ring, 0.75 * tol)
    back = arc_points(arcs, tol / 100)
    assert _ellipse_distance(back, 25, 15).max() <= tol
    thin = decimate(ring, 0.75 * tol)
    mids = 0.5 * (thin + np.roll(thin, -1, axis=0))
    assert _ellipse_distance(mids, 25, 15).max() <= tol
    assert len(thin) <= len(ring) and len(arcs.vertices) * 4 < len(ring)


def test_a_large_ring_is_walked_in_blocks_within_tolerance(monkeypatch):
    """Past ``_SIDE_BY_SIDE`` vertices a ring of long runs is walked from many cuts at once: on a
    circle of radius 2 m sampled as the product samples (chords within a quarter of the
    tolerance) the arcs and the thinned ring stay within the tolerance of the exact circle; on
    a wavy ring (200 waves) the walk in blocks costs at most one vertex per cut more than the
    walk from one cut."""
    from gearcad.geometry import arcfit

    tol, radius = 1e-4, 2000.0
    ring = polyline(shapes.circle(radius), tol / 4)
    assert len(ring) >= arcfit._SIDE_BY_SIDE

    def off_circle(points):
        return np.abs(np.hypot(*points.T) - radius).max()

    assert off_circle(arc_points(fit_arcs(ring, 0.75 * tol), tol / 100)) <= tol
    thin = decimate(ring, 0.75 * tol)
    assert off_circle(0.5 * (thin + np.roll(thin, -1, axis=0))) <= tol

    phi = np.linspace(0, 2 * math.pi, 60000, endpoint=False)
    wavy = (100 + np.cos(200 * phi))[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
    blocks = fit_arcs(wavy, 1e-3)
    monkeypatch.setattr(arcfit, "_SIDE_BY_SIDE", len(wavy) + 1)
    whole = fit_arcs(wavy, 1e-3)
    cuts = len(wavy) // (16 * arcfit._LONG_RUN)  # at most one cut per 16 runs of the shortest length walked so
    assert len(whole.vertices) <= len(blocks.vertices) <= len(whole.vertices) + cuts


@pytest.mark.parametrize("arcs", [True, False])
def test_reach_ahead_and_the_chained_walk_measure_what_every_vertex_would(arcs):
    """The reach tried several lengths ahead equals the doubling-then-bisection reach at any
    starts; and the arc runs found by walks stopping where they meet are the walk's runs from
    every vertex's reach: on a wavy ring with a corner (runs of many lengths, some cut short by
    the ring's end)."""
    from gearcad.geometry import arcfit

    phi = np.linspace(0, 2 * math.pi, 1200, endpoint=False)
    wavy = (20 + 0.5 * np.cos(7 * phi) + 0.3 * np.abs(np.sin(3 * phi)))[:, None] * np.column_stack(
        [np.cos(phi), np.sin(phi)]
    )
    pts, _ = arcfit._rolled(wavy)
    n = len(wavy)
    every = np.arange(n)
    for tol in (1e-4, 1e-3, 1e-2):
        reach = arcfit._reach_at(pts, every, n - every, tol, arcs)
        assert reach.min() >= 1 and reach.max() > 8
        rng = np.random.default_rng(5)
        for size in (1, 9, 200):
            starts = np.sort(rng.choice(n, size, replace=False))
            assert np.array_equal(arcfit._reach_ahead(pts, starts, n - starts, tol, arcs), reach[starts])
        if arcs:
            walked = arcfit._chained(pts, n, tol)
            i = 0
            while i < n:
                assert walked[i] == reach[i]
                i += reach[i]


def _lobed(lobes: int, per_lobe: int, e: float = 0.02) -> np.ndarray:
    """r = 10·(1 + e·cos(lobes·θ)) sampled ``per_lobe`` times a lobe: its own vertices turned by
    2π/lobes."""
    t = np.linspace(0, 2 * math.pi, lobes * per_lobe, endpoint=False)
    r = 10 * (1 + e * np.cos(lobes * t))
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def test_a_ring_drawn_lobe_by_lobe_is_found_to_repeat_and_its_arcs_repeat_too():
    """A 7-lobed curve sampled 300 times a lobe repeats by 2π/7 (not by more: 2π/14 moves a
    crest onto a trough); moved off its own turn by 1e-6 mm at one vertex it repeats no more.
    Fitted with ``repeats`` its arcs are one lobe's, repeated: each lobe's arc ends are the first
    lobe's turned by 2π/7 (to 1e-12 mm), the bulges alike, and every point of the arcs within
    the tolerance of the curve (its closed form r(θ), along the radius: within 1 % of the normal
    distance at this slope, r′/r ≤ 0.14)."""
    from gearcad.geometry.outline import rotate, turn_repeats

    ring = _lobed(7, 300)
    assert turn_repeats(ring) == 7
    bent = ring.copy()
    bent[5] += 1e-6
    assert turn_repeats(bent) == 1
    tol = 0.002
    arcs = fit_arcs(ring, tol, repeats=7)
    n = len(arcs.vertices)
    assert n % 7 == 0
    m = n // 7
    assert np.max(np.abs(rotate(arcs.vertices[:m], 2 * math.pi / 7) - arcs.vertices[m : 2 * m])) < 1e-12
    assert np.array_equal(arcs.bulges[:m], arcs.bulges[m : 2 * m])
    pts = arc_points(arcs, tol / 50)
    theta = np.arctan2(pts[:, 1], pts[:, 0])
    off = np.abs(np.hypot(pts[:, 0], pts[:, 1]) - 10 * (1 + 0.02 * np.cos(7 * theta)))
    assert off.max() <= 1.01 * tol
