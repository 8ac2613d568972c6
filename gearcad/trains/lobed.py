"""The lobed pitch curve the carrier-less noncircular planetary's sun and planets share,
r(θ) = R·(1 + e·cos nθ + e₂·cos 2nθ), and the largest e that keeps it convex."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Lobed", "convex_limit"]


@dataclass(frozen=True)
class Lobed:
    """The shared pitch curve r(θ) = R·(1 + e·cos nθ + e₂·cos 2nθ), mm."""

    radius: float
    lobes: int
    e: float
    e2: float = 0.0

    def r(self, t):
        n = self.lobes
        return self.radius * (1.0 + self.e * np.cos(n * t) + self.e2 * np.cos(2 * n * t))

    def dr(self, t):
        n = self.lobes
        return -self.radius * n * (self.e * np.sin(n * t) + 2.0 * self.e2 * np.sin(2 * n * t))

    def d2r(self, t):
        n = self.lobes
        return -self.radius * n * n * (self.e * np.cos(n * t) + 4.0 * self.e2 * np.cos(2 * n * t))

    def speed(self, t):
        """|dS/dθ|: arc length per radian of polar angle."""
        return np.hypot(self.r(t), self.dr(t))

    def curvature(self, t):
        r, dr, d2r = self.r(t), self.dr(t), self.d2r(t)
        return (r * r + 2 * dr * dr - r * d2r) / (r * r + dr * dr) ** 1.5

    def tangent_angle(self, t):
        """Direction of dS/dθ (counter-clockwise tangent), rad, continuous in θ."""
        return t + np.arctan2(self.r(t), self.dr(t))

    def point(self, t) -> np.ndarray:
        r = self.r(t)
        return np.stack([r * np.cos(t), r * np.sin(t)], axis=-1)

    # plain-float versions for the scalar integrator of by_sun_angle
    def _scalar(self, t: float) -> tuple[float, float, float]:
        n, e, e2, big = self.lobes, self.e, self.e2, self.radius
        c1, s1, c2, s2 = math.cos(n * t), math.sin(n * t), math.cos(2 * n * t), math.sin(2 * n * t)
        r = big * (1.0 + e * c1 + e2 * c2)
        dr = -big * n * (e * s1 + 2.0 * e2 * s2)
        d2r = -big * n * n * (e * c1 + 4.0 * e2 * c2)
        return r, dr, d2r


def convex_limit(lobes: int) -> float:
    """Largest e for which 1 + e·cos nθ stays convex: the margin r² + 2r′² − r·r″ is least in
    the valley, θ = π/n, where it is (1 − e)² − (1 − e)·n²·e > 0, i.e. e < 1/(n² + 1)."""
    return 1.0 / (lobes * lobes + 1)
