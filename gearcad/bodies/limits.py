"""Seed 003: amplitude limits of the body against the roller radius r as well as m, and the
paper's statements about r (Gogolin, Kobylyansky et al., Figs. 1–2).

The body is the roller path P offset by r, so its curvature is κ_P/(1 − r·κ_P): it is convex
exactly where P is (a limit independent of r) until r·κ_P reaches 1 and the offset grows a cusp.
Loops (the paper's nodal points) come from the offset, so the loop-free ('simple') limit falls
fast with r.  The paper says "the roller radius does not affect the body's shape" and that at
a = 0.2 (m = 3) nodal points appear: :func:`radius_claim_check` and :func:`nodal_points_check`
give the numbers (units of R throughout).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.optimize import brentq, minimize_scalar
from scipy.spatial import cKDTree

from ..findings import amount, listed
from . import rollers as RB
from .claims import PAPER_M, paper_check

__all__ = [
    "PAPER_RADII",
    "AMPLITUDE_CAP",
    "amplitude_limit",
    "LimitTable",
    "amplitude_limit_table",
    "radius_effect",
    "radius_claim_check",
    "nodal_points_check",
    "shape_family",
]

PAPER_RADII = (0.0, 0.1, 0.2, 0.3, 0.4)
"""The roller radii of the paper's Figs. 1–2 (units of R)."""
TWO_PI = 2 * math.pi
AMPLITUDE_CAP = 1.0
"""Amplitudes are searched up to R: a body whose centre swings out to the roller circle is no
body.  A contour still simple there (the bare roller path of a vertical oscillation of odd m always is)
has no simple limit, reported as ``inf`` (``None`` in JSON)."""


def _json(values: np.ndarray) -> list:
    return [[None if math.isinf(x) else float(x) for x in row] for row in values]


@dataclass(frozen=True)
class LimitTable:
    """Largest amplitudes (units of R) keeping the contour convex / simple, per direction,
    frequency m and roller radius r: ``convex[direction]`` is an (len(m), len(r)) array."""

    m: tuple[int, ...]
    r: tuple[float, ...]
    convex: dict[str, np.ndarray]
    simple: dict[str, np.ndarray]

    def as_dict(self) -> dict:
        return {
            "m": list(self.m),
            "r": list(self.r),
            "convex": {d: _json(v) for d, v in self.convex.items()},
            "simple": {d: _json(v) for d, v in self.simple.items()},
        }


_swing = functools.lru_cache(maxsize=32)(RB.Swing)


def _kappa_at(direction: str, m: int, a: float, s: float) -> float:
    """Roller-path curvature (convex positive, R = 1) at one τ, in floats: the minimiser calls it often."""
    x1, y1, x2, y2 = math.cos(s), -math.sin(s), -math.sin(s), -math.cos(s)
    d1, d2 = a * m * math.cos(m * s), -a * m * m * math.sin(m * s)
    if direction == "horizontal":
        x1, x2 = x1 + d1, x2 + d2
    else:
        y1, y2 = y1 + d1, y2 + d2
    return -(x1 * y2 - y1 * x2) / math.hypot(x1, y1) ** 3


def _convex_margin(direction: str, m: int, r: float, a: float) -> float:
    """min over τ of κ_P and of 1/r − κ_P (roller-path curvature), each grid minimum refined by
    Brent's method so that the margin is exact to round-off, not to the grid."""
    swing = _swing(direction, m, R=1.0, samples=4096)
    tau = np.linspace(0, TWO_PI, 4096, endpoint=False)
    step = tau[1]
    grid = swing.kappa(a)
    margins = []
    for sign, offset in ((1.0, 0.0), (-1.0, 1 / r if r > 0 else math.inf)):
        if math.isinf(offset):
            continue
        k = int(np.argmin(offset + sign * grid))
        res = minimize_scalar(
            lambda s, sign=sign, offset=offset: offset + sign * _kappa_at(direction, m, a, s),
            bounds=(tau[k] - step, tau[k] + step),
            method="bounded",
            options={"xatol": 1e-12},
        )
        margins.append(float(res.fun))
    return min(margins)


@functools.lru_cache(maxsize=256)
def amplitude_limit(direction: str, m: int, *, r: float, test: str) -> float:
    """:func:`rollers.amplitude_limit` searched within ``AMPLITUDE_CAP`` (``inf`` if none below);
    the convex limit is then polished on the refined curvature margin (the grid's minimum is
    ~1e-7 high)."""
    if test == "simple" and RB.is_simple(RB.harmonic(direction, AMPLITUDE_CAP, m), r=r):
        return math.inf
    a0 = RB.amplitude_limit(direction, m, r=r, test=test, hi=AMPLITUDE_CAP)
    if test != "convex":
        return a0
    lo, hi = 0.999 * a0, 1.001 * a0
    if _convex_margin(direction, m, r, lo) <= 0 or _convex_margin(direction, m, r, hi) >= 0:
        return a0  # pragma: no cover - the grid value is within 0.1 % of the root
    return brentq(lambda a: _convex_margin(direction, m, r, a), lo, hi, xtol=1e-15)


