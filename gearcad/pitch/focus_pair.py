"""Two identical ellipses turning about their foci: the one noncircular pair in closed form.

With ``r(φ) = b²/(a − c·cos φ)`` (far apex at φ = 0, c = √(a² − b²)) the mate is the same
ellipse, the centre distance is 2a, and the follower turns by

    ψ(φ) = 2·atan(K·tan(φ/2)),   K = (a + c)/(a − c)

(seed 004 §2; Litvin, *Noncircular gears*, ch. 4).  Everything a pitch-stage screen needs
follows without a fit: radii a ∓ c, ratio K^±1, perimeter 4a·E(e), radius of curvature ≥ b²/a,
and the convexity margin (r² + 2r'² − r·r'')/r² = a·r/b² ≥ a/(a + c) (u = 1/r has u + u'' = a/b²).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .curve import TWO_PI

__all__ = ["FocusPair", "focus_pair", "follower_angle"]


@dataclass(frozen=True)
class FocusPair:
    """The closed-form measures of a focus-pivoted elliptic pair (mm, rad)."""

    a: float
    b: float
    c: float
    center_distance: float
    r_min: float
    r_max: float
    perimeter: float
    min_curvature_radius: float
    convexity_margin_min: float
    ratio_range: tuple[float, float]
    contact_residual: float
    """max |r1 + r2(π − ψ) − 2a| on a grid, with ψ from the closed form, mm."""
    slip_residual: float
    """max |r1 − r2·ψ'| on the same grid, mm per rad."""

    def radius(self, phi) -> np.ndarray:
        return self.b * self.b / (self.a - self.c * np.cos(phi))

    def arc(self, phi) -> np.ndarray:
        """Arc length from the far apex to polar angle ``phi`` (about the focus), mm: through the
        eccentric anomaly t (x = a·cos t about the centre) and the incomplete integral E."""
        from scipy.special import ellipeinc

        phi = np.asarray(phi, dtype=float)
        r = self.radius(phi)
        t = np.arctan2(r * np.sin(phi) / self.b, (r * np.cos(phi) - self.c) / self.a)
        t += TWO_PI * np.round((phi - t) / TWO_PI)  # the branch that follows φ
        m = (self.c / self.a) ** 2
        return self.a * (ellipeinc(np.pi / 2, m) - ellipeinc(np.pi / 2 - t, m))


def follower_angle(phi, a: float, b: float) -> np.ndarray:
    """ψ(φ) = 2·atan(K·tan(φ/2)), continued over whole turns (rad)."""
    c = math.sqrt(a * a - b * b)
    k = (a + c) / (a - c)
    phi = np.asarray(phi, dtype=float)
    turns = np.floor((phi + np.pi) / TWO_PI)
    half = (phi - TWO_PI * turns) / 2  # in [−π/2, π/2)
    return 2 * np.arctan(k * np.tan(half)) + TWO_PI * turns


def focus_pair(a: float, b: float, *, samples: int = 64) -> FocusPair:
    """The closed form of the pair of ellipses (semi-axes ``a`` ≥ ``b``) about their foci."""
    from scipy.special import ellipe

    c = math.sqrt(max(a * a - b * b, 0.0))
    k = (a + c) / (a - c)
    phi = np.linspace(0.0, TWO_PI, samples, endpoint=False)
    psi = follower_angle(phi, a, b)
    slope = k / (np.cos(phi / 2) ** 2 + (k * np.sin(phi / 2)) ** 2)  # ψ'(φ), no pole at φ = π

    def radius(p):
        return b * b / (a - c * np.cos(p))

    r1, r2 = radius(phi), radius(np.pi - psi)
    return FocusPair(
        a=a,
        b=b,
        c=c,
        center_distance=2 * a,
        r_min=a - c,
        r_max=a + c,
        perimeter=4 * a * float(ellipe((c / a) ** 2)),
        min_curvature_radius=b * b / a,
        convexity_margin_min=a / (a + c),
        ratio_range=(1 / k, k),
        contact_residual=float(np.max(np.abs(r1 + r2 - 2 * a))),
        slip_residual=float(np.max(np.abs(r1 - r2 * slope))),
    )
