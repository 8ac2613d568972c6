"""A closed pitch curve in polar form about its pivot, and what can be measured on it.

A :class:`PitchCurve` is ``r(φ)`` with its first two derivatives, 2π-periodic, smooth between
the angles listed in ``breaks``.  Everything else — points, tangent, curvature, arc length and
its inverse, convexity, corners, extreme radii — is a pure function of the curve.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..tolerances import DEFAULT, Tolerances
from . import chebyshev

__all__ = [
    "PitchCurve",
    "Corner",
    "ConvexityData",
    "points",
    "tangent_angle",
    "curvature",
    "polar_curvature",
    "segments",
    "arc_length_map",
    "perimeter",
    "radius_range",
    "convexity",
    "corners",
    "harmonic_series",
    "zoom_min",
    "TWO_PI",
]

TWO_PI = 2.0 * np.pi
Func = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class PitchCurve:
    """A closed polar curve ``r(φ)`` about its pivot (mm, radians).

    Parameters
    ----------
    name : str
        What the curve is, for reports.
    r, dr, d2r : callable
        ``r(φ)``, ``dr/dφ`` and ``d²r/dφ²``, vectorised over float arrays, 2π-periodic.
    lobes : int
        How many times the curve repeats per turn.
    breaks : tuple of float
        Angles in [0, 2π) where the law changes (possible corners); smooth in between.
    """

    name: str
    r: Func
    dr: Func
    d2r: Func
    lobes: int = 1
    breaks: tuple[float, ...] = field(default=())


def segments(curve: PitchCurve) -> np.ndarray:
    """Piece boundaries over one turn, starting at 0: (m + 1,) float, rad."""
    wrapped = np.sort(np.asarray(curve.breaks, dtype=float) % TWO_PI)
    edges = [0.0]
    for b in wrapped:
        if b - edges[-1] > 1e-12 and TWO_PI - b > 1e-12:
            edges.append(float(b))
    return np.array([*edges, TWO_PI])


def points(curve: PitchCurve, phi) -> np.ndarray:
    """Points of the curve at polar angles ``phi``: (n, 2) float, mm."""
    phi = np.asarray(phi, dtype=float)
    r = curve.r(phi)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi)])


def tangent_angle(curve: PitchCurve, phi) -> np.ndarray:
    """Direction of the tangent (increasing φ) at ``phi``, rad."""
    phi = np.asarray(phi, dtype=float)
    r, dr = curve.r(phi), curve.dr(phi)
    return np.arctan2(dr * np.sin(phi) + r * np.cos(phi), dr * np.cos(phi) - r * np.sin(phi))


def _convexity_numerator(curve: PitchCurve, phi) -> np.ndarray:
    r, dr, d2r = curve.r(phi), curve.dr(phi), curve.d2r(phi)
    return r * r + 2 * dr * dr - r * d2r


def curvature(curve: PitchCurve, phi) -> np.ndarray:
    """Signed curvature (1/mm), positive where the curve bends towards its pivot side."""
    phi = np.asarray(phi, dtype=float)
    return polar_curvature(curve.r(phi), curve.dr(phi), curve.d2r(phi))


def polar_curvature(r, dr, d2r) -> np.ndarray:
    """Signed curvature (1/mm) of a polar curve from r, r′ and r″ at the same angles."""
    return (r * r + 2 * dr * dr - r * d2r) / (r * r + dr * dr) ** 1.5


def arc_length_map(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> chebyshev.Piecewise:
    """s(φ): arc length from φ = 0, mm, on [0, 2π]; ``.inverse()`` gives φ(s)."""
    speed = chebyshev.fit(lambda p: np.hypot(curve.r(p), curve.dr(p)), segments(curve), rel_tol=tol.fit_rel)
    return speed.integral()


def perimeter(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> float:
    """Length of the closed curve, mm."""
    return float(arc_length_map(curve, tol=tol)(np.array([TWO_PI]))[0])


def _dense(curve: PitchCurve) -> tuple[np.ndarray, np.ndarray]:
    """Sample angles covering every piece with its end points (≈1024 in all, ≥ 64 a piece),
    and the piece of each."""
    edges = segments(curve)
    per_piece = max(64, 1024 // (len(edges) - 1))
    t = np.linspace(0.0, 1.0, per_piece + 1)
    phi = np.concatenate([a + (b - a) * t for a, b in zip(edges[:-1], edges[1:])])
    piece = np.repeat(np.arange(len(edges) - 1), per_piece + 1)
    return phi, piece


def zoom_min(func, lo: float, hi: float, x0: float, step: float, rounds: int = 3) -> tuple[float, float]:
    """Minimum of a scalar function near ``x0`` within [lo, hi], by vectorised zooming.

    Each round samples 33 points over ±step around the best point so far and shrinks step 16×:
    three rounds narrow the position 4096×, and so the value, quadratic near a smooth minimum,
    16 million times — with three vectorised calls instead of dozens of scalar ones.
    """
    best_x, best_f = x0, float(func(np.array([x0]))[0])
    for _ in range(rounds):
        x = np.clip(np.linspace(best_x - step, best_x + step, 33), lo, hi)
        f = func(x)
        k = int(np.argmin(f))
        if f[k] < best_f:
            best_x, best_f = float(x[k]), float(f[k])
        step /= 16
    return best_x, best_f


def _refined_min(func, phi, piece, edges) -> tuple[float, float]:
    """Minimum of ``func`` over the curve: dense sample, then zoom on the best sample."""
    values = func(phi)
    k = int(np.argmin(values))
    j = piece[k]
    step = (edges[j + 1] - edges[j]) / (np.count_nonzero(piece == j) - 1)
    return zoom_min(func, edges[j], edges[j + 1], float(phi[k]), step)


def radius_range(curve: PitchCurve) -> tuple[float, float]:
    """(r_min, r_max) of the curve, mm, refined beyond the sampling grid."""
    phi, piece = _dense(curve)
    edges = segments(curve)
    _, rmin = _refined_min(curve.r, phi, piece, edges)
    _, neg_rmax = _refined_min(lambda p: -curve.r(p), phi, piece, edges)
    return rmin, -neg_rmax


@dataclass(frozen=True)
class Corner:
    """A tangent discontinuity at polar angle ``phi``: the tangent turns by ``turn`` rad
    (positive = towards the pivot side, a convex corner; negative = a notch)."""

    phi: float
    turn: float

    @property
    def convex(self) -> bool:
        return self.turn > 0


def corners(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> list[Corner]:
    """Corners at the curve's seams, found from one-sided tangents."""
    found = []
    for b in segments(curve)[:-1]:
        eps = 1e-9
        before = tangent_angle(curve, np.array([b - eps]))[0]
        after = tangent_angle(curve, np.array([b + eps]))[0]
        turn = (after - before + np.pi) % TWO_PI - np.pi
        # A smooth curve still turns by κ·ds over 2·eps; only a jump far above that counts.
        smooth_turn = abs(curvature(curve, np.array([b + eps]))[0]) * 2 * eps * curve.r(np.array([b]))[0] * 10
        if abs(turn) > max(tol.corner_rad, smooth_turn):
            found.append(Corner(phi=float(b), turn=float(turn)))
    return found


