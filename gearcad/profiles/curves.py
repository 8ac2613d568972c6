"""``[gear1]``: the driver's pitch curve, one model per ``curve`` (a tagged union)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from .common import ParamsModel
from .motion import MotionParams
from .values import Length, LengthOrZero, Must, PartName, Problems, choice, close_enough, integer, number, terms

__all__ = [
    "EllipseParams",
    "OvalParams",
    "CircleParams",
    "RatioParams",
    "WalkerParams",
    "SamplesParams",
    "MotionParams",
    "CurveParams",
    "Curve",
    "CURVES",
]

CURVES = ("ellipse", "oval", "circle", "ratio", "walker", "samples", "motion")

Lobes = integer(ge=1, le=24)
_MOST_ECCENTRICITY = 0.998
"""Beyond it (b < 0.063·a) the pair's ratio spans over 10⁵ and its synthesis misses its own
closure and rolling checks (e = 0.999 fails at either pivot, b/a = 0.02 at the centre)."""
_LEAST_OVAL = 0.005
"""Smallest b/a of an oval: at 0.001 its pair misses its closure check."""
Eccentricity = number("an eccentricity", ge=0, le=_MOST_ECCENTRICITY)
SpeedRatio = number("a speed ratio", gt=0)
Pivot = choice("focus", "centre")
Harmonics = terms(max_order=64)
BlendWidth = number("an angle in degrees", ge=0, lt=45)
MIN_BLEND_DEG = 0.1
"""Narrowest blend, degrees: at 0.01° a walker pair took 14 s (its mate's arc length fitted in
4 600 pieces), at 1e-6° 80 s, below ~1e-150° the blend's quartic overflows; 0.1° takes 0.2 s."""
Radii = Annotated[
    tuple[Length, ...],
    Must("a list of 8 to 100000 lengths in mm > 0, equally spaced over one turn from φ = 0", items=(8, 100_000)),
]


class EllipseParams(ParamsModel):
    """An ellipse turning about a focus (one lobe) or its centre (two lobes).

    Give the semi-minor axis ``b`` or the ``eccentricity``; after validation ``b`` is always set.
    """

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["ellipse"] = "ellipse"
    a: Length
    """Semi-major axis, mm."""
    b: Length | None = None
    """Semi-minor axis, mm (≤ a); or give eccentricity instead."""
    eccentricity: Eccentricity | None = None
    """Eccentricity 0 ≤ e < 1, instead of b: b = a·√(1 − e²)."""
    pivot: Pivot = "focus"
    """The point the gear turns about."""

    @property
    def lobes(self) -> int:
        return 1 if self.pivot == "focus" else 2

    @model_validator(mode="after")
    def _minor_axis(self) -> EllipseParams:
        problems = Problems()
        e = self.eccentricity
        from_e = None if e is None else self.a * math.sqrt(1 - e * e)
        if self.b is None and from_e is None:
            problems.missing("b", f"give gear1.b (a length in mm) or gear1.eccentricity (0 ≤ e ≤ {_MOST_ECCENTRICITY})")
        elif self.b is not None and from_e is not None and not close_enough(self.b, from_e):
            problems.add(
                "eccentricity",
                e,
                f"gives b = a·√(1 − e²) = {from_e:g} mm, but gear1.b = {self.b:g} is given too; give only one of them",
            )
        elif self.b is not None and self.b > self.a:
            problems.add("b", self.b, f"must not exceed gear1.a = {self.a:g} (b is the semi-minor axis)")
        elif self.b is not None and self.b < (least := self.a * math.sqrt(1 - _MOST_ECCENTRICITY**2)):
            rule = f"must be at least {least:.4g} mm = 0.0632·a (eccentricity ≤ {_MOST_ECCENTRICITY})"
            problems.add("b", self.b, rule)
        problems.raise_any()
        if self.b is None:
            # the instance is not yet visible to anyone: filling a derived field is construction
            object.__setattr__(self, "b", from_e)
        return self


