"""A ratio law from a required motion: the smoothest closing law within a stated error and limits.

The user gives the follower's angle ψ(φ) (or the speed ratio k = ω2/ω1) at n equal steps of
the driver's angle over one turn.  A pair that closes turns the follower n1/n2 of a turn per
driver turn, so ψ(φ) = (n1/n2)·φ + p(φ) with p periodic (period 2π/n1 for n1 lobes); p is
held by its Fourier series (the samples' FFT: spectrally accurate for smooth periodic data).
The *smoothest* law is the series cut at the lowest order M whose motion error — the largest
|ψ_law − ψ_given| on the samples — is within the tolerance, among the orders whose law stays
within the limits that let teeth be cut: a ratio range (both pitch radii r1 = E·k/(1 + k) and
E − r1 must reach the teeth's roots and keep a wall round the pivot) and a smallest radius of
curvature (convex stretches of both gears, where a rack cuts without undercut).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from .curve import TWO_PI, harmonic_series

__all__ = ["MotionLimits", "MotionFit", "fit_motion", "follower_from_ratio", "law_functions", "smoothest_law"]

GRID = 4096
"""Points per turn on which limits are checked: the laws kept are of order ≤ n/2 ≤ a few
hundred, so 4096 points resolve their extremes to well under a per cent of the curvature."""


MOST_ORDER = 360
"""Highest order of a law tried: no tooth follows a finer wiggle (the limit radii given as samples
have too), and GRID resolves the extremes of every law up to it."""


def _kept(spectrum: np.ndarray, lobes: int, order: int) -> np.ndarray:
    """The law's spectrum of order ``order``: the orders that are multiples of ``lobes``, up to it."""
    keep = np.zeros(len(spectrum), dtype=complex)
    keep[lobes : order + 1 : lobes] = spectrum[lobes : order + 1 : lobes]
    return keep


@dataclass(frozen=True)
class MotionLimits:
    """What teeth need of the law: k within ``ratio`` and radius of curvature ≥ ``curvature_radius``."""

    ratio: tuple[float, float]
    curvature_radius: float = 0.0
    why: str = ""
    """Where the ratio limit comes from, for messages."""


@dataclass(frozen=True)
class MotionFit:
    """The law kept: k(φ) = mean + Σ (c_j cos jφ + s_j sin jφ), and what it achieves."""

    mean: float
    harmonics: tuple[tuple[int, float, float], ...]
    order: int
    error: float
    """Largest |ψ_law − ψ_given| on the samples, rad."""
    ratio_range: tuple[float, float]
    min_curvature_radius: float
    """Smallest radius of curvature on convex stretches of either gear, mm."""


def follower_from_ratio(ratio: np.ndarray) -> np.ndarray:
    """ψ at the samples' angles from k at the same angles (ψ(0) = 0): the spectral integral of the
    samples' trigonometric interpolant, its mean turning ψ by mean·φ."""
    n = len(ratio)
    spectrum = np.fft.rfft(ratio) / n
    m = np.arange(len(spectrum))
    phi = TWO_PI * np.arange(n) / n
    integral = np.zeros_like(spectrum)
    integral[1:] = spectrum[1:] / (1j * m[1:])
    if n % 2 == 0:
        integral[-1] = 0.0  # the Nyquist term's integral is not determined by the samples
    p = np.fft.irfft(integral * n, n)
    return spectrum[0].real * phi + p - p[0]


def _curvature_radii(r, dr, d2r) -> np.ndarray:
    """Radius of curvature of a polar curve (inf where straight, negative where concave)."""
    num = r * r + 2 * dr * dr - r * d2r
    with np.errstate(divide="ignore"):
        return (r * r + dr * dr) ** 1.5 / num


