"""One gear's pitch curve placed on its pivot, with the measures every check reads."""

from __future__ import annotations

from dataclasses import dataclass

from ..tolerances import DEFAULT, Tolerances
from .curve import ConvexityData, PitchCurve, convexity, perimeter, radius_range

__all__ = ["GearData", "gear_data"]


@dataclass(frozen=True)
class GearData:
    """A pitch curve on its pivot (mm): radius range, perimeter and shape (convexity, corners)."""

    name: str
    curve: PitchCurve
    pivot: tuple[float, float]
    r_min: float
    r_max: float
    perimeter: float
    shape: ConvexityData

    @property
    def round(self) -> bool:
        """True for a circle (to round-off): every turn of it is the same gear."""
        return self.r_max - self.r_min < 1e-9 * self.r_max


def gear_data(name: str, curve: PitchCurve, pivot, *, tol: Tolerances = DEFAULT) -> GearData:
    """Measure a pitch curve: radius range, perimeter and convexity."""
    r_min, r_max = radius_range(curve)
    return GearData(name, curve, tuple(pivot), r_min, r_max, perimeter(curve, tol=tol), convexity(curve, tol=tol))
