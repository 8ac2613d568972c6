"""Piecewise Chebyshev series: spectrally accurate functions, integrals and inverses.

A pitch curve is smooth between a few known seams (a corner of the wheel-walker curve, the
edge of a blend).  On each smooth piece a Chebyshev series converges geometrically, so a
function that is analytic there is held to round-off with a few dozen coefficients; its
integral and derivative are exact operations on the coefficients (Clenshaw–Curtis), and the
inverse of a monotone function is fitted the same way from bracketed Newton solves.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.polynomial import chebyshev as C

from ..errors import DesignError

__all__ = ["coefficients", "Piecewise", "fit", "lobatto_points", "solve_monotone"]

_MIN_POINTS = 16
_MAX_POINTS = 128
"""Largest series on one piece: beyond it the piece is split in two, which keeps every
evaluation cheap (Clenshaw costs one step per coefficient) and resolves sharp peaks locally."""
_MAX_DEPTH = 12


def lobatto_points(n: int) -> np.ndarray:
    """Chebyshev–Lobatto points cos(πk/n), k = 0…n, on [−1, 1] (descending)."""
    return np.cos(np.pi * np.arange(n + 1) / n)


def coefficients(values: np.ndarray) -> np.ndarray:
    """Chebyshev coefficients of the interpolant through values at the Lobatto points."""
    n = len(values) - 1
    # DCT-I as the real FFT of the even extension (numpy's FFT: no scipy.fft import at start-up)
    c = np.fft.rfft(np.concatenate([values, values[-2:0:-1]])).real[: n + 1] / n
    c[0] /= 2
    c[-1] /= 2
    return c


def _fit_piece(func, lo: float, hi: float, rel_tol: float, depth: int = 0) -> list:
    """Adaptive Chebyshev fit of func on [lo, hi]: a list of (lo, hi, coefficients).

    Doubles the points until the tail is flat; the Lobatto points of n are every other point of
    2n, so each doubling samples only the new half.  Past ``_MAX_POINTS`` the piece is split.
    """
    n = _MIN_POINTS
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    values = np.asarray(func(mid + half * lobatto_points(n)), dtype=float)
    while True:
        if not np.all(np.isfinite(values)):
            raise DesignError(f"function is not finite on [{lo:.6g}, {hi:.6g}]")
        c = coefficients(values)
        scale = np.max(np.abs(c))
        tail = np.max(np.abs(c[-4:]))
        if tail <= rel_tol * scale or scale == 0.0:
            keep = np.nonzero(np.abs(c) > rel_tol * scale * 0.1)[0]
            return [(lo, hi, c[: (keep[-1] + 1 if len(keep) else 1)].copy())]
        if n >= _MAX_POINTS:
            if depth >= _MAX_DEPTH:
                return [(lo, hi, c)]  # not smooth here (a hidden corner): keep the best fit
            return _fit_piece(func, lo, mid, rel_tol, depth + 1) + _fit_piece(func, mid, hi, rel_tol, depth + 1)
        odd = np.cos(np.pi * np.arange(1, 2 * n, 2) / (2 * n))
        finer = np.empty(2 * n + 1)
        finer[0::2] = values
        finer[1::2] = np.asarray(func(mid + half * odd), dtype=float)
        values, n = finer, 2 * n


def _assemble(pieces: list) -> Piecewise:
    breaks = np.array([p[0] for p in pieces] + [pieces[-1][1]])
    return Piecewise(breaks, tuple(p[2] for p in pieces))


@dataclass(frozen=True)
class Piecewise:
    """A function held as one Chebyshev series per piece between ``breaks``.

    Parameters
    ----------
    breaks : (m + 1,) float
        Increasing piece boundaries.
    coefs : tuple of m float arrays
        Chebyshev coefficients of each piece on its own interval mapped to [−1, 1].
    """

    breaks: np.ndarray
    coefs: tuple[np.ndarray, ...]

    @property
    def lo(self) -> float:
        return float(self.breaks[0])

    @property
    def hi(self) -> float:
        return float(self.breaks[-1])

    @property
    def hi_value(self) -> float:
        """The function's value at the right end."""
        return float(self(np.array([self.hi]))[0])

    @property
    def degree(self) -> int:
        """Total number of coefficients held (a measure of cost)."""
        return sum(len(c) for c in self.coefs)

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        piece = np.clip(np.searchsorted(self.breaks, x, side="right") - 1, 0, len(self.coefs) - 1)
        a, b = self.breaks[piece], self.breaks[piece + 1]
        return _clenshaw((2 * x - (a + b)) / (b - a), self._table, piece)

    @cached_property
    def _table(self) -> np.ndarray:
        """Coefficients of all pieces, zero-padded to one (pieces, degree) array."""
        table = np.zeros((len(self.coefs), max(len(c) for c in self.coefs)))
        for j, c in enumerate(self.coefs):
            table[j, : len(c)] = c
        return table

    def derivative(self) -> Piecewise:
        coefs = tuple(
            C.chebder(c) * 2 / (b - a) if len(c) > 1 else np.zeros(1)
            for c, a, b in zip(self.coefs, self.breaks[:-1], self.breaks[1:])
        )
        return Piecewise(self.breaks, coefs)

    def integral(self) -> Piecewise:
        """The antiderivative that is zero at ``lo`` and continuous across breaks."""
        coefs, start = [], 0.0
        for c, a, b in zip(self.coefs, self.breaks[:-1], self.breaks[1:]):
            ci = C.chebint(c, lbnd=-1) * (b - a) / 2
            ci[0] += start
            coefs.append(ci)
            start = float(C.chebval(1.0, ci))
        return Piecewise(self.breaks, tuple(coefs))

    def inverse(self, *, rel_tol: float) -> Piecewise:
        """The inverse of a strictly increasing function, fitted piece by piece."""
        slope = self.derivative()
        values = self(self.breaks)
        if np.any(np.diff(values) <= 0):
            raise DesignError("an angle or arc-length map is not increasing: it cannot be inverted")
        coefs = []
        for j in range(len(self.coefs)):
            a, b = self.breaks[j], self.breaks[j + 1]
            table_x = np.linspace(a, b, 257)
            table_y = self(table_x)
            if np.any(np.diff(table_y) <= 0):
                raise DesignError("an angle or arc-length map is not increasing: it cannot be inverted")

            def inv(y, a=a, b=b, table_x=table_x, table_y=table_y):
                return solve_monotone(self, slope, y, a, b, np.interp(y, table_y, table_x))

            coefs += _fit_piece(inv, values[j], values[j + 1], rel_tol)
        return _assemble(coefs)


