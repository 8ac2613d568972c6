"""Driver pitch curves in closed form, from a ratio law, or spectrally from samples."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..errors import DesignError
from .curve import PitchCurve, harmonic_series

__all__ = [
    "circle",
    "ellipse_focus",
    "ellipse_centre",
    "oval",
    "from_ratio",
    "harmonic_ratio",
    "from_samples",
    "outlier",
    "spike_note",
]


def circle(radius: float) -> PitchCurve:
    """A circle about its centre."""
    return PitchCurve(
        name=f"circle r={radius:g}",
        r=lambda p: np.full_like(np.asarray(p, dtype=float), radius),
        dr=lambda p: np.zeros_like(np.asarray(p, dtype=float)),
        d2r=lambda p: np.zeros_like(np.asarray(p, dtype=float)),
    )


def _reciprocal_cosine(name: str, p: float, alpha: float, beta: float, n: int) -> PitchCurve:
    """r = p / (α − β·cos nφ) and its derivatives in closed form."""

    def den(phi):
        return alpha - beta * np.cos(n * phi)

    def r(phi):
        return p / den(np.asarray(phi, dtype=float))

    def dr(phi):
        phi = np.asarray(phi, dtype=float)
        return -p * beta * n * np.sin(n * phi) / den(phi) ** 2

    def d2r(phi):
        phi = np.asarray(phi, dtype=float)
        d, s, c = den(phi), np.sin(n * phi), np.cos(n * phi)
        return -p * beta * n * n * (c * d - 2 * beta * s * s) / d**3

    return PitchCurve(name=name, r=r, dr=dr, d2r=d2r, lobes=n)


def ellipse_focus(a: float, b: float) -> PitchCurve:
    """Ellipse pivoted at a focus, far apex at φ = 0: r = b²/(a − c·cos φ) (seed 004 eq. 6)."""
    c = np.sqrt(a * a - b * b)
    return _reciprocal_cosine(f"ellipse a={a:g} b={b:g} about a focus", b * b, a, c, 1)


def oval(a: float, b: float) -> PitchCurve:
    """Self-conjugate centre-pivoted oval r = 2ab/((a + b) − (a − b)·cos 2φ) (SPEC §1a ii)."""
    return _reciprocal_cosine(f"oval a={a:g} b={b:g} about its centre", 2 * a * b, a + b, a - b, 2)


def ellipse_centre(a: float, b: float) -> PitchCurve:
    """Ellipse pivoted at its centre: r = ab/√(b²cos²φ + a²sin²φ) (seed 004 eq. 16)."""
    k = a * a - b * b

    def r(phi):
        phi = np.asarray(phi, dtype=float)
        return a * b / np.sqrt(b * b + k * np.sin(phi) ** 2)

    def dr(phi):
        phi = np.asarray(phi, dtype=float)
        d = b * b + k * np.sin(phi) ** 2
        return -a * b * k * np.sin(2 * phi) / (2 * d**1.5)

    def d2r(phi):
        phi = np.asarray(phi, dtype=float)
        d = b * b + k * np.sin(phi) ** 2
        d1 = k * np.sin(2 * phi)
        d2 = 2 * k * np.cos(2 * phi)
        return -a * b * (d2 / (2 * d**1.5) - 0.75 * d1 * d1 / d**2.5)

    return PitchCurve(name=f"ellipse a={a:g} b={b:g} about its centre", r=r, dr=dr, d2r=d2r, lobes=2)


def from_ratio(
    name: str,
    k: Callable,
    dk: Callable,
    d2k: Callable,
    center_distance: float,
    *,
    lobes: int = 1,
    breaks: tuple[float, ...] = (),
) -> PitchCurve:
    """Driver curve from a transmission function k(φ1) = ω2/ω1: r1 = E·k/(1 + k) (SPEC §1)."""
    e = center_distance

    def r(phi):
        kk = k(np.asarray(phi, dtype=float))
        return e * kk / (1 + kk)

    def dr(phi):
        phi = np.asarray(phi, dtype=float)
        return e * dk(phi) / (1 + k(phi)) ** 2

    def d2r(phi):
        phi = np.asarray(phi, dtype=float)
        kk, k1 = k(phi), dk(phi)
        return e * (d2k(phi) * (1 + kk) - 2 * k1 * k1) / (1 + kk) ** 3

    return PitchCurve(name=name, r=r, dr=dr, d2r=d2r, lobes=lobes, breaks=breaks)


def harmonic_ratio(mean: float, terms) -> tuple[Callable, Callable, Callable]:
    """k(φ) = mean + Σ (c_j cos jφ + s_j sin jφ) and its two derivatives.

    ``terms`` is a sequence of (j, c_j, s_j).
    """
    terms = [(int(j), float(c), float(s)) for j, c, s in terms]

    def k(phi):
        phi = np.asarray(phi, dtype=float)
        out = np.full_like(phi, mean)
        for j, c, s in terms:
            out += c * np.cos(j * phi) + s * np.sin(j * phi)
        return out

    def dk(phi):
        phi = np.asarray(phi, dtype=float)
        out = np.zeros_like(phi)
        for j, c, s in terms:
            out += j * (-c * np.sin(j * phi) + s * np.cos(j * phi))
        return out

    def d2k(phi):
        phi = np.asarray(phi, dtype=float)
        out = np.zeros_like(phi)
        for j, c, s in terms:
            out -= j * j * (c * np.cos(j * phi) + s * np.sin(j * phi))
        return out

    return k, dk, d2k


def _noise(coefficients: np.ndarray, amplitude: np.ndarray, negligible: float) -> np.ndarray:
    """The most orders (smallest amplitudes first, never the mean) whose sum moves the curve by
    at most ``negligible``, as a mask: a bisection on how many.  The sum of the dropped orders
    (a trigonometric polynomial of degree K < N/8) is evaluated on N = 8 points per coefficient
    by an inverse FFT; its largest value anywhere is at most the largest on the grid over
    cos(πK/N) (Ehlich and Zeller), so that bound is what is held to ``negligible``."""
    quiet = np.argsort(amplitude[1:], kind="stable") + 1
    grid = 8 * len(coefficients)
    between = 1 / math.cos(math.pi * (len(coefficients) - 1) / grid)  # ≤ 1/cos(π/8) = 1.08

    def change(count: int) -> float:
        dropped = np.zeros_like(coefficients)
        dropped[quiet[:count]] = coefficients[quiet[:count]]
        # r = Re Σ c_k e^{ikφ}: irfft of c/2 (k > 0) times the grid size gives that sum
        return between * float(np.max(np.abs(np.fft.irfft(dropped * grid / 2, grid))))

    lo, hi = 0, len(quiet)
    while lo < hi:
        mid = (lo + hi + 1) // 2
        lo, hi = (mid, hi) if change(mid) <= negligible else (lo, mid - 1)
    mask = np.zeros(len(coefficients), dtype=bool)
    mask[quiet[:lo]] = True
    return mask


def _smooth_order(spectrum: np.ndarray, radii: np.ndarray, smoothing: float) -> int:
    """The lowest K whose series (orders ≤ K of the samples' rfft/n) is within ``smoothing`` of
    every sample: a bisection (the largest residual shrinks, if not strictly, as K grows)."""
    n = len(radii)

    def misses(k: int) -> bool:
        cut = np.where(np.arange(len(spectrum)) <= k, spectrum, 0.0)
        return float(np.max(np.abs(np.fft.irfft(cut * n, n) - radii))) > smoothing

    lo, hi = 0, len(spectrum) - 1
    while lo < hi:
        mid = (lo + hi) // 2
        lo, hi = (mid + 1, hi) if misses(mid) else (lo, mid)
    return lo


def outlier(radii) -> tuple[int, float, float] | None:
    """The one sample that stands out from its neighbours — a misreading, a spike — as (index,
    value, what its four neighbours predict by the cubic through them), or None.

    A spike of height h makes the cubic through the neighbours of each sample miss by h at the
    spike, −2h/3 beside it and h/6 two steps away: that signature is asked for (within a margin),
    and a miss of 20 times the typical sample's and a tenth of the median radius."""
    radii = np.asarray(radii, dtype=float)
    n = len(radii)
    if n < 8:
        return None
    predicted = (-np.roll(radii, 2) + 4 * np.roll(radii, 1) + 4 * np.roll(radii, -1) - np.roll(radii, -2)) / 6
    miss = radii - predicted
    j = int(np.argmax(np.abs(miss)))
    h = miss[j]
    beside = np.array([miss[j - 1], miss[(j + 1) % n]]) / h
    apart = np.array([miss[j - 2], miss[(j + 2) % n]]) / h
    tall = abs(h) > max(20 * float(np.median(np.abs(miss))), 0.1 * float(np.median(radii)))
    if tall and np.all((-0.8 < beside) & (beside < -0.5)) and np.all((0.05 < apart) & (apart < 0.3)):
        return j, float(radii[j]), float(predicted[j])
    return None


SPIKE_SAMPLES = 64
"""From this many radii on, a sample with a spike's signature is refused up front: measured
data that dense does not jump by a tenth of its radius at one sample (coarser samples of a sharp
curve — an ellipse of e ≥ 0.95 in 64 or fewer — look the same and are left to the checks)."""


def spike_note(radii, key: str) -> str:
    """``key[j] = value: stands out …`` for the sample :func:`outlier` finds, else ``""``."""
    found = outlier(radii)
    if found is None:
        return ""
    j, value, predicted = found
    return f"{key}[{j}] = {value:g}: stands out from its neighbours (they give {predicted:.4g} mm there), a misreading?"


def _work(small: np.ndarray) -> int:
    """What a series costs: (top order + 1) × (orders held)."""
    held = np.flatnonzero(~small)
    return (int(held[-1]) + 1) * len(held)


def _refuse_work(spectrum, radii, noise, max_work: int, smoothing: float, key: str) -> None:
    """Refuse a series that costs more than ``max_work``, naming the least smoothing (two
    figures, rounded up) whose cut fits: a bisection on it, as the cut's order falls (if not
    strictly) as the smoothing grows."""
    kept = np.where(noise, 0.0, spectrum)
    orders = np.arange(len(spectrum))

    def cost(allowed: float) -> int:
        return _work(noise | (orders > _smooth_order(kept, radii, allowed)))

    lo, hi = max(smoothing, 0.0), float(np.max(np.abs(radii - spectrum[0].real)))  # at hi: the mean circle
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cost(mid) > max_work else (lo, mid)
        if hi - lo <= 1e-3 * hi:
            break
    need = float(f"{hi:.2g}")
    need = need if need >= hi else float(f"{hi * 1.05:.2g}")
    held = ~noise
    held[0] = False
    name = key.rsplit(".", 1)[0] + ".smoothing" if "." in key else "smoothing"
    spike = spike_note(radii, key)
    if spike:
        raise DesignError(
            f"{spike} With it the radii keep {int(np.count_nonzero(held))} waves per turn, more than a build "
            f"cuts in about half a minute; correct that sample, or set {name} = {need:g} mm or more"
        )
    raise DesignError(
        f"{name} = {smoothing:g}: the radii keep {int(np.count_nonzero(held))} waves up to order "
        f"{int(np.flatnonzero(held)[-1]) if held.any() else 0} per turn (noise or detail), more than a build cuts "
        f"in about half a minute (order × waves at most {max_work:,}); set {name} = {need:g} mm or more, "
        "or give smoother radii"
    )


def _check_lobes(orders: np.ndarray, lobes: int, key: str) -> None:
    """Refuse radii that repeat another number of times per turn than ``lobes`` says: a curve
    with n lobes holds only orders that are multiples of n, so the radii's lobes are the greatest
    common divisor of the orders they hold (a circle holds none and has any number)."""
    if not len(orders):
        return
    found = int(np.gcd.reduce(orders))
    if found != lobes:
        name = key.rsplit(".", 1)[0] + ".lobes" if "." in key else "lobes"
        raise DesignError(
            f"{name} = {lobes}: the radii repeat {found} time{'s' if found > 1 else ''} per turn (their waves "
            f"are of orders {', '.join(map(str, orders[:4]))}{', …' if len(orders) > 4 else ''}); set {name} = {found}"
        )


def _cos_sin(spectrum: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The real series' cosine and sine coefficients of an ``rfft`` of n samples over n."""
    weight = np.ones(len(spectrum))
    weight[1:] = 2.0
    if n % 2 == 0:
        weight[-1] = 1.0  # the Nyquist term appears once
    return weight * spectrum.real, -weight * spectrum.imag


def _too_fine(key: str, negligible: float, top: int, max_order: int) -> DesignError:
    return DesignError(
        f"{key}: the radii vary on a finer scale than any tooth can follow — beyond {negligible:.2g} mm of "
        f"noise they hold waves up to order {top} per turn (at most order {max_order}); smooth them or give "
        "fewer samples"
    )


def from_samples(
    name: str,
    radii,
    *,
    lobes: int = 1,
    negligible: float = 0.0,
    max_order: int | None = None,
    key: str = "radii",
    smoothing: float = 0.0,
    max_work: int | None = None,
) -> PitchCurve:
    """A smooth curve through radii sampled at equal steps over one turn (trigonometric
    interpolation: spectrally accurate for smooth periodic data).

    ``negligible`` (mm): the smallest orders are dropped while their amplitudes add up to at
    most this — together they move the curve by no more — so that noise in measured radii
    (rounding, a scanner's grain) does not cost an evaluation of every order.  An order above
    ``max_order`` left after that is refused (:class:`DesignError` naming ``key``): the time to
    cut teeth grows with it, and no tooth follows a wiggle that fine.

    ``smoothing`` (mm, for measured radii with noise): first cut the series at the lowest order
    that passes within this of every sample.

    ``max_work``: the most (top order + 1) × (orders held) the curve may cost — every later
    evaluation costs one step per order held, and the pieces a fit needs grow with the top
    order.  Beyond it :class:`DesignError` names the smoothing that would fit, before any work.
    """
    radii = np.asarray(radii, dtype=float)
    n = len(radii)
    if n > SPIKE_SAMPLES and (spike := spike_note(radii, key)):
        raise DesignError(f"{spike} Correct that sample (one spike rings through the whole curve)")
    spectrum = np.fft.rfft(radii) / n
    orders = np.arange(len(spectrum))
    cos_c, sin_c = _cos_sin(spectrum, n)
    # orders at the FFT's rounding level (all but a few for smooth data) only cost time: together
    # they move the curve by under 1e-10 of its size
    amplitude = np.hypot(cos_c, sin_c)
    small = amplitude <= 1e-15 * np.max(np.abs(radii))
    if negligible > 0:
        small |= _noise(cos_c - 1j * sin_c, amplitude, negligible)
    small[0] = False
    noise = small.copy()
    if smoothing > 0:  # the lowest order whose series passes within ``smoothing`` of every sample
        small |= orders > _smooth_order(np.where(noise, 0.0, spectrum), radii, smoothing)
    top = int(np.flatnonzero(~small)[-1])
    if max_order is not None and top > max_order:
        raise _too_fine(key, negligible, top, max_order)
    if max_work is not None and _work(small) > max_work:
        _refuse_work(spectrum, radii, noise, max_work, smoothing, key)
    _check_lobes(np.flatnonzero(~small[1:]) + 1, lobes, key)
    series = harmonic_series(np.where(small, 0.0, cos_c - 1j * sin_c)[: top + 1])
    return PitchCurve(
        name=name,
        r=lambda p: series(p, 0),
        dr=lambda p: series(p, 1),
        d2r=lambda p: series(p, 2),
        lobes=lobes,
    )
