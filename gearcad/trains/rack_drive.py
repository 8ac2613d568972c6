"""A wheel rolling on the ground, driven through an inclined rack (seed 000).

Wheel 1 (radius r) turns about a fixed axis; wheel 2 (radius R) rolls on the ground; a rack
(or thread) is tangent to both, inclined at β.  L and H are the horizontal and vertical
distances between the centres.  Projecting the closed contour gives (eq. 1)

    L = l·cos β − (R − r)·sin β,    H = l·sin β + (R − r)·cos β,

hence H·cos β − L·sin β = R − r (β in closed form, eq. 10), l = L·cos β + H·sin β and
l² = L² + H² − (R − r)² (the printed eq. 2 has + (R − r)²: it does not follow from eq. 1).
Rates: ω2 = (r/R)·ω1/(1 + cos β) (eq. 8), ω3 = β̇ = (r/l)·ω1·tan(β/2) (eq. 11) and
ε2 = (r/R)·[ε1/(1 + cos β) + ω1·ω3·sin β/(1 + cos β)²] — the printed eq. 9 lacks the square.

Eq. 10 as printed, sin β = L(R − r)/(L² + H²)·[√(1 + (L² + H²)/L²·(H²/(R − r)² − 1)) − 1], is
the quadratic's root with the square root's sign taken as sgn(L·(R − r)): it is the rack's
root only where L·(R − r)·H > 0 — with R < r (or the driver behind or below the wheel) it is
the other root, the lower common tangent, which runs under the wheels.  It is undefined for
L = 0 or R = r.  The paper's second method (eqs. 12–13: equal projections of the velocities
of the tangent points A and B on the rack, and the rack's instantaneous centre) is
:func:`velocity_projections`, an independent check of eqs. 8 and 11.

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
    "contour_state",
    "inclination",
    "paper_inclination",
    "rack_length",
    "paper_rack_length",
    "paper_eps2",
    "law_by_contour",
    "law_by_rates",
    "rates",
    "inclination_roots",
    "paper_inclination_at",
    "paper_root_is_right",
    "eq10_check",
    "Projections",
    "velocity_projections",
    "projection_check",
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


def contour_state(d: RackDrive, beta1: float):
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
            return contour_state(d, b)[0] - target

        hi = beta0
        step = 1e-3
        while miss(hi) < 0:  # the wheel rolls towards wheel 1, so β grows
            hi = min(hi + step, math.pi / 2 - 1e-12)
            step *= 2
            if hi >= math.pi / 2 - 1e-12 and miss(hi) < 0:
                raise DesignError("the wheel would roll past the point where the rack stands vertical")
        beta = brentq(miss, beta0, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        out[k] = contour_state(d, beta)[1]
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


def inclination_roots(d: RackDrive, L=None) -> tuple[np.ndarray, np.ndarray]:
    """Both roots of H·cos β − L·sin β = R − r: the rack's (upper common tangent, as drawn)
    and the other one (lower common tangent), each in (−π, π]."""
    L = d.L if L is None else np.asarray(L, dtype=float)
    rho = np.hypot(L, d.H)
    ratio = (d.R - d.r) / rho
    if np.any(np.abs(ratio) > 1):
        raise DesignError("the rack cannot touch both wheels: (R − r) exceeds the distance between the centres")
    gamma = np.arctan2(L, d.H)
    upper = np.arccos(ratio) - gamma
    lower = -np.arccos(ratio) - gamma
    return np.angle(np.exp(1j * upper)), np.angle(np.exp(1j * lower))


def paper_inclination_at(d: RackDrive, L=None) -> np.ndarray:
    """Eq. 10 as printed, vectorised over L; NaN where it is undefined (L = 0 or R = r)."""
    L = np.atleast_1d(np.asarray(d.L if L is None else L, dtype=float))
    k = d.R - d.r
    out = np.full(L.shape, np.nan)
    if k == 0:
        return out
    ok = L != 0
    Lo = L[ok]
    rho2 = Lo * Lo + d.H * d.H
    s = Lo * k / rho2 * (np.sqrt(1 + rho2 / (Lo * Lo) * (d.H * d.H / (k * k) - 1)) - 1)
    out[ok] = np.arcsin(np.clip(s, -1.0, 1.0))
    return out


def paper_root_is_right(d: RackDrive, L=None) -> np.ndarray:
    """Where the printed eq. 10 gives the rack's root: L·(R − r)·H > 0."""
    L = np.asarray(d.L if L is None else L, dtype=float)
    return L * (d.R - d.r) * d.H > 0


def eq10_check(d: RackDrive, L_values) -> dict:
    """Eq. 10 as printed against the rack's β over the horizontal distances ``L_values`` (mm).

    Report-ready: the largest |Δβ| (rad), the L range where the printed form picks the other
    root or is undefined, and whether it holds over the whole range.
    """
    L_values = np.asarray(L_values, dtype=float)
    beta, other = inclination_roots(d, L_values)
    printed = paper_inclination_at(d, L_values)
    gap = np.abs(printed - beta)
    wrong = ~np.isfinite(printed) | (gap > 1e-9)
    on_other = np.isfinite(printed) & (np.abs(np.sin(printed) - np.sin(other)) < 1e-9) & wrong
    where = L_values[wrong]
    holds = not bool(np.any(wrong))
    parts = []
    if np.any(on_other):
        parts.append(
            f"for L in [{L_values[on_other].min():g}, {L_values[on_other].max():g}] mm it gives the other root "
            f"(the lower common tangent, under the wheels), off by up to {np.degrees(np.max(gap[on_other])):.3f}°"
        )
    if np.any(~np.isfinite(printed)):
        parts.append("it is undefined at L = 0" if d.R != d.r else "it is undefined for R = r")
    message = (
        "printed eq. 10 gives the rack's inclination over the whole range"
        if holds
        else f"printed eq. 10 takes the square root with the sign of L·(R − r) (R − r = {d.R - d.r:g} mm, "
        f"H = {d.H:g} mm): " + "; ".join(parts) + ". The rack's root is "
        "sin β = (H·√(L² + H² − (R − r)²) − L(R − r))/(L² + H²)"
    )
    return {
        "code": "paper-root",
        "claim": "eq. 10: sin β in closed form",
        "holds": holds,
        "largest_difference_rad": float(np.nanmax(np.where(np.isfinite(printed), gap, np.nan), initial=0.0)),
        "wrong_for_L": [float(where.min()), float(where.max())] if where.size else None,
        "undefined": bool(np.any(~np.isfinite(printed))),
        "message": message,
    }


