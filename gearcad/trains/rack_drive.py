"""A wheel rolling on the ground, driven through an inclined rack (seed 000).

Wheel 1 (radius r) turns about a fixed axis; wheel 2 (radius R) rolls on the ground; a rack
(or thread) is tangent to both, inclined at β.  L and H are the horizontal and vertical
distances between the centres.  Projecting the closed contour gives (eq. 1)

    L = l·cos β − (R − r)·sin β,    H = l·sin β + (R − r)·cos β,

hence H·cos β − L·sin β = R − r (β in closed form, eq. 10), l = L·cos β + H·sin β and
l² = L² + H² − (R − r)² (the printed eq. 2 has + (R − r)²: it does not follow from eq. 1).
Rates: ω2 = (r/R)·ω1/(1 + cos β) (eq. 8), ω3 = β̇ = (r/l)·ω1·tan(β/2) (eq. 11) and
ε2 = (r/R)·[ε1/(1 + cos β) + ω1·ω3·sin β/(1 + cos β)²] — the printed eq. 9 lacks the square.

The motion law φ2(φ1) two ways: from the closed contour (eqs. 3, 5 with L1 = L − R·Δφ2),
which is explicit in β and inverted by a bracketed root finder; and by integrating eq. 8
with β updated from eq. 10 (an ODE solved with DOP853).  They must agree.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from ..roots import brentq

__all__ = [
    "RackDrive",
    "inclination",
    "paper_inclination",
    "rack_length",
    "paper_rack_length",
    "paper_eps2",
    "law_by_contour",
    "law_by_rates",
    "rates",
]


@dataclass(frozen=True)
class RackDrive:
    r: float
    R: float
    L: float
    H: float


def inclination(d: RackDrive, L=None) -> np.ndarray:
    """β from H·cos β − L·sin β = R − r (eq. 10, the root with the rack tangent as drawn)."""
    L = d.L if L is None else np.asarray(L, dtype=float)
    rho = np.hypot(L, d.H)
    ratio = (d.R - d.r) / rho
    if np.any(np.abs(ratio) > 1):
        raise DesignError("the rack cannot touch both wheels: (R − r) exceeds the distance between the centres")
    return np.arccos(ratio) - np.arctan2(L, d.H)


def paper_inclination(d: RackDrive) -> float:
    """Eq. 10 exactly as printed (for the tests): sin β from the quadratic."""
    L, H, k = d.L, d.H, d.R - d.r
    s = L * k / (L * L + H * H) * (math.sqrt(1 + (L * L + H * H) / (L * L) * (H * H / (k * k) - 1)) - 1)
    return math.asin(s)


def rack_length(d: RackDrive, L=None) -> np.ndarray:
    """l between the tangent points: L·cos β + H·sin β (from eq. 1)."""
    L = d.L if L is None else np.asarray(L, dtype=float)
    beta = inclination(d, L)
    return L * np.cos(beta) + d.H * np.sin(beta)


def paper_rack_length(d: RackDrive) -> float:
    """Eq. 2 as printed, l² = L² + H² + (R − r)², which eq. 1 does not give."""
    return math.sqrt(d.L**2 + d.H**2 + (d.R - d.r) ** 2)


def rates(d: RackDrive, L, *, omega1: float, eps1: float = 0.0):
    """(ω2, ω3, ε2) at horizontal distance L: eqs. 8, 11 and the derivative of eq. 8."""
    beta = inclination(d, L)
    length = rack_length(d, L)
    w2 = d.r / d.R * omega1 / (1 + np.cos(beta))
    w3 = d.r / length * omega1 * np.tan(beta / 2)
    e2 = d.r / d.R * (eps1 / (1 + np.cos(beta)) + omega1 * w3 * np.sin(beta) / (1 + np.cos(beta)) ** 2)
    return w2, w3, e2


def paper_eps2(d: RackDrive, L, *, omega1: float, eps1: float = 0.0):
    """Eq. 9 as printed: (r/R)·ε1/(1 + cos β) + (r/R)·ω1·ω3·sin β/(1 + cos β)."""
    beta = inclination(d, L)
    _, w3, _ = rates(d, L, omega1=omega1)
    return d.r / d.R * (eps1 / (1 + np.cos(beta)) + omega1 * w3 * np.sin(beta) / (1 + np.cos(beta)))


def _contour_state(d: RackDrive, beta1: float):
    """Driver and wheel turns (Δφ1, Δφ2) at which the rack is inclined at β1 (eqs. 3, 5)."""
    beta0 = float(inclination(d))
    l0 = float(rack_length(d))
    k = d.R - d.r
    L1 = (d.H * math.cos(beta1) - k) / math.sin(beta1) if abs(math.sin(beta1)) > 1e-300 else math.inf
    l1 = L1 * math.cos(beta1) + d.H * math.sin(beta1)
    dphi2 = (d.L - L1) / d.R
    dbeta = beta1 - beta0
    dphi1 = (l0 - l1 + d.R * (dphi2 + dbeta)) / d.r - dbeta
    return dphi1, dphi2


def law_by_contour(d: RackDrive, phi1: np.ndarray) -> np.ndarray:
    """φ2 at each φ1 from the closed-contour equations, by a bracketed root find on β."""
    beta0 = float(inclination(d))
    out = np.empty(len(phi1))
    for k, target in enumerate(phi1):
        if target == 0:
            out[k] = 0.0
            continue

        def miss(b, target=target):
            return _contour_state(d, b)[0] - target

        hi = beta0
        step = 1e-3
        while miss(hi) < 0:  # the wheel rolls towards wheel 1, so β grows
            hi = min(hi + step, math.pi / 2 - 1e-12)
            step *= 2
            if hi >= math.pi / 2 - 1e-12 and miss(hi) < 0:
                raise DesignError("the wheel would roll past the point where the rack stands vertical")
        beta = brentq(miss, beta0, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        out[k] = _contour_state(d, beta)[1]
    return out


def law_by_rates(d: RackDrive, phi1: np.ndarray) -> np.ndarray:
    """φ2 at each φ1 by integrating dφ2/dφ1 = (r/R)/(1 + cos β), β from eq. 10 at L − R·φ2."""

    from scipy.integrate import solve_ivp  # only the rolling wheel integrates: imported on use

    def rate(_, y):
        return [d.r / d.R / (1 + math.cos(float(inclination(d, d.L - d.R * y[0]))))]

    sol = solve_ivp(rate, (0.0, float(phi1[-1])), [0.0], method="DOP853", t_eval=phi1, rtol=1e-13, atol=1e-15)
    if not sol.success:
        raise DesignError(f"the motion law could not be integrated: {sol.message}")
    return sol.y[0]