def amplitude_limit_table(directions=("horizontal", "vertical"), ms=PAPER_M, radii=PAPER_RADII) -> LimitTable:
    """Exact convex and simple amplitude limits for every direction, m and roller radius r."""
    convex, simple = {}, {}
    for d in directions:
        convex[d] = np.array([[amplitude_limit(d, m, r=r, test="convex") for r in radii] for m in ms])
        simple[d] = np.array([[amplitude_limit(d, m, r=r, test="simple") for r in radii] for m in ms])
    return LimitTable(tuple(int(m) for m in ms), tuple(float(r) for r in radii), convex, simple)


def _normalised(points: np.ndarray) -> np.ndarray:
    """The contour scaled about the body centre to unit area-equivalent radius."""
    return points / math.sqrt(abs(shapely.Polygon(points).area) / math.pi)


def _hausdorff(p: np.ndarray, q: np.ndarray) -> float:
    """Hausdorff distance of two densely sampled closed curves (to the sample spacing)."""
    return float(max(cKDTree(q).query(p)[0].max(), cKDTree(p).query(q)[0].max()))


def _finite(x: float) -> float | None:
    return None if math.isinf(x) else x


def radius_effect(direction: str, amplitude: float, m: int, radii=PAPER_RADII, samples: int = 4096) -> list[dict]:
    """What the roller radius does to the body, one row per r (units of R).

    ``out_of_round`` is (ρmax − ρmin)/(ρmax + ρmin) of the distance from the body centre;
    ``shape_distance`` the Hausdorff distance between the contour and the roller path (r = 0),
    both scaled to unit area-equivalent radius — zero if r only scaled the body.
    """
    osc = RB.harmonic(direction, amplitude, m)
    tau = np.linspace(0, TWO_PI, samples, endpoint=False)
    reference = _normalised(RB.roller_path(osc, tau))
    rows = []
    for r in radii:
        pts = RB.contour(osc, tau, r=r)
        rho = np.hypot(*pts.T)
        simple = RB.is_simple(osc, r=r)
        rows.append(
            {
                "r": float(r),
                "convex": RB.is_convex(osc, r=r),
                "simple": simple,
                "out_of_round": float((rho.max() - rho.min()) / (rho.max() + rho.min())),
                "shape_distance": _hausdorff(reference, _normalised(pts)) if simple else None,
                "convex_limit": amplitude_limit(direction, m, r=r, test="convex"),
                "simple_limit": _finite(amplitude_limit(direction, m, r=r, test="simple")),
            }
        )
    return rows


def radius_claim_check(direction: str = "vertical", amplitude: float = 0.1, m: int = 3, radii=PAPER_RADII) -> dict:
    """'The roller radius does not affect the body's shape' (about Fig. 1), with the numbers."""
    rows = radius_effect(direction, amplitude, m, radii)
    simple = [math.inf if row["simple_limit"] is None else row["simple_limit"] for row in rows]
    convex = [row["convex_limit"] for row in rows]
    oor = [row["out_of_round"] for row in rows]
    message = (
        f"the roller radius changes the body ({direction}, m = {m}, a = {amplitude:g}): over r = "
        f"{rows[0]['r']:g}…{rows[-1]['r']:g} R the out-of-roundness goes {oor[0]:.4f}→{oor[-1]:.4f} and the "
        f"largest loop-free amplitude {amount(simple[0], '.4f', infinite='no limit')}→"
        f"{amount(simple[-1], '.4f', infinite='no limit')}; the convex ('oval') limit "
        f"{min(convex):.4f}…{max(convex):.4f} depends on r only where the offset grows a cusp"
    )
    return paper_check(
        "paper-claim",
        "the roller radius does not affect the body's shape",
        "no effect",
        {"rows": rows},
        max(simple) - min(simple) < 1e-6 and max(oor) - min(oor) < 1e-6,
        message,
    )


def nodal_points_check(direction: str = "vertical", m: int = 3, amplitude: float = 0.2, radii=PAPER_RADII) -> dict:
    """'At a = 0.2 nodal points appear on the contour' (m = 3, Fig. 1, all radii drawn)."""
    osc = RB.harmonic(direction, amplitude, m)
    looped = [float(r) for r in radii if not RB.is_simple(osc, r=r)]
    clean = [float(r) for r in radii if float(r) not in looped]
    return paper_check(
        "paper-claim",
        f"at a = {amplitude:g} (m = {m}) the contour has nodal points",
        "for every roller radius of the figure",
        {"looped_for_r": looped, "loop_free_for_r": clean},
        not clean,
        f"at a = {amplitude:g} ({direction}, m = {m}) the contour has loops only for r = {listed(looped)} R; "
        f"for r = {listed(clean)} R it has none",
    )


def shape_family(direction: str, m: int, amplitudes, radii, samples: int = 721) -> list[dict]:
    """Contours for the paper's Figs. 1–2: one entry per (amplitude, r) with its kind.

    ``kind`` is "convex" (the paper's 'oval'), "concave" (simple with concave stretches) or
    "looped" (self-crossing or cusped: the paper's nodal points).  ``points`` (n, 2) in units of
    R, counter-clockwise, closed (first point repeated).
    """
    tau = np.linspace(0, TWO_PI, samples)
    out = []
    for a in amplitudes:
        osc = RB.harmonic(direction, a, m)
        for r in radii:
            if not RB.is_simple(osc, r=r):
                kind = "looped"
            elif RB.is_convex(osc, r=r):
                kind = "convex"
            else:
                kind = "concave"
            out.append({"amplitude": float(a), "r": float(r), "kind": kind, "points": RB.contour(osc, tau, r=r)[::-1]})
    return out