@dataclass(frozen=True)
class Projections:
    """The rates from the paper's second method (eqs. 12–13), in the fixed frame: wheel 2 at
    the origin rolling on y = −R, wheel 1 at (L, H), both turning clockwise (ω > 0)."""

    omega2: np.ndarray
    """From v_A·u = v_B·u (eq. 13), rad/s."""
    omega3: np.ndarray
    """The rack's counter-clockwise rate about its instantaneous centre, rad/s."""
    centre: np.ndarray
    """(n, 2) the rack's instantaneous centre of velocities, mm (NaN where it translates)."""
    A: np.ndarray
    """(n, 2) tangent point on wheel 2, mm."""
    B: np.ndarray
    """(n, 2) tangent point on wheel 1, mm."""


def velocity_projections(d: RackDrive, L, *, omega1: float) -> Projections:
    """ω2 and ω3 from velocities, not from eqs. 8 and 11 (the paper's eqs. 12–13 and the rack's
    instantaneous centre).

    The rack is tangent above both wheels at A = C2 + R·n and B = C1 + r·n (n its upward normal,
    u = (cos β, sin β) along it).  B moves with wheel 1: v_B = ω1 × (B − C1); A moves with wheel
    2, v_A = v_C2 + ω2 × (A − C2), v_C2 = (ω2·R, 0).  The rack is rigid: v_A·u = v_B·u fixes ω2
    (eq. 13), and its instantaneous centre P is where the normals to v_A at A and to v_B at B
    meet; ω3 = v_B·(ẑ × (B − P))/|B − P|².
    """
    L = np.atleast_1d(np.asarray(L, dtype=float))
    beta = np.atleast_1d(inclination(d, L))
    u = np.column_stack([np.cos(beta), np.sin(beta)])
    n = np.column_stack([-np.sin(beta), np.cos(beta)])
    C1 = np.column_stack([L, np.full_like(L, d.H)])
    A, B = d.R * n, C1 + d.r * n

    def cw(omega, arm):  # velocity of a point at ``arm`` from the centre, clockwise rate ω
        return omega * np.column_stack([arm[:, 1], -arm[:, 0]])

    v_B = cw(omega1, B - C1)
    # v_A = ω2·[(R, 0) + cw(1, A − C2)] is linear in ω2
    unit_A = np.column_stack([np.full_like(L, d.R), np.zeros_like(L)]) + cw(1.0, A)
    omega2 = np.einsum("ij,ij->i", v_B, u) / np.einsum("ij,ij->i", unit_A, u)
    v_A = omega2[:, None] * unit_A
    # P = A + s·perp(v_A) = B + t·perp(v_B): solve the 2×2 system for (s, t)
    perp_A = np.column_stack([-v_A[:, 1], v_A[:, 0]])
    perp_B = np.column_stack([-v_B[:, 1], v_B[:, 0]])
    rhs = B - A
    det = perp_A[:, 0] * -perp_B[:, 1] + perp_A[:, 1] * perp_B[:, 0]
    # parallel velocities (a horizontal rack translates): no finite centre, ω3 = 0
    turning = (
        np.abs(det) > 1e-12 * np.einsum("ij,ij->i", perp_A, perp_A) ** 0.5 * np.einsum("ij,ij->i", v_B, v_B) ** 0.5
    )
    safe = np.where(turning, det, 1.0)
    s = (rhs[:, 0] * -perp_B[:, 1] + rhs[:, 1] * perp_B[:, 0]) / safe
    P = np.where(turning[:, None], A + s[:, None] * perp_A, np.nan)
    arm = np.where(turning[:, None], B - P, 1.0)
    omega3 = np.where(
        turning,
        np.einsum("ij,ij->i", v_B, np.column_stack([-arm[:, 1], arm[:, 0]])) / np.einsum("ij,ij->i", arm, arm),
        0.0,
    )
    return Projections(omega2, omega3, P, A, B)


def projection_check(d: RackDrive, L_values, *, omega1: float) -> dict:
    """Eqs. 8 and 11 against the velocity projections over ``L_values``: report-ready."""
    L_values = np.asarray(L_values, dtype=float)
    proj = velocity_projections(d, L_values, omega1=omega1)
    w2, w3, _ = rates(d, L_values, omega1=omega1)
    turning = np.abs(w3) > 1e-12 * abs(omega1)  # a horizontal rack has no finite centre
    gap2 = float(np.max(np.abs(proj.omega2 - w2)))
    gap3 = float(np.max(np.abs(proj.omega3[turning] - w3[turning]), initial=0.0))
    scale = float(np.max(np.abs(w2)))
    return {
        "claim": "eqs. 12–13: ω2 from the projections of v_A and v_B, ω3 from the rack's instantaneous centre",
        "omega2_difference": gap2,
        "omega3_difference": gap3,
        "holds": gap2 <= 1e-12 * scale and gap3 <= 1e-12 * scale,
    }
