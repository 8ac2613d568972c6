"""The internal conjugate (gearcad.pitch.internal): a pinion rolling inside a ring about fixed
centres, against closed forms — circles, and the focus ellipse in a two-lobe ring."""

import math
from dataclasses import replace

import numpy as np
import pytest

from gearcad.errors import DesignError
from gearcad.pitch import shapes
from gearcad.pitch.internal import internal_pair


def test_circles_are_an_internal_spur_pair():
    """A circle of radius 10 as 2 "lobes" in a ring of 3: ring radius 15, E = 5, ratio 2/3; the
    curvature margin 1/10 − 1/15."""
    pair = internal_pair(replace(shapes.circle(10.0), lobes=2), ring_lobes=3)
    assert pair.center_distance == pytest.approx(5.0, abs=1e-12)
    assert pair.ring.r(np.linspace(0, 6, 7)) == pytest.approx(15.0, abs=1e-12)
    assert pair.angle_map(np.array([1.0]))[0] == pytest.approx(2 / 3, abs=1e-13)
    assert pair.curvature_margin == pytest.approx(1 / 10 - 1 / 15, abs=1e-12)


def test_the_focus_ellipse_closes_in_a_two_lobe_ring_at_the_closed_form():
    """r = p/(1 − ε·cos φ): ∫ r/(r + E) dφ = 2πp/√((p + E)² − E²ε²); closing at π (two lobes)
    gives (1 − ε²)E² + 2pE − 3p² = 0."""
    a, b = 25.0, 15.0
    p, eps = b * b / a, math.sqrt(a * a - b * b) / a
    exact = p * (math.sqrt(1 + 3 * (1 - eps**2)) - 1) / (1 - eps**2)
    pair = internal_pair(shapes.ellipse_focus(a, b), ring_lobes=2)
    assert pair.center_distance == pytest.approx(exact, rel=1e-13)
    assert pair.closure_error < 1e-11
    assert max(pair.contact_residual, pair.slip_residual) < 1e-9
    # the rolling checked without the pair's own angle map: trapezoid sums of r1/(r1 + E)
    phi = np.linspace(0.0, 2 * math.pi, 200001)
    r1 = pair.pinion.r(phi)
    rate = r1 / (r1 + exact)
    phi2 = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(phi))])
    k = np.arange(0, len(phi), 20000)
    assert pair.ring.r(phi2[k]) == pytest.approx(r1[k] + exact, abs=1e-6)
    assert phi2[-1] == pytest.approx(math.pi, abs=1e-8)


def test_a_ring_needs_more_lobes_than_its_pinion():
    with pytest.raises(DesignError, match=r"^ring.lobes = 2: .* 3 or more"):
        internal_pair(replace(shapes.circle(10.0), lobes=2), ring_lobes=2)
