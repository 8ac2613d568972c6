"""A body rolling on three rollers (seed 003, Gogolin, Kobylyansky et al.).

Lengths are in units of R, the radius of the circle through the three roller centres.  In the
body's frame a roller centre traces P(τ) = (R·sin τ + f(τ), R·cos τ + g(τ)); the body contour
is P moved by the roller radius r along the unit normal (R·sin τ − g'(τ), R·cos τ + f'(τ))/W
towards the body (eq. 3; the printed equation lost the factor r).  The three rollers touch the
body together only if f and g repeat every 2π/3, i.e. every harmonic order is a multiple of 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from ..roots import brentq

__all__ = [
    "Oscillation",
    "harmonic",
    "contour",
    "roller_path",
    "contour_curvature",
    "is_convex",
    "is_simple",
    "amplitude_limit",
    "Swing",
    "point_motion",
    "centre_extremes",
]


@dataclass(frozen=True)
class Oscillation:
    """f(τ) = Σ fc_j·cos jτ + fs_j·sin jτ, g likewise: tuples of (order, cos, sin)."""

    f: tuple[tuple[int, float, float], ...] = ()
    g: tuple[tuple[int, float, float], ...] = ()

    def check(self) -> None:
        for name, terms in (("f", self.f), ("g", self.g)):
            for order, *_ in terms:
                if order % 3:
                    raise DesignError(
                        f"body.{name} has a harmonic of order {order}: the three rollers touch the body "
                        "together only if the oscillation repeats every 120° (orders that are multiples of 3)"
                    )

    def scaled(self, factor: float) -> Oscillation:
        return Oscillation(
            tuple((j, c * factor, s * factor) for j, c, s in self.f),
            tuple((j, c * factor, s * factor) for j, c, s in self.g),
        )


def harmonic(direction: str, amplitude: float, m: int) -> Oscillation:
    """The paper's harmonic oscillations: horizontal f = a·sin mτ, or vertical g = a·sin mτ."""
    term = ((m, 0.0, amplitude),)
    return Oscillation(f=term) if direction == "horizontal" else Oscillation(g=term)


def _series(terms, t, derivative: int = 0) -> np.ndarray:
    out = np.zeros_like(t, dtype=float)
    for j, c, s in terms:
        # d^k/dt^k of c·cos jt + s·sin jt
        phase = derivative * math.pi / 2
        out += j**derivative * (c * np.cos(j * t + phase) + s * np.sin(j * t + phase))
    return out


def roller_path(osc: Oscillation, tau, *, R: float = 1.0) -> np.ndarray:
    """The roller centre's path in the body frame, P(τ) = (R·sin τ + f, R·cos τ + g): (n, 2)."""
    tau = np.asarray(tau, dtype=float)
    return np.column_stack([R * np.sin(tau) + _series(osc.f, tau), R * np.cos(tau) + _series(osc.g, tau)])


def contour(osc: Oscillation, tau, *, r: float, R: float = 1.0) -> np.ndarray:
    """Body contour points at parameters τ: (n, 2), units of R's length."""
    tau = np.asarray(tau, dtype=float)
    f, g = _series(osc.f, tau), _series(osc.g, tau)
    f1, g1 = _series(osc.f, tau, 1), _series(osc.g, tau, 1)
    nx, ny = R * np.sin(tau) - g1, R * np.cos(tau) + f1
    w = np.hypot(nx, ny)
    return np.column_stack([R * np.sin(tau) + f - r * nx / w, R * np.cos(tau) + g - r * ny / w])


def contour_curvature(osc: Oscillation, tau, *, r: float, R: float = 1.0) -> np.ndarray:
    """Signed curvature of the contour (positive where convex, for the clockwise-in-τ path),
    from the roller-centre path P: the offset by r inwards has radius ρ_P − r."""
    tau = np.asarray(tau, dtype=float)
    x1 = R * np.cos(tau) + _series(osc.f, tau, 1)
    y1 = -R * np.sin(tau) + _series(osc.g, tau, 1)
    x2 = -R * np.sin(tau) + _series(osc.f, tau, 2)
    y2 = -R * np.cos(tau) + _series(osc.g, tau, 2)
    speed = np.hypot(x1, y1)
    kappa_p = -(x1 * y2 - y1 * x2) / speed**3  # P runs clockwise: make convex positive
    return kappa_p / (1 - r * kappa_p)


def is_convex(osc: Oscillation, *, r: float, R: float = 1.0, samples: int = 4096) -> bool:
    tau = np.linspace(0, 2 * math.pi, samples, endpoint=False)
    tau_p = np.asarray(tau)
    x1 = R * np.cos(tau_p) + _series(osc.f, tau_p, 1)
    y1 = -R * np.sin(tau_p) + _series(osc.g, tau_p, 1)
    x2 = -R * np.sin(tau_p) + _series(osc.f, tau_p, 2)
    y2 = -R * np.cos(tau_p) + _series(osc.g, tau_p, 2)
    kappa_p = -(x1 * y2 - y1 * x2) / np.hypot(x1, y1) ** 3
    # convex contour: the roller path is convex and the offset keeps it so (no cusp: r·κ_P < 1)
    return bool(np.all(kappa_p > 0) and np.all(r * kappa_p < 1))