def _clenshaw(t: np.ndarray, table: np.ndarray, piece: np.ndarray) -> np.ndarray:
    """Σ c_k T_k(t) with each point's coefficients taken from its piece's row of ``table``.

    Few points: T_k(t) = cos(k·arccos t) as one (points, degree) array — no Python loop.
    Many points: Clenshaw's recurrence, one vectorised step per coefficient.
    """
    degree = table.shape[1]
    if t.size * degree <= 1 << 15:
        angles = np.arccos(np.clip(t, -1.0, 1.0))
        return np.sum(np.cos(angles[..., None] * np.arange(degree)) * table[piece], axis=-1)
    if table.shape[0] == 1:
        return C.chebval(t, table[0])
    columns = np.ascontiguousarray(table.T)  # coefficient k of every piece, contiguous: a cheap take
    b1 = np.zeros_like(t)
    b2 = np.zeros_like(t)
    two_t = 2 * t
    for k in range(degree - 1, 0, -1):
        b1, b2 = columns[k].take(piece) + two_t * b1 - b2, b1
    return columns[0].take(piece) + t * b1 - b2


def fit(func: Callable[[np.ndarray], np.ndarray], breaks, *, rel_tol: float) -> Piecewise:
    """Fit ``func`` on each interval between consecutive ``breaks`` to relative ``rel_tol``."""
    breaks = np.asarray(breaks, dtype=float)
    return _assemble([p for a, b in zip(breaks[:-1], breaks[1:]) for p in _fit_piece(func, a, b, rel_tol)])


def solve_monotone(f, df, y, lo, hi, guess, iterations: int = 60) -> np.ndarray:
    """Solve f(x) = y for increasing f on [lo, hi], vectorised over y.

    Newton steps kept inside a shrinking bracket; a step that leaves it is replaced by
    bisection, so convergence is guaranteed and, from a good guess, quadratic.
    """
    y = np.asarray(y, dtype=float)
    x = np.clip(np.asarray(guess, dtype=float) * np.ones_like(y), lo, hi)
    left = np.full_like(y, lo)
    right = np.full_like(y, hi)
    small = 1e-13 * max(abs(lo), abs(hi), 1.0)
    for _ in range(iterations):
        fx = f(x) - y
        left = np.where(fx < 0, x, left)
        right = np.where(fx > 0, x, right)
        d = df(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = x - np.where(d > 0, fx / d, np.inf)
        outside = ~((new >= left) & (new <= right))
        new = np.where(outside, 0.5 * (left + right), new)
        step = np.max(np.abs(new - x)) if len(x) else 0.0
        x = new
        if step <= small:
            break  # the step before this one was already below 1e-13: x is at round-off
    return x
