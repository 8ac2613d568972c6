"""Wheel-walker drive pair (seed 002, Skoybeda, Komyak, Zhukovets).

The carrier wheel H must turn so that ω/ω_H = r_H/r = i·u(φ)/K over each quarter turn
φ ∈ [−π/4, π/4], with u = K + 3b·cos 2φ and K = a − b + c; r + r_H = L.

Two constructions live here:

* the paper's: r_H from eq. 10, the pinion r(θ) from eq. 12 with the assumed mapping θ = 4φ,
  and i from equal arc lengths (eq. 15, trapezoid 0.1°/0.4°, successive approximation from
  i = 4) — kept for traceability and to reproduce the published i and Table 1;
* the one that rolls: the wheel is the ratio law k(φ) = i·u/K, and i follows from closure
  (the pinion turns exactly 2π per quarter turn of the wheel): ∫ k dφ = 2π per quarter,
  i = 2πK / ∫u dφ.  The pinion is then the computed conjugate of the wheel.

At the quarter-turn seams u has a V-shaped minimum (dr_H/dφ changes sign), so the wheel has
a corner; :func:`ratio_law` can replace sin 2|t| near each seam (t = distance to the seam) by
the even quartic that matches it to second order at |t| = w/2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .curve import TWO_PI, PitchCurve
from .shapes import from_ratio

__all__ = [
    "WalkerGeometry",
    "shoe_functions",
    "paper_wheel_radius",
    "paper_pinion_radius",
    "paper_arc_length_difference",
    "paper_ratio_constant",
    "paper_pinion",
    "RatioLaw",
    "ratio_law",
    "wheel_curve",
]

QUARTER = np.pi / 2


@dataclass(frozen=True)
class WalkerGeometry:
    """Leg geometry (mm): ``a`` hub–crank axes, ``b`` crank, ``c`` shoe post; ``L`` centres."""

    L: float
    a: float
    b: float
    c: float

    @property
    def K(self) -> float:
        return self.a - self.b + self.c


def shoe_functions(phi, g: WalkerGeometry) -> dict[str, np.ndarray]:
    """Eqs. 1–4 of the paper: Y1, Y2, axle height Y01 and the speed analogue dX01/dφ."""
    phi = np.asarray(phi, dtype=float)
    a, b, c = g.a, g.b, g.c
    y1 = 4 * b * np.cos(phi) - a
    y2 = a - 2 * b * (1 + np.cos(phi) ** 2) + c
    y01 = (a + y1) * np.cos(phi) - b * np.cos(2 * phi) + y2
    dx01 = (a + y1) * np.cos(phi) + 2 * b * np.cos(2 * phi) + y2
    return {"Y1": y1, "Y2": y2, "Y01": y01, "dX01": dx01}


def _u(phi, g: WalkerGeometry):
    return g.K + 3 * g.b * np.cos(2 * np.asarray(phi, dtype=float))


def paper_wheel_radius(phi, i: float, g: WalkerGeometry) -> np.ndarray:
    """Eq. 10: r_H(φ) = L·i·u/(K + i·u)."""
    u = _u(phi, g)
    return g.L * i * u / (g.K + i * u)


def paper_pinion_radius(theta, i: float, g: WalkerGeometry) -> np.ndarray:
    """Eq. 12: r(θ) = L·K/(K + i·(K + 3b·cos(θ/2))), i.e. eq. 11 with θ = 4φ."""
    return g.L * g.K / (g.K + i * _u(np.asarray(theta, dtype=float) / 4, g))


def _paper_wheel_slope(phi, i, g):
    """Eq. 13."""
    u = _u(phi, g)
    return -6 * g.L * i * g.b * g.K * np.sin(2 * phi) / (g.K + i * u) ** 2


def _paper_pinion_slope(theta, i, g):
    """Eq. 14."""
    u = _u(theta / 4, g)
    return 1.5 * g.L * i * g.b * g.K * np.sin(theta / 2) / (g.K + i * u) ** 2


def _trapezoid(values: np.ndarray, step: float) -> float:
    return float(step * (values.sum() - 0.5 * (values[0] + values[-1])))


def paper_arc_length_difference(
    i: float, g: WalkerGeometry, *, wheel_step_deg: float = 0.1, pinion_step_deg: float = 0.4
) -> float:
    """Eq. 15 by the paper's trapezoid rule: wheel quarter arc minus pinion arc, mm."""
    hw, hp = np.radians(wheel_step_deg), np.radians(pinion_step_deg)
    phi = np.linspace(-np.pi / 4, np.pi / 4, int(round(QUARTER / hw)) + 1)
    theta = np.linspace(-np.pi, np.pi, int(round(TWO_PI / hp)) + 1)
    wheel = np.hypot(paper_wheel_radius(phi, i, g), _paper_wheel_slope(phi, i, g))
    pinion = np.hypot(paper_pinion_radius(theta, i, g), _paper_pinion_slope(theta, i, g))
    return _trapezoid(wheel, phi[1] - phi[0]) - _trapezoid(pinion, theta[1] - theta[0])


def paper_ratio_constant(
    g: WalkerGeometry,
    *,
    start: float = 4.0,
    wheel_step_deg: float = 0.1,
    pinion_step_deg: float = 0.4,
) -> tuple[float, int]:
    """The paper's i: successive approximation (secant) on eq. 15 from i = 4.

    Returns (i, iterations).
    """

    def f(i):
        return paper_arc_length_difference(i, g, wheel_step_deg=wheel_step_deg, pinion_step_deg=pinion_step_deg)

    x0, x1 = start, start * 0.99
    f0, f1 = f(x0), f(x1)
    for n in range(1, 100):
        if f1 == f0:
            return x1, n
        x0, x1, f0 = x1, x1 - f1 * (x1 - x0) / (f1 - f0), f1
        f1 = f(x1)
        if abs(x1 - x0) <= 1e-13 * abs(x1):
            return x1, n
    raise RuntimeError("the paper's successive approximation did not converge")  # pragma: no cover


