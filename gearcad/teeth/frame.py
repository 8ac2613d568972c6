"""A pitch curve parametrised by arc length: point, tangent and outward normal at s."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..pitch.chebyshev import Piecewise
from ..pitch.curve import TWO_PI, PitchCurve, arc_length_map, curvature
from ..tolerances import DEFAULT, Tolerances

__all__ = ["ArcFrame", "arc_frame"]


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
        r, dr = self.curve.r(phi), self.curve.dr(phi)
        c, si = np.cos(phi), np.sin(phi)
        point = np.stack([r * c, r * si], axis=-1)
        d = np.stack([dr * c - r * si, dr * si + r * c], axis=-1)
        t = d / np.linalg.norm(d, axis=-1, keepdims=True)
        n = np.stack([t[..., 1], -t[..., 0]], axis=-1)
        return point, t, n

    def curvature(self, s) -> np.ndarray:
        """Signed curvature at s, 1/mm (positive where convex)."""
        return curvature(self.curve, self.angle(s))


def arc_frame(curve: PitchCurve, *, tol: Tolerances = DEFAULT) -> ArcFrame:
    s_map = arc_length_map(curve, tol=tol)
    return ArcFrame(curve, s_map, s_map.inverse(rel_tol=tol.fit_rel), s_map.hi_value)
