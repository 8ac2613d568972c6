"""gearcad's Brent root finder against scipy's, on smooth, flat and steep functions."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq as scipy_brentq

from gearcad.errors import DesignError
from gearcad.roots import brentq

CASES = [
    (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),  # Wallis's cubic, root 2.0945514815423265
    (lambda x: math.cos(x) - x, 0.0, 1.0),
    (lambda x: math.exp(x) - 1e6, 0.0, 20.0),
    (lambda x: (x - 1) ** 3, 0.0, 3.0),  # a triple root: flat
    (lambda x: math.atan(1e6 * (x - 0.3)), -1.0, 1.0),  # steep
]


@pytest.mark.parametrize("f,a,b", CASES)
def test_agrees_with_scipy(f, a, b):
    assert brentq(f, a, b, xtol=1e-15) == pytest.approx(scipy_brentq(f, a, b, xtol=1e-15, maxiter=500), abs=1e-12)
    assert abs(f(brentq(f, a, b, xtol=1e-15))) <= abs(f(a)) * 1e-9 + 1e-12


@settings(max_examples=60, deadline=None, derandomize=True)
@given(root=st.floats(-50, 50), scale=st.floats(0.01, 100), lo=st.floats(0.01, 10), hi=st.floats(0.01, 10))
def test_finds_the_root_of_a_shifted_cubic(root, scale, lo, hi):
    x = brentq(lambda t: scale * (t - root) ** 3 + (t - root), root - lo, root + hi, xtol=1e-13)
    assert x == pytest.approx(root, abs=1e-10)


def test_needs_a_bracket():
    with pytest.raises(DesignError, match="no sign change"):
        brentq(lambda x: x * x + 1, -1.0, 1.0)
