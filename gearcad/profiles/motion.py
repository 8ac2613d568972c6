"""``[gear1] curve = "motion"``: the driver's pitch curve from the motion the follower must make.

Give the follower's angle (``follower_deg``) or the speed ratio ω2/ω1 (``ratio``) at equal steps
of the driver's angle over one turn; gearcad fits the smoothest ratio law that closes, within
``tolerance_deg`` of the motion and within what teeth need (see :mod:`gearcad.pitch.motion`).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import model_validator

from .common import ParamsModel
from .values import Must, PartName, Problems, integer, number

__all__ = ["MotionParams"]

_Angle = number("an angle in degrees", ge=-1e9, le=1e9)
_Ratio = number("a speed ratio", gt=0, le=1e6)
Samples = Annotated[
    tuple[_Angle, ...],
    Must("a list of 8 to 100000 angles in degrees, equally spaced over one driver turn from φ = 0", items=(8, 100_000)),
]
Ratios = Annotated[
    tuple[_Ratio, ...],
    Must("a list of 8 to 100000 speed ratios > 0, equally spaced over one driver turn from φ = 0", items=(8, 100_000)),
]


class MotionParams(ParamsModel):
    """A pitch curve fitted to a required motion: the follower's angle or the speed ratio, sampled."""

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["motion"] = "motion"
    follower_deg: Samples | None = None
    """The follower's angle ψ in degrees at φ = 360°·j/n, j = 0 … n − 1, in the follower's own sense
    of turning (ψ grows; angles that fall, measured in the driver's sense, are read as −ψ); or give ratio."""
    ratio: Ratios | None = None
    """The speed ratio ω2/ω1 at φ = 360°·j/n, j = 0 … n − 1; or give follower_deg."""
    tolerance_deg: number("an angle in degrees", gt=0, le=30) = 0.01
    """Largest motion error |Δψ| the fitted law may make, degrees."""
    lobes: integer(ge=1, le=24) = 1
    """Lobes of the driver: the law repeats this many times per turn."""

    @model_validator(mode="after")
    def _one_source(self) -> MotionParams:
        problems = Problems()
        if (self.follower_deg is None) == (self.ratio is None):
            problems.add("ratio", self.ratio, "give gear1.follower_deg or gear1.ratio (exactly one)")
        problems.raise_any()
        return self
