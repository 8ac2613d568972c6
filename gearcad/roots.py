"""Brent's bracketed root finder (inverse quadratic interpolation, secant and bisection), and
golden sections over many brackets at once (:func:`golden_sections`).

The same method as ``scipy.optimize.brentq`` (Brent 1973, "Algorithms for Minimization without
Derivatives", ch. 4), a few lines here so that designing a gear pair does not import
scipy.optimize (a third of a second at start-up).  Checked against scipy in the tests.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .errors import DesignError

__all__ = ["brentq", "golden_sections"]

_EPS = 2.220446049250313e-16
GOLDEN = (math.sqrt(5) - 1) / 2


def golden_sections(f: Callable, lo, hi, steps: int, done: Callable | None = None):
    """Golden sections of ``f`` (an array of positions -> an array of values) over the brackets
    [lo, hi] (arrays), all at once: one new probe per bracket and step, at most ``steps`` steps,
    ending early once ``done(lo, hi, fa, fb)``.  Returns the two inner probes and their values
    (a, b, f(a), f(b)); the least lies in [lo, b] where f(a) <= f(b), else in [a, hi]."""
    a, b = hi - GOLDEN * (hi - lo), lo + GOLDEN * (hi - lo)
    fa, fb = f(a), f(b)
    for _ in range(steps):
        left = fa <= fb  # the least lies in [lo, b]: b becomes the upper end, a the new b
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
        a2, b2 = hi - GOLDEN * (hi - lo), lo + GOLDEN * (hi - lo)
        a, b = np.where(left, a2, b), np.where(left, a, b2)
        fresh = f(np.where(left, a, b))  # the one new probe of each bracket
        fa, fb = np.where(left, fresh, fb), np.where(left, fa, fresh)
        if done is not None and done(lo, hi, fa, fb):
            break
    return a, b, fa, fb


def brentq(
    f: Callable[[float], float], a: float, b: float, *, xtol: float = 2e-12, rtol: float = 4 * _EPS, maxiter: int = 200
) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) differ in sign, to ``xtol + rtol·|x|``."""
    fa, fb = f(a), f(b)
    if fa == 0:
        return a
    if fb == 0:
        return b
    if math.copysign(1.0, fa) == math.copysign(1.0, fb):
        raise DesignError(f"no sign change of the residual between {a:g} and {b:g}")
    c, fc = a, fa
    d = e = b - a
    for _ in range(maxiter):
        if math.copysign(1.0, fb) == math.copysign(1.0, fc):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 2 * rtol * abs(b) + xtol / 2
        m = (c - b) / 2
        if abs(m) <= tol or fb == 0:
            return b
        if abs(e) >= tol and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:  # secant
                p, q = 2 * m * s, 1 - s
            else:  # inverse quadratic interpolation
                q, r = fa / fc, fb / fc
                p = s * (2 * m * q * (q - r) - (b - a) * (r - 1))
                q = (q - 1) * (r - 1) * (s - 1)
            if p > 0:
                q = -q
            else:
                p = -p
            if 2 * p < min(3 * m * q - abs(tol * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = m
        else:
            d = e = m
        a, fa = b, fb
        b += d if abs(d) > tol else math.copysign(tol, m)
        fb = f(b)
    raise DesignError(f"the root finder did not converge in {maxiter} steps between {a:g} and {b:g}")