def _law_measures(mean: float, spectrum: np.ndarray, e: float) -> tuple[float, float, float]:
    """(k_min, k_max, smallest convex radius of curvature of driver and mate) on the grid, for
    k = mean + p' with p's kept spectrum (rfft/n): three inverse FFTs instead of a sum per order."""
    m = np.arange(len(spectrum))
    padded = np.zeros(GRID // 2 + 1, dtype=complex)

    def on_grid(power: int) -> np.ndarray:
        padded[: len(spectrum)] = spectrum * (1j * m) ** power
        return np.fft.irfft(padded * GRID, GRID)

    k, dk, d2k = mean + on_grid(1), on_grid(2), on_grid(3)
    if k.min() <= 0:
        return float(k.min()), float(k.max()), 0.0
    r1 = e * k / (1 + k)
    dr1 = e * dk / (1 + k) ** 2
    d2r1 = e * (d2k * (1 + k) - 2 * dk * dk) / (1 + k) ** 3
    # the mate, r2(θ) = E − r1 with dθ/dφ = k: d/dθ = (1/k)·d/dφ
    r2, dr2 = e - r1, -dr1 / k
    d2r2 = (-d2r1 / k + dr1 * dk / k**2) / k
    rho = np.concatenate([_curvature_radii(r1, dr1, d2r1), _curvature_radii(r2, dr2, d2r2)])
    convex = rho[rho > 0]
    return float(k.min()), float(k.max()), float(convex.min()) if len(convex) else math.inf


def _no_law(key: str, best, limits: MotionLimits, tolerance: float, given, *, capped: bool, max_order: int):
    """The refusal when no law within the limits meets the tolerance: the best one's error, what
    the teeth allow and the ratios the motion asks for."""
    lo, hi = limits.ratio
    achievable = (
        f"the best law within them misses it by {math.degrees(best.error):.4g}° (order {best.order}"
        + (f"; orders above {max_order} are not tried: no tooth follows a finer wiggle)" if capped else ")")
        if best is not None
        else "no law within them exists"
    )
    allowed = (
        f"the smallest ratio the teeth allow is {lo:.4g} (the largest {hi:.4g}; {limits.why})"
        if lo <= hi
        else f"the teeth allow no ratio ({limits.why})"
    )
    return DesignError(
        f"{key}: no closing ratio law meets the motion within {math.degrees(tolerance):g}° and the limits teeth "
        f"need — {achievable}; {allowed}"
        + (f", curvature radius ≥ {limits.curvature_radius:.4g} mm" if limits.curvature_radius > 0 else "")
        + f"; the motion asks for ratios from about {given.min():.4g} to {given.max():.4g}"
    )


def _follower_sense(psi: np.ndarray) -> np.ndarray:
    """ψ given in the driver's sense of rotation (the follower, turning the other way, goes
    negative) is the same motion: the law wants ψ in the follower's own sense."""
    return -psi if len(psi) > 1 and psi[-1] < psi[0] else psi


def fit_motion(
    psi: np.ndarray,
    *,
    lobes: int,
    mate_lobes: int,
    center_distance: float,
    tolerance: float,
    limits: MotionLimits,
    key: str,
    max_order: int = MOST_ORDER,
) -> MotionFit:
    """The smoothest closing law for follower angles ``psi`` (rad) at φ = 2πj/n.

    ψ is measured in the follower's own sense of rotation (it grows as the driver turns); angles
    measured in the driver's sense (the follower, turning the other way, going negative: ψ falls)
    are the same motion and are taken as −ψ.

    Laws of order up to ``max_order`` are tried (each in O(n log n) time and O(n) memory: the
    100,000 samples a profile may give take about a second).  Raises :class:`DesignError`
    naming ``key`` with the best error the limits allow when no law within them meets
    ``tolerance`` (rad).
    """
    psi = _follower_sense(np.asarray(psi, dtype=float))
    n = len(psi)
    mean = lobes / mate_lobes
    phi = TWO_PI * np.arange(n) / n
    p = psi - mean * phi
    top = min((n - 1) // 2, max_order)  # below Nyquist: every kept order has both its cosine and its sine
    spectrum = (np.fft.rfft(p) / n)[: top + 1]
    candidates = [m for m in range(0, top + 1, lobes)]
    errors: dict[int, float] = {}

    def error(order: int) -> float:  # one order's law at a time: memory O(n), not a spectrum per order
        if order not in errors:
            law = np.fft.irfft(_kept(spectrum, lobes, order) * n, n) + spectrum[0].real
            errors[order] = float(np.max(np.abs(law - p)))
        return errors[order]

    def within(order: int) -> MotionFit | None:
        kept = _kept(spectrum, lobes, order)
        k_lo, k_hi, rho = _law_measures(mean, kept, center_distance)
        if not (limits.ratio[0] <= k_lo and k_hi <= limits.ratio[1] and rho >= limits.curvature_radius):
            return None
        orders = np.flatnonzero(kept)
        a, b = 2 * kept.real[orders], -2 * kept.imag[orders]  # p = Σ a_m cos mφ + b_m sin mφ
        c, s = orders * b, -orders * a  # k = mean + p'
        harmonics = tuple(zip(orders.tolist(), c.tolist(), s.tolist()))
        return MotionFit(mean, harmonics, order, error(order), (k_lo, k_hi), rho)

    # the smoothest: the lowest order that meets the tolerance within the limits
    for order in (o for o in candidates if error(o) <= tolerance):
        fit = within(order)
        if fit is not None:
            return fit
    # else the best the limits allow: the smallest error among the orders within them
    best = next((f for f in map(within, sorted(candidates, key=lambda o: (error(o), o))) if f is not None), None)
    given = np.gradient(np.unwrap(psi), phi) if n > 2 else np.array([mean])
    raise _no_law(key, best, limits, tolerance, given, capped=top == max_order, max_order=max_order)


def smoothest_law(
    psi: np.ndarray, *, lobes: int, mate_lobes: int, tolerance: float
) -> tuple[float, float, float] | None:
    """The law :func:`fit_motion` keeps when no limit binds — the lowest order within
    ``tolerance`` — as (k_min, k_max, smallest convex radius of curvature at a centre distance of
    1): radii scale with the centre distance, ratios do not.  None if no order meets the tolerance."""
    psi = np.asarray(psi, dtype=float)
    n = len(psi)
    mean = lobes / mate_lobes
    p = psi - mean * TWO_PI * np.arange(n) / n
    spectrum = np.fft.rfft(p) / n
    for order in range(0, (n - 1) // 2 + 1, lobes):
        keep = np.zeros(len(spectrum), dtype=bool)
        keep[lobes : order + 1 : lobes] = True
        kept = np.where(keep, spectrum, 0)
        if np.max(np.abs(np.fft.irfft(kept * n, n) + spectrum[0].real - p)) <= tolerance:
            return _law_measures(mean, kept, 1.0)
    return None


def law_functions(fit: MotionFit):
    """k, dk/dφ, d²k/dφ² of the fitted law, vectorised: k = mean + Re Σ (c_j − i·s_j)·z^j with
    z = e^{iφ}, by Horner's rule (one complex multiply-add per order, not a cosine and a sine)."""
    top = max((j for j, _, _ in fit.harmonics), default=0)
    coef = np.zeros(top + 1, dtype=complex)
    for j, c, s in fit.harmonics:
        coef[j] = c - 1j * s
    series = harmonic_series(coef)
    return (lambda p: fit.mean + series(p, 0), lambda p: series(p, 1), lambda p: series(p, 2))
