"""A wheel rolling on the ground, driven through a rack from a fixed wheel (``mechanism = "rolling-wheel"``)."""

from __future__ import annotations

from typing import Literal

from pydantic import model_validator

from .common import OutputParams, ParamsModel
from .values import SMALLEST_LENGTH, PartName, Problems, Speed, Text, number

__all__ = ["DriveParams", "RollingWheelParams"]

_LIMIT = 1e5  # mm: 100 m, far beyond any part, still a number the geometry handles exactly
DriveLength = number("a length in mm", ge=SMALLEST_LENGTH, le=_LIMIT)
Height = number("a length in mm", ge=0, le=_LIMIT)


class DriveParams(ParamsModel):
    """``[drive]``: the two wheels and where they stand, mm."""

    r: DriveLength
    """Radius of the driver wheel (on the fixed axis), mm."""
    R: DriveLength
    """Radius of the rolling wheel, mm."""
    L: DriveLength
    """Horizontal distance between the centres, mm."""
    H: Height
    """Vertical distance between the centres (driver above), mm; at least R − r."""
    driver_rpm: Speed = 30.0
    """Speed of the driver wheel, rev/min."""
    travel: DriveLength = 100.0
    """How far the rolling wheel rolls towards the driver, mm (less than L)."""

    @model_validator(mode="after")
    def _layout(self) -> DriveParams:
        problems = Problems()
        if self.H < self.R - self.r:
            problems.add(
                "H",
                self.H,
                f"must be ≥ R − r = {self.R - self.r:g} mm: the rack slopes up to wheel 1 "
                "(H = R − r is the horizontal case)",
            )
        if self.travel >= self.L:
            problems.add("travel", self.travel, f"must be under drive.L = {self.L:g} mm (wheel 2 would pass wheel 1)")
        problems.raise_any()
        return self


class RollingWheelParams(ParamsModel):
    """Seed 000: a rolling wheel pulled by a rack (or thread) wound on a driver wheel."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["rolling-wheel"] = "rolling-wheel"
    drive: DriveParams
    output: OutputParams = OutputParams()

    @property
    def r(self) -> float:
        return self.drive.r

    @property
    def R(self) -> float:  # noqa: N802 - the paper's name
        return self.drive.R

    @property
    def L(self) -> float:  # noqa: N802
        return self.drive.L

    @property
    def H(self) -> float:  # noqa: N802
        return self.drive.H

    @property
    def driver_rpm(self) -> float:
        return self.drive.driver_rpm

    @property
    def travel(self) -> float:
        return self.drive.travel
