"""A pitch curve parametrised by arc length: point, tangent and outward normal at s."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..pitch import chebyshev
from ..pitch.chebyshev import Piecewise
from ..pitch.curve import TWO_PI, PitchCurve, arc_length_map, polar_curvature
from ..tolerances import DEFAULT, Tolerances

__all__ = ["ArcFrame", "arc_frame", "ParametricFrame"]


@dataclass(frozen=True)
class ArcFrame:
    """Arc-length view of a closed pitch curve (mm), s measured counter-clockwise from φ = 0."""

    curve: PitchCurve
    s_of_phi: Piecewise
    phi_of_s: Piecewise
    perimeter: float

    def angle(self, s) -> np.ndarray:
        """Polar angle φ at arc length s (any real s; periodic)."""
        s = np.asarray(s, dtype=float)
        turns = np.floor(s / self.perimeter)
        return self.phi_of_s(s - turns * self.perimeter) + turns * TWO_PI

    def arc(self, phi) -> np.ndarray:
        """Arc length at polar angle φ (any real φ)."""
        phi = np.asarray(phi, dtype=float)
        turns = np.floor(phi / TWO_PI)
        return self.s_of_phi(phi - turns * TWO_PI) + turns * self.perimeter

    def frame(self, s) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Point C, unit tangent T (increasing s) and outward unit normal N at s: (…, 2) each."""
        phi = self.angle(s)
        return self._frame(phi, self.curve.r(phi), self.curve.dr(phi))

    def _frame(self, phi, r, dr):
        c, si = np.cos(phi), np.sin(phi)
        point = np.stack([r * c, r * si], axis=-1)
        d = np.stack([dr * c - r * si, dr * si + r * c], axis=-1)
        t = d / np.linalg.norm(d, axis=-1, keepdims=True)
        n = np.stack([t[..., 1], -t[..., 0]], axis=-1)
        return point, t, n

    def curvature(self, s) -> np.ndarray:
        """Signed curvature at s, 1/mm (positive where convex)."""
        phi = self.angle(s)
        return polar_curvature(self.curve.r(phi), self.curve.dr(phi), self.curve.d2r(phi))

    def frame_curvature(self, s) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`frame` and :meth:`curvature` at s, each of φ(s), r, r′ and r″ evaluated once."""
        phi = self.angle(s)
        r, dr = self.curve.r(phi), self.curve.dr(phi)
        return (*self._frame(phi, r, dr), polar_curvature(r, dr, self.curve.d2r(phi)))


def arc_frame(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> ArcFrame:
    s_map = arc_length_map(curve, tol=tol)
    return ArcFrame(curve, s_map, s_map.inverse(rel_tol=tol.fit_rel), s_map.hi_value)


class ParametricFrame:
    """Arc-length view of a smooth closed curve given by samples at equal parameter steps
    (counter-clockwise), held as a truncated Fourier series: spectrally accurate for a smooth
    periodic curve, with exact derivatives.  Same interface as :class:`ArcFrame` for cutting
    teeth on pitch curves that are not polar about a pivot (a body on rollers)."""

    def __init__(self, samples: np.ndarray, *, tol: Tolerances = DEFAULT):
        n = len(samples)
        coeff = np.stack([np.fft.fft(samples[:, 0]), np.fft.fft(samples[:, 1])]) / n
        orders = np.fft.fftfreq(n, 1.0 / n)
        keep = np.max(np.abs(coeff), axis=0) > 1e-15 * np.max(np.abs(coeff))
        # every order between the lowest and highest kept, ascending (zeros between): Horner's rule
        low, high = int(orders[keep].min()), int(orders[keep].max())
        self._k = np.arange(low, high + 1, dtype=float)
        self._c = np.zeros((2, high - low + 1), dtype=complex)
        self._c[:, orders[keep].astype(int) - low] = coeff[:, keep]
        speed = chebyshev.fit(lambda u: np.hypot(*self._derivative(u, 1)), [0.0, TWO_PI], rel_tol=tol.fit_rel)
        self._s = speed.integral()
        self._u = self._s.inverse(rel_tol=tol.fit_rel)
        self.perimeter = self._s.hi_value

    def _derivative(self, u, order: int) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        c = self._c * (1j * self._k) ** order
        z = np.exp(1j * u)
        total = np.zeros((2, *u.shape), dtype=complex)
        for j in range(c.shape[1] - 1, -1, -1):  # Σ c_k z^k = z^low·(c_low + z(c_low+1 + z(…)))
            total = total * z + c[:, j].reshape((2,) + (1,) * u.ndim)
        return np.real(total * z ** int(self._k[0]))  # (2, …)

    def _param(self, s) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        turns = np.floor(s / self.perimeter)
        return self._u(s - turns * self.perimeter) + turns * TWO_PI

    def frame(self, s):
        u = self._param(s)
        point = np.moveaxis(self._derivative(u, 0), 0, -1)
        d = np.moveaxis(self._derivative(u, 1), 0, -1)
        t = d / np.linalg.norm(d, axis=-1, keepdims=True)
        return point, t, np.stack([t[..., 1], -t[..., 0]], axis=-1)

    def curvature(self, s) -> np.ndarray:
        u = self._param(s)
        (x1, y1), (x2, y2) = self._derivative(u, 1), self._derivative(u, 2)
        return (x1 * y2 - y1 * x2) / np.hypot(x1, y1) ** 3

    def frame_curvature(self, s):
        u = self._param(s)
        (x0, y0), (x1, y1), (x2, y2) = (self._derivative(u, k) for k in range(3))
        t = np.stack([x1, y1], axis=-1)
        t = t / np.linalg.norm(t, axis=-1, keepdims=True)
        kappa = (x1 * y2 - y1 * x2) / np.hypot(x1, y1) ** 3
        return np.stack([x0, y0], axis=-1), t, np.stack([t[..., 1], -t[..., 0]], axis=-1), kappa

    def angle(self, s) -> np.ndarray:
        """Polar angle of the curve point at s about the origin (for reports)."""
        p, _, _ = self.frame(s)
        return np.arctan2(p[..., 1], p[..., 0])

    def arc_at(self, u) -> np.ndarray:
        """Arc length at curve parameter u."""
        return self._s(np.asarray(u, dtype=float) % TWO_PI)