@dataclass(frozen=True)
class ConvexityData:
    """Result of the convexity test r² + 2r'² − r·r'' ≥ 0 (and of the corners)."""

    convex: bool
    min_margin: float
    """Smallest (r² + 2r'² − r·r'')/r² over the curve: negative on a concave stretch."""
    min_margin_phi: float
    concave_intervals: tuple[tuple[float, float], ...]
    """Polar-angle intervals (rad) where the curve is concave."""
    min_curvature_radius: float
    """Smallest radius of curvature on convex stretches, mm (limits the tooth size)."""
    corners: tuple[Corner, ...]
    min_concave_radius: float = float("inf")
    """Smallest radius of curvature on concave stretches, mm (∞ where there is none): how far a
    generating rack strays from the outline there (x²/2ρ at x from its contact)."""


def convexity(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> ConvexityData:
    """Test convexity of both the smooth stretches and the corners of ``curve``."""
    phi, piece = _dense(curve)
    edges = segments(curve)

    def margin(p):
        return _convexity_numerator(curve, p) / curve.r(p) ** 2

    at, low = _refined_min(margin, phi, piece, edges)
    values = margin(phi)
    negative = values < -tol.convex_rel
    intervals = []
    if np.any(negative):
        idx = np.nonzero(negative)[0]
        starts = idx[np.r_[True, np.diff(idx) > 1]]
        ends = idx[np.r_[np.diff(idx) > 1, True]]
        intervals = [(float(phi[s]), float(phi[e])) for s, e in zip(starts, ends)]
    elif low < -tol.convex_rel:
        intervals = [(at, at)]
    kappa = curvature(curve, phi)
    _, neg_kmax = _refined_min(lambda p: -curvature(curve, p), phi, piece, edges)
    kmax = max(-neg_kmax, float(np.max(kappa)))
    _, kmin = _refined_min(lambda p: curvature(curve, p), phi, piece, edges)
    kmin = min(kmin, float(np.min(kappa)))
    found = tuple(corners(curve, tol=tol))
    convex = low >= -tol.convex_rel and all(c.convex for c in found)
    return ConvexityData(
        convex=bool(convex),
        min_margin=float(low),
        min_margin_phi=float(at),
        concave_intervals=tuple(intervals),
        min_curvature_radius=float(1.0 / kmax) if kmax > 0 else float("inf"),
        corners=found,
        min_concave_radius=float(-1.0 / kmin) if kmin < 0 else float("inf"),
    )


def harmonic_series(spectrum: np.ndarray):
    """``series(phi, power)``: the ``power``-th derivative (0, 1, 2) of Re Σ spectrum[k]·z^k with
    z = e^{iφ} (spectrum[k] = c_k − i·s_k for c_k cos kφ + s_k sin kφ), by Horner's rule: one
    complex multiply-add per order on the angles' array (10× faster than a cosine and a sine of
    every angle × order, and the memory of one array however many orders)."""
    spectrum = np.asarray(spectrum, dtype=complex)
    orders = np.arange(len(spectrum))

    def series(phi, power: int = 0):
        phi = np.asarray(phi, dtype=float)
        coef = spectrum * (1j * orders) ** power
        z = np.exp(1j * phi)
        acc = np.full(phi.shape, coef[-1], dtype=complex)
        for a in coef[-2::-1]:
            acc *= z
            acc += a
        return acc.real[()]

    return series
