"""Conjugate synthesis: the mate of a driver curve that rolls on it without slip.

Pivots sit ``E`` apart on the x axis, gear 1 at the origin, gear 2 at (E, 0).  The driver
turns clockwise by φ1, so the body point at polar angle φ1 is on the line of centres; the mate
turns counter-clockwise by φ2, so its body point at polar angle π − φ2 is there.  Rolling
without slip means ``r1(φ1) + r2(π − φ2) = E`` and ``dφ2/dφ1 = r1/(E − r1)`` (SPEC §1).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from math import gcd

import numpy as np

from ..errors import DesignError
from ..roots import brentq
from ..tolerances import DEFAULT, Tolerances
from . import chebyshev
from .curve import TWO_PI, PitchCurve, radius_range, segments, zoom_min

__all__ = [
    "turn_on_nodes",
    "AngleMap",
    "PairData",
    "ClaimData",
    "angle_map",
    "solve_center_distance",
    "mate_curve",
    "conjugate_pair",
    "rolling_residuals",
    "shape_difference",
    "identical_mate_claim",
]


@dataclass(frozen=True)
class AngleMap:
    """φ2(φ1) = ∫ r1/(E − r1) dφ1 held spectrally over one driver turn, extended periodically."""

    forward: chebyshev.Piecewise
    rate: chebyshev.Piecewise
    exact_rate: Callable[[np.ndarray], np.ndarray]
    """r1/(E − r1) from the driver curve itself: the derivative Newton steps use."""
    turn: float
    """φ2(2π): how far the mate turns while the driver turns once, rad."""

    def __call__(self, phi1) -> np.ndarray:
        phi1 = np.asarray(phi1, dtype=float)
        q = np.floor(phi1 / TWO_PI)
        return self.forward(phi1 - q * TWO_PI) + q * self.turn

    def slope(self, phi1) -> np.ndarray:
        phi1 = np.asarray(phi1, dtype=float)
        return self.rate(phi1 - np.floor(phi1 / TWO_PI) * TWO_PI)

    @cached_property
    def _table(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x = np.linspace(0.0, TWO_PI, 2049)
        return self.forward(x), x, 1.0 / self.exact_rate(x)

    def _guess(self, y: np.ndarray) -> np.ndarray:
        """Cubic Hermite interpolation of φ1(φ2) on the table, whose slopes are 1/k: error
        ~h⁴, so one Newton step usually reaches round-off."""
        ty, tx, slope = self._table
        j = np.clip(np.searchsorted(ty, y) - 1, 0, len(ty) - 2)
        h = ty[j + 1] - ty[j]
        t = (y - ty[j]) / h
        t2, t3 = t * t, t * t * t
        return (
            (2 * t3 - 3 * t2 + 1) * tx[j]
            + (t3 - 2 * t2 + t) * h * slope[j]
            + (-2 * t3 + 3 * t2) * tx[j + 1]
            + (t3 - t2) * h * slope[j + 1]
        )

    def inverse(self, phi2) -> np.ndarray:
        """φ1(φ2): Newton on the spectral map from a Hermite guess (quadratic convergence)."""
        phi2 = np.asarray(phi2, dtype=float)
        q = np.floor(phi2 / self.turn)
        y = phi2 - q * self.turn
        x = self._guess(y)
        for _ in range(8):
            step = (self.forward(x) - y) / self.exact_rate(x)
            x = np.clip(x - step, 0.0, TWO_PI)
            # quadratic convergence: after a step below 1e-9 the error is ~1e-18·|Φ''/Φ'|
            if np.max(np.abs(step), initial=0.0) < 1e-9:
                break
        return x + q * TWO_PI


def angle_map(curve: PitchCurve, center_distance: float, *, tol: Tolerances = DEFAULT) -> AngleMap:
    """The mate's angle as a function of the driver's for centre distance ``E``."""
    e = center_distance

    def rate(p):
        r = curve.r(p)
        return r / (e - r)

    fitted = chebyshev.fit(rate, segments(curve), rel_tol=tol.fit_rel)
    forward = fitted.integral()
    turn = float(forward(np.array([TWO_PI]))[0])
    return AngleMap(forward, fitted, rate, turn)


def turn_on_nodes(curve: PitchCurve, n: int):
    """Clenshaw–Curtis rule with n + 1 nodes per smooth piece for ∫ f(r(φ)) dφ over a turn."""
    edges = segments(curve)
    x = chebyshev.lobatto_points(n)
    k = np.arange(n + 1)
    even = k % 2 == 0
    moments = np.zeros(n + 1)
    moments[even] = 2.0 / (1.0 - k[even].astype(float) ** 2)
    radii = [curve.r(0.5 * (a + b) + 0.5 * (b - a) * x) for a, b in zip(edges[:-1], edges[1:])]
    halves = 0.5 * np.diff(edges)

    def turn(e: float) -> float:
        total = 0.0
        for r, h in zip(radii, halves):
            c = chebyshev.coefficients(r / (e - r))
            total += h * float(moments @ c)
        return total

    return turn


def solve_center_distance(curve: PitchCurve, target_turn: float, *, tol: Tolerances = DEFAULT) -> float:
    """Centre distance E at which the mate turns ``target_turn`` per driver turn.

    The turn ∫ r/(E − r) dφ falls monotonically from +∞ (E → r_max) to 0 (E → ∞), so the root
    is bracketed and found by Brent's method on a Clenshaw–Curtis rule; the rule is refined
    until the spectrally fitted angle map confirms closure.
    """
    if not target_turn > 0:
        raise DesignError(f"the mate's turn per driver turn must be positive, got {target_turn}")
    r_max = radius_range(curve)[1]
    n = 64
    while True:
        turn = turn_on_nodes(curve, n)
        lo = r_max * (1 + 1e-12) + 1e-300
        if turn(lo) - target_turn <= 0:
            if n >= 1 << 14:
                raise DesignError(
                    f"no centre distance closes the pair: the mate would have to turn "
                    f"{target_turn:.6g} rad per driver turn, more than the curve allows"
                )
            n *= 4
            continue
        hi = 2 * r_max
        while turn(hi) - target_turn > 0:
            hi *= 2
        e = brentq(lambda x: turn(x) - target_turn, lo, hi, xtol=1e-15 * hi, rtol=1e-15)
        closure = abs(angle_map(curve, e, tol=tol).turn - target_turn)
        if closure <= tol.closure_rad or n >= 1 << 14:
            return e
        n *= 4


def mate_curve(driver: PitchCurve, center_distance: float, amap: AngleMap, *, lobes: int, name: str = "") -> PitchCurve:
    """The curve r2(θ) = E − r1(φ1) with φ1 = φ2⁻¹(π − θ), derivatives by the chain rule."""
    e = center_distance
    last: list = [None, None]  # r, dr and d2r are usually asked at the same angles in turn

    def driver_angle(theta):
        theta = np.asarray(theta, dtype=float)
        if last[0] is not None and last[0].shape == theta.shape and np.array_equal(last[0], theta):
            return last[1]
        phi1 = amap.inverse(np.pi - theta)
        last[0], last[1] = theta.copy(), phi1
        return phi1

    def r(theta):
        return e - driver.r(driver_angle(theta))

    def dr(theta):
        p = driver_angle(theta)
        r1 = driver.r(p)
        return driver.dr(p) * (e - r1) / r1

    def d2r(theta):
        p = driver_angle(theta)
        r1, r1p, r1pp = driver.r(p), driver.dr(p), driver.d2r(p)
        h = e * (r1pp * r1 - r1p * r1p) / (r1 * r1) - r1pp
        return -h * (e - r1) / r1

    repeats = int(np.ceil(TWO_PI / amap.turn)) + 2
    seams = [float(b) for b in driver.breaks]
    mapped = amap(np.array(seams)) if seams else np.array([])
    breaks = [float(np.pi - m - q * amap.turn) % TWO_PI for m in mapped for q in range(-1, repeats)]
    probe = PitchCurve(name="", r=r, dr=dr, d2r=d2r, breaks=tuple(breaks))
    return PitchCurve(
        name=name or f"mate of {driver.name}",
        r=r,
        dr=dr,
        d2r=d2r,
        lobes=lobes,
        breaks=tuple(float(b) for b in segments(probe)[1:-1]),  # 0 is always a piece edge
    )


def rolling_residuals(
    gear1: PitchCurve, gear2: PitchCurve, center_distance: float, phi2_of, rate_of, phi1
) -> tuple[float, float]:
    """Largest contact residual |r1 + r2 − E| (mm) and slip |r1 − r2·dφ2/dφ1| (mm/rad).

    ``phi2_of`` and ``rate_of`` are the angle map the pair is assembled with — the computed
    conjugate map, or a paper's assumed one (the walker's θ = 4φ).
    """
    phi1 = np.asarray(phi1, dtype=float)
    r1 = gear1.r(phi1)
    r2 = gear2.r(np.pi - phi2_of(phi1))
    contact = float(np.max(np.abs(r1 + r2 - center_distance)))
    slip = float(np.max(np.abs(r1 - r2 * rate_of(phi1))))
    return contact, slip


@dataclass(frozen=True)
class PairData:
    """A pair of pitch curves that roll on each other, with its measured residuals."""

    gear1: PitchCurve
    gear2: PitchCurve
    center_distance: float
    lobes: tuple[int, int]
    angle_map: AngleMap
    closure_error: float
    """|φ2(2π) − 2π·n1/n2|, rad."""
    contact_residual: float
    """max |r1 + r2 − E| over a full cycle, mm."""
    slip_residual: float
    """max |r1 − r2·dφ2/dφ1| over a full cycle, mm per rad of driver."""

    @property
    def rolling_residual(self) -> float:
        return max(self.contact_residual, self.slip_residual)

    @property
    def cycle(self) -> float:
        """Driver angle after which the pair returns to its start, rad."""
        n1, n2 = self.lobes
        return TWO_PI * n2 / gcd(n1, n2)


def conjugate_pair(
    driver: PitchCurve,
    *,
    mate_lobes: int,
    center_distance: float | None = None,
    mate_name: str = "",
    tol: Tolerances = DEFAULT,
) -> PairData:
    """Synthesise the mate of ``driver`` with ``mate_lobes`` lobes.

    With ``center_distance=None`` it is solved from closure φ2(2π) = 2π·n1/n2; a given value
    is used as is and the closure error says whether the pair closes.
    """
    n1, n2 = driver.lobes, mate_lobes
    target = TWO_PI * n1 / n2
    if center_distance is None:
        center_distance = solve_center_distance(driver, target, tol=tol)
    amap = angle_map(driver, center_distance, tol=tol)
    mate = mate_curve(driver, center_distance, amap, lobes=n2, name=mate_name)
    cycle = TWO_PI * n2 / gcd(n1, n2)
    phi1 = np.linspace(0.0, cycle, 4097)
    contact, slip = rolling_residuals(driver, mate, center_distance, amap, amap.slope, phi1)
    return PairData(
        gear1=driver,
        gear2=mate,
        center_distance=float(center_distance),
        lobes=(n1, n2),
        angle_map=amap,
        closure_error=abs(amap.turn - target),
        contact_residual=contact,
        slip_residual=slip,
    )


def _best_rotation(misfit) -> tuple[float, float]:
    """min over δ of misfit(δ, stride), a vectorised max-norm misfit: a coarse pass over 180
    rotations on every 8th sample, then zooming at full resolution."""
    grid = np.linspace(0.0, TWO_PI, 180, endpoint=False)
    k = int(np.argmin(misfit(grid, 8)))
    x, f = zoom_min(
        lambda d: misfit(d, 1), grid[k] - grid[1], grid[k] + grid[1], float(grid[k]), float(grid[1]), rounds=4
    )
    return f, x % TWO_PI


def shape_difference(curve: PitchCurve, other: PitchCurve, samples: int = 1024) -> tuple[float, float]:
    """min over rotations δ of max_θ |other.r(θ) − curve.r(θ + δ)|: (mm, δ in rad)."""
    theta = np.linspace(0.0, TWO_PI, samples, endpoint=False)
    b = other.r(theta)

    def misfit(deltas, stride):
        t = theta[::stride]
        return np.max(np.abs(b[::stride] - curve.r(t[None, :] + np.asarray(deltas)[:, None])), axis=1)

    return _best_rotation(misfit)


@dataclass(frozen=True)
class ClaimData:
    """Check of a claim that a curve meshes with an identical copy at a given centre distance."""

    center_distance: float
    target_turn: float
    turn: float
    """How far the computed mate turns per driver turn at the claimed distance, rad."""
    shape_difference: float
    """How far the curve that really rolls differs from the claimed identical mate, mm."""
    holds: bool

    @property
    def shortfall(self) -> float:
        return self.target_turn - self.turn


def identical_mate_claim(curve: PitchCurve, center_distance: float, *, tol: Tolerances = DEFAULT) -> ClaimData:
    """Test 'the mate is the same curve at centre distance E' against closure and contact."""
    amap = angle_map(curve, center_distance, tol=tol)
    phi1 = np.linspace(0.0, TWO_PI, 1025)
    needed = center_distance - curve.r(phi1)  # the mate's radius the contact requires
    theta = np.pi - amap(phi1)

    def misfit(deltas, stride):
        t = theta[::stride]
        return np.max(np.abs(needed[::stride] - curve.r(t[None, :] + np.asarray(deltas)[:, None])), axis=1)

    diff, _ = _best_rotation(misfit)
    closure = abs(amap.turn - TWO_PI)
    return ClaimData(
        center_distance=center_distance,
        target_turn=TWO_PI,
        turn=amap.turn,
        shape_difference=diff,
        holds=closure <= tol.closure_rad and diff <= tol.rolling_mm,
    )