def is_simple(osc: Oscillation, *, r: float, R: float = 1.0, samples: int = 4096) -> bool:
    """No self-intersection and no cusp of the roller offset (1 − r·κ_P stays positive)."""
    tau = np.linspace(0, 2 * math.pi, samples, endpoint=False)
    x1 = R * np.cos(tau) + _series(osc.f, tau, 1)
    y1 = -R * np.sin(tau) + _series(osc.g, tau, 1)
    x2 = -R * np.sin(tau) + _series(osc.f, tau, 2)
    y2 = -R * np.cos(tau) + _series(osc.g, tau, 2)
    kappa_p = -(x1 * y2 - y1 * x2) / np.hypot(x1, y1) ** 3
    if np.any(r * kappa_p >= 1):
        return False
    return bool(shapely.LinearRing(contour(osc, tau, r=r, R=R)).is_simple)


class Swing:
    """The roller path of the harmonic oscillation a·sin mτ as base + a·term on a fixed τ grid:
    the amplitude searches evaluate it for many a, so the trigonometry is done once."""

    def __init__(self, direction: str, m: int, *, R: float, samples: int):
        tau = np.linspace(0, 2 * math.pi, samples, endpoint=False)
        s, c, sm = np.sin(tau), np.cos(tau), np.sin(m * tau)
        # (P, P', P'') of the round path, then of the term on its axis (x horizontal, y vertical)
        self.base = (np.array([R * s, R * c]), np.array([R * c, -R * s]), np.array([-R * s, -R * c]))
        axis = 0 if direction == "horizontal" else 1
        self.term = tuple(np.zeros((2, samples)) for _ in range(3))
        for k, values in enumerate((sm, m * np.cos(m * tau), -m * m * sm)):
            self.term[k][axis] = values
        for array in (*self.base, *self.term):  # shared by every search that reuses this swing
            array.flags.writeable = False

    def path(self, a: float, order: int = 0) -> np.ndarray:
        return self.base[order] + a * self.term[order]

    def kappa(self, a: float) -> np.ndarray:
        """Roller-path curvature, convex positive (as :func:`contour_curvature` at r = 0)."""
        (x1, y1), (x2, y2) = self.path(a, 1), self.path(a, 2)
        return -(x1 * y2 - y1 * x2) / np.hypot(x1, y1) ** 3

    def is_simple(self, a: float, r: float) -> bool:
        """:func:`is_simple` of this oscillation at amplitude a."""
        if np.any(r * self.kappa(a) >= 1):
            return False
        (x, y), (x1, y1) = self.path(a), self.path(a, 1)
        nx, ny = -y1, x1  # the normal (R·sin τ − g', R·cos τ + f') towards the body
        w = np.hypot(nx, ny)
        return bool(shapely.LinearRing(np.column_stack([x - r * nx / w, y - r * ny / w])).is_simple)


def amplitude_limit(direction: str, m: int, *, r: float, test: str, R: float = 1.0, hi: float = 1.0) -> float:
    """The largest amplitude a keeping the contour convex (``test="convex"``) or simple.

    Convexity: the smallest curvature of the roller path is continuous in a, so its zero is
    found by Brent's method on a bracket.  Simplicity is a yes/no test: bisection to 1e-10.
    """
    if test == "convex":
        swing = Swing(direction, m, R=R, samples=8192)

        def margin(a):
            kappa_p = swing.kappa(a)
            return float(min(np.min(kappa_p), np.min(1 / r - kappa_p) if r > 0 else np.inf))

        while margin(hi) > 0:
            hi *= 2
        return brentq(margin, 0.0, hi, xtol=1e-13)
    swing = Swing(direction, m, R=R, samples=4096)
    lo = 0.0
    while swing.is_simple(hi, r):
        lo, hi = hi, hi * 2
    while hi - lo > 1e-10:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if swing.is_simple(mid, r) else (lo, mid)
    return lo


def point_motion(osc: Oscillation, x1: float, y1: float, *, w: float, t):
    """Position, velocity, acceleration of the body point (x1, y1) at uniform rotation φ = w·t
    (eqs. 5–8): x = (x1 − f)cos φ − (y1 − g)sin φ, y = (x1 − f)sin φ + (y1 − g)cos φ."""
    t = np.asarray(t, dtype=float)
    phi = w * t
    u = x1 - _series(osc.f, phi)
    v = y1 - _series(osc.g, phi)
    du, dv = -w * _series(osc.f, phi, 1), -w * _series(osc.g, phi, 1)
    ddu, ddv = -w * w * _series(osc.f, phi, 2), -w * w * _series(osc.g, phi, 2)
    c, s = np.cos(phi), np.sin(phi)
    pos = np.column_stack([u * c - v * s, u * s + v * c])
    vel = np.column_stack([du * c - dv * s - w * (u * s + v * c), du * s + dv * c + w * (u * c - v * s)])
    acc = np.column_stack(
        [
            ddu * c - ddv * s - 2 * w * (du * s + dv * c) - w * w * (u * c - v * s),
            ddu * s + ddv * c + 2 * w * (du * c - dv * s) - w * w * (u * s + v * c),
        ]
    )
    return pos, vel, acc


def centre_extremes(a: float, m: int, w: float) -> tuple[float, float]:
    """The paper's closed forms for the centre: Vmax = a·m·w, Amax = a·w²(m² + 1)."""
    return a * m * w, a * w * w * (m * m + 1)
