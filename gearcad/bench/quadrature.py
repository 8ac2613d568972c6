"""Integrals: the closure turn of the centre-pivoted ellipse by every method, and the walker
paper's ratio constant by the paper's own method against the closed form."""

from __future__ import annotations

import math
import warnings

import numpy as np

from .timing import time_interleaved, time_once

__all__ = ["bench_quadrature"]


def bench_quadrature(quick: bool) -> list[dict]:
    """The centre-pivoted ellipse's closure turn ∫ r/(E − r) dφ at E = 40 mm by every method,
    and the walker's i by the paper's method against the closed form."""
    from numpy.polynomial.legendre import leggauss
    from scipy.integrate import quad

    from ..pitch import shapes
    from ..pitch.pair import angle_map

    curve = shapes.ellipse_centre(25.0, 15.0)
    e = 40.0
    rounds = 3 if quick else 7

    def f(p):
        r = curve.r(p)
        return r / (e - r)

    with warnings.catch_warnings():  # QUADPACK warns that it cannot prove 1e-14; it reaches it
        warnings.simplefilter("ignore")
        reference = quad(f, 0, math.pi / 2, epsabs=1e-14, epsrel=1e-14, limit=400)[0] * 4

    def trapezoid(n):
        return lambda: 2 * math.pi / n * float(np.sum(f(np.arange(n) * 2 * math.pi / n)))

    def gauss(n):
        x, w = leggauss(n)
        return lambda: math.pi * float(np.sum(w * f(math.pi * (x + 1))))

    def adaptive(eps):
        def run():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return quad(f, 0, 2 * math.pi, epsabs=eps, epsrel=eps, limit=400)[0]

        return run

    funcs = {}
    for n in [8, 32, 128] if quick else [4, 8, 16, 32, 64, 128, 256, 1024]:
        funcs[("trapezoid (periodic)", n)] = trapezoid(n)
        funcs[("Gauss-Legendre", n)] = gauss(n)
    for eps in [1e-6, 1e-10] if quick else [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]:
        funcs[("adaptive (QUADPACK)", eps)] = adaptive(eps)
    amap_key = ("gearcad (Chebyshev, Clenshaw-Curtis)", 0)
    funcs[amap_key] = lambda: angle_map(curve, e)
    timed = time_interleaved(funcs, rounds)
    rows = []
    for (method, n), t in timed.items():
        value = t.result.turn if (method, n) == amap_key else t.result
        rows.append(
            {
                "study": "quadrature",
                "method": method,
                "n": t.result.forward.degree if (method, n) == amap_key else n,
                "seconds": t.best,
                "seconds_median": t.median,
                "error": abs(value - reference),
            }
        )
    return rows + _walker_rows(quick, rounds)


def _walker_rows(quick: bool, rounds: int) -> list[dict]:
    """The walker's i by the paper's method and by gearcad's closed form, against the exact one."""
    from ..pitch import walker as W

    rows = []
    g = W.WalkerGeometry(75.0, 100.0, 50.0, 322.0)
    t = time_once(lambda: W.paper_ratio_constant(g), 1 if quick else 3)
    i_paper, _ = t.result
    exact = W.ratio_law(g).i
    rows.append(
        {
            "study": "walker-i",
            "method": "paper: trapezoid 0.1°/0.4°, successive approximation",
            "n": 0,
            "seconds": t.best,
            "seconds_median": t.median,
            "error": abs(i_paper - exact),
        }
    )
    t = time_once(lambda: W.ratio_law(g), rounds)
    rows.append(
        {
            "study": "walker-i",
            "method": "gearcad: closure, closed form",
            "n": 0,
            "seconds": t.best,
            "seconds_median": t.median,
            "error": abs(t.result.i - 2 * math.pi / (math.pi / 2 + 3 * g.b / g.K)),
        }
    )
    return rows
