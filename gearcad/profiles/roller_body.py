"""A body turning on three rollers while its centre oscillates (``mechanism = "roller-body"``)."""

from __future__ import annotations

import math
from typing import Literal

from .common import BoreParams, OutputParams, ParamsModel
from .process import ProcessParams
from .values import (
    LARGEST_LENGTH,
    SMALLEST_LENGTH,
    LengthOrZero,
    PartName,
    Speed,
    StandardRackPressureAngleDeg,
    Text,
    choice,
    integer,
    number,
    terms,
)

__all__ = ["BodyParams", "KinematicsParams", "RollerTeethParams", "RollerBodyParams"]

_EVERY_120 = " (the three rollers touch the body together only if the oscillation repeats every 120°)"

Scale = number("a scale in mm per unit of R", ge=SMALLEST_LENGTH, le=LARGEST_LENGTH)  # R itself: a length
RollerRadius = number("a radius in units of R", ge=0.005, lt=1)
Direction = choice("horizontal", "vertical", "series")
Amplitude = number("an amplitude in units of R", ge=0)
Oscillations = integer("a multiple of 3", ge=3, le=30, multiple_of=3, why=_EVERY_120)
Series = terms(max_order=60, multiple_of=3, why=_EVERY_120)
RollerCount = integer(ge=8, le=200)


class BodyParams(ParamsModel):
    """``[body]``: the oscillation of the body's centre; lengths in units of R (the rollers' circle)."""

    scale: Scale = 100.0
    """mm per unit of R: the radius of the circle the roller centres lie on, mm."""
    roller_radius: RollerRadius = 0.1
    """Roller radius, units of R (0.005 ≤ r < 1)."""
    direction: Direction = "vertical"
    """How the centre oscillates: along x, along y, or by the series f and g."""
    amplitude: Amplitude = 0.1
    """Amplitude of the oscillation, units of R (ignored for "series")."""
    m: Oscillations = 3
    """Oscillations per turn, a multiple of 3 (ignored for "series")."""
    f: Series = ()
    """x of the centre for "series": [[order, cos, sin], …], orders multiples of 3."""
    g: Series = ()
    """y of the centre for "series": [[order, cos, sin], …], orders multiples of 3."""


class KinematicsParams(ParamsModel):
    """``[kinematics]``: how fast the body turns."""

    rpm: Speed = 90.0
    """Speed of the body, rev/min."""


class RollerTeethParams(ParamsModel):
    """``[teeth]``: the rollers become pinions, and the body is toothed by the same rack."""

    roller_count: RollerCount
    """Teeth on each roller (the roller radius is nudged so that they fit)."""
    pressure_angle_deg: StandardRackPressureAngleDeg = 20.0
    """Pressure angle of the rack, degrees."""
    backlash: LengthOrZero = 0.0
    """Backlash of each roller on the body, mm on the pitch curve: the body's and the rollers'
    teeth are cut half of it thinner. Default 0; left out with a [process] named, gearcad
    chooses the smallest that keeps every roller's worst case free."""


class RollerBodyParams(ParamsModel):
    """Seed 003: a body on three rollers 120° apart, its centre oscillating as it turns."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["roller-body"] = "roller-body"
    body: BodyParams
    kinematics: KinematicsParams = KinematicsParams()
    teeth: RollerTeethParams | None = None
    bore: BoreParams = BoreParams()
    process: ProcessParams = ProcessParams()
    """How the parts are made and assembled, with its tolerances (the mesh's band)."""
    output: OutputParams = OutputParams()

    @property
    def scale(self) -> float:
        return self.body.scale

    @property
    def roller_radius(self) -> float:
        return self.body.roller_radius

    @property
    def direction(self) -> str:
        return self.body.direction

    @property
    def amplitude(self) -> float:
        """The amplitude in units of R; 0 for a "series" oscillation, which f and g give."""
        return 0.0 if self.body.direction == "series" else self.body.amplitude

    @property
    def m(self) -> int:
        return 3 if self.body.direction == "series" else self.body.m

    @property
    def f(self) -> tuple[tuple[int, float, float], ...]:
        return self.body.f

    @property
    def g(self) -> tuple[tuple[int, float, float], ...]:
        return self.body.g

    @property
    def rpm(self) -> float:
        return self.kinematics.rpm

    @property
    def roller_teeth(self) -> int | None:
        """Teeth on each roller, None for smooth rollers."""
        return self.teeth.roller_count if self.teeth is not None else None

    @property
    def backlash(self) -> float:
        """Backlash of each roller on the body, mm on the pitch curve (0 for smooth rollers)."""
        return self.teeth.backlash if self.teeth is not None else 0.0

    @property
    def pressure_angle(self) -> float:
        """The pressure angle in radians."""
        return math.radians(self.teeth.pressure_angle_deg if self.teeth is not None else 20.0)