class OvalParams(ParamsModel):
    """The self-conjugate oval r = 2ab / ((a + b) − (a − b)·cos 2φ), turning about its centre."""

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["oval"] = "oval"
    a: Length
    """Largest radius, mm."""
    b: Length
    """Smallest radius, mm (≤ a)."""

    @property
    def lobes(self) -> int:
        return 2

    @model_validator(mode="after")
    def _radii(self) -> OvalParams:
        problems = Problems()
        if self.b > self.a:
            problems.add("b", self.b, f"must not exceed gear1.a = {self.a:g} (b is the smallest radius)")
        elif self.b < _LEAST_OVAL * self.a:
            problems.add("b", self.b, f"must be at least {_LEAST_OVAL * self.a:.4g} mm = {_LEAST_OVAL}·a")
        problems.raise_any()
        return self


class CircleParams(ParamsModel):
    """A circle turning about its centre: a spur gear's pitch circle."""

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["circle"] = "circle"
    radius: Length
    """Pitch radius, mm."""

    @property
    def lobes(self) -> int:
        return 1


class RatioParams(ParamsModel):
    """A speed-ratio law k(φ1) = ω2/ω1 = mean + Σ (cos·cos jφ1 + sin·sin jφ1).

    ``mean`` is fixed by closure (lobes / gear2 lobes); the pair fills it in when it is absent,
    so that after a :class:`GearPairParams` is validated its ``gear1.mean`` is a float.
    """

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["ratio"] = "ratio"
    mean: SpeedRatio | None = None
    """Mean speed ratio; leave it out: closure fixes it to gear1.lobes / gear2.lobes."""
    harmonics: Harmonics = ()
    """[[order, cos, sin], …]: at most 16 terms, each order a multiple of lobes and ≤ 64."""
    lobes: Lobes = 1
    """Lobes of the driver's pitch curve."""

    @model_validator(mode="after")
    def _orders(self) -> RatioParams:
        problems = Problems()
        for n, term in enumerate(self.harmonics):
            if term[0] % self.lobes:
                problems.add(
                    f"harmonics[{n}]",
                    list(term),
                    f"the order must be a multiple of gear1.lobes = {self.lobes} so that the curve has "
                    f"{self.lobes} lobes",
                )
        problems.raise_any()
        return self


class WalkerParams(ParamsModel):
    """The wheel-walker carrier wheel: its ratio law from the leg geometry a, b, c."""

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["walker"] = "walker"
    a: Length
    """Distance between the hub and crank axes, mm."""
    b: Length
    """Crank length, mm."""
    c: Length
    """Shoe post length, mm."""
    blend_width_deg: BlendWidth = 0.0
    """Wheel angle over which each quarter-turn corner is blended, degrees (0: sharp corners, else ≥ 0.1)."""

    @property
    def lobes(self) -> int:
        return 4

    @property
    def blend_width(self) -> float:
        """The blend width in radians."""
        return math.radians(self.blend_width_deg)

    @model_validator(mode="after")
    def _positive_ratio(self) -> WalkerParams:
        problems = Problems()
        if 0 < self.blend_width_deg < MIN_BLEND_DEG:
            problems.add(
                "blend_width_deg",
                self.blend_width_deg,
                f"must be 0 (sharp corners) or from {MIN_BLEND_DEG:g} to 45: a narrower blend is a corner in all "
                "but its cost (its curvature defeats the spectral fits)",
            )
        slack = self.a - 4 * self.b + self.c
        if slack <= 0:
            problems.add(
                "b",
                self.b,
                f"the walker law needs a − 4b + c > 0 so that the ratio stays positive (got {slack:g} mm)",
            )
        problems.raise_any()
        return self


class SamplesParams(ParamsModel):
    """A pitch curve given by its radii, equally spaced in polar angle over one turn."""

    name: PartName = "gear1"
    """The gear's name: its files are named after it."""
    curve: Literal["samples"] = "samples"
    radii: Radii
    """Radii in mm at φ = 2πk/n, k = 0 … n − 1 (at least 8)."""
    lobes: Lobes = 1
    """Lobes of the curve (the samples should repeat that many times)."""
    smoothing: LengthOrZero = 0.0
    """For measured radii with noise: the largest change smoothing may make to any radius, mm
    (0: none). The curve keeps the fewest waves per turn that pass within this of every sample;
    the report gives the deviation it made."""


CurveParams = EllipseParams | OvalParams | CircleParams | RatioParams | WalkerParams | SamplesParams | MotionParams
Curve = Annotated[CurveParams, Field(discriminator="curve")]
"""``[gear1]`` as a field: the union, told apart by ``curve``."""