def paper_pinion(i: float, g: WalkerGeometry) -> PitchCurve:
    """The paper's pinion, eq. 12, as a mate curve: body angle ψ = π − θ, one lobe.

    The paper measures θ at the contact, so its θ = 0 (smallest radius) meets the wheel's
    φ = 0; in gearcad's mate convention that body point sits at ψ = π.
    """

    def theta(psi):
        return _centred(np.pi - np.asarray(psi, dtype=float), TWO_PI)

    def r(psi):
        return paper_pinion_radius(theta(psi), i, g)

    def dr(psi):
        return -_paper_pinion_slope(theta(psi), i, g)

    def d2r(psi):  # quotient rule on eq. 14; dθ/dψ = −1 twice gives +
        t = theta(psi)
        den = g.K + i * _u(t / 4, g)
        num = 1.5 * g.L * i * g.b * g.K
        dden = -1.5 * i * g.b * np.sin(t / 2)
        return num * (0.5 * np.cos(t / 2) * den - 2 * np.sin(t / 2) * dden) / den**3

    return PitchCurve(name="pinion (paper, θ = 4φ)", r=r, dr=dr, d2r=d2r, lobes=1, breaks=(0.0,))


def _centred(phi: np.ndarray, period: float) -> np.ndarray:
    """Reduce to [−period/2, period/2)."""
    return (phi + period / 2) % period - period / 2


@dataclass(frozen=True)
class RatioLaw:
    """The wheel's ratio law k(φ) = ω_pinion/ω_wheel = i·(K + 3b·G(φ))/K.

    G is cos 2φ on each quarter (a V at the seams), or the blended version.
    """

    g: WalkerGeometry
    i: float
    half_width: float
    """Half the blend width, rad of wheel angle; 0 for the paper's law with its corners."""
    poly: tuple[float, float, float]
    """(A, B, C) of the blend G = A + B·t² + C·t⁴ near a seam."""

    def shape(self, phi, order: int = 0) -> np.ndarray:
        """G(φ) (order 0) or its first / second derivative."""
        psi = _centred(np.asarray(phi, dtype=float), QUARTER)
        if order == 0:
            out = np.cos(2 * psi)
        elif order == 1:
            out = -2 * np.sin(2 * psi)
        else:
            out = -4 * np.cos(2 * psi)
        if self.half_width == 0:
            return out
        t = np.pi / 4 - np.abs(psi)  # distance to the nearest seam
        inside = t < self.half_width
        if np.any(inside):
            A, B, C = self.poly
            ti = t[inside]
            if order == 0:
                out[inside] = A + B * ti**2 + C * ti**4
            elif order == 1:  # dt/dφ = −sign(ψ)
                out[inside] = -np.sign(psi[inside]) * (2 * B * ti + 4 * C * ti**3)
            else:
                out[inside] = 2 * B + 12 * C * ti**2
        return out

    def k(self, phi):
        return self.i * (self.g.K + 3 * self.g.b * self.shape(phi)) / self.g.K

    def dk(self, phi):
        return self.i * 3 * self.g.b * self.shape(phi, 1) / self.g.K

    def d2k(self, phi):
        return self.i * 3 * self.g.b * self.shape(phi, 2) / self.g.K

    @property
    def breaks(self) -> tuple[float, ...]:
        seams = np.pi / 4 + QUARTER * np.arange(4)
        if self.half_width == 0:
            return tuple(float(s) for s in seams)
        return tuple(sorted(float(s + d) % TWO_PI for s in seams for d in (-self.half_width, self.half_width)))


def _blend(h: float) -> tuple[float, float, float]:
    """Even quartic matching sin 2t in value, slope and curvature at t = h."""
    if h == 0:
        return 0.0, 0.0, 0.0
    s, d, dd = np.sin(2 * h), 2 * np.cos(2 * h), -4 * np.sin(2 * h)
    C = (dd - d / h) / (8 * h * h)
    B = (d - 4 * C * h**3) / (2 * h)
    A = s - B * h * h - C * h**4
    return float(A), float(B), float(C)


def ratio_law(g: WalkerGeometry, *, blend_width: float = 0.0) -> RatioLaw:
    """The ratio law whose wheel closes 4:1 with its pinion, i from the closure condition.

    ∫ over a quarter of G is 1 for cos 2φ; the blend replaces sin 2t by the quartic on
    t < h at each of the quarter's two ends, changing the integral by 2·∫₀ʰ (quartic − sin 2t).
    """
    h = 0.5 * blend_width
    if not 0 <= h < np.pi / 8:
        raise ValueError(f"blend width must be in [0, 45°), got {np.degrees(blend_width):g}°")
    A, B, C = _blend(h)
    integral_g = 1.0 + 2 * ((A * h + B * h**3 / 3 + C * h**5 / 5) - (1 - np.cos(2 * h)) / 2)
    i = TWO_PI * g.K / (g.K * QUARTER + 3 * g.b * integral_g)
    return RatioLaw(g=g, i=float(i), half_width=h, poly=(A, B, C))


def wheel_curve(law: RatioLaw) -> PitchCurve:
    """The carrier wheel r_H = L·k/(1 + k): four lobes, corners or blends at the seams."""
    blend = f", seams blended over {np.degrees(2 * law.half_width):g}°" if law.half_width else ""
    return from_ratio(
        f"carrier wheel (i = {law.i:.6f}{blend})",
        law.k,
        law.dk,
        law.d2k,
        law.g.L,
        lobes=4,
        breaks=law.breaks,
    )
