"""A noncircular pinion rolling inside a noncircular ring about fixed centres (``mechanism = "nc-internal"``)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from .common import BoreParams, OutputParams, ParamsModel, distinct_names
from .curves import CircleParams, EllipseParams, Lobes, OvalParams, SamplesParams
from .process import ProcessParams
from .values import LengthOrZero, PartName, Problems, StandardRackPressureAngleDeg, Text, integer, number

__all__ = ["RingParams", "InternalTeethParams", "NcInternalParams"]

PinionCurve = Annotated[EllipseParams | OvalParams | CircleParams | SamplesParams, Field(discriminator="curve")]
"""``[pinion]``: the curves that need no centre distance to be drawn (a ratio law or a motion
is an external pair's)."""


class RingParams(ParamsModel):
    """``[ring]``: the ring, whose pitch curve is the pinion's internal conjugate."""

    name: PartName = "ring"
    """The ring's name: its files are named after it."""
    lobes: Lobes
    """Lobes of the ring, more than the pinion's: it turns lobes_pinion/lobes of a turn per pinion turn."""
    wall: number("a coefficient (× module)", ge=1.5, le=20) = 3.75
    """The ring's wall outside its tooth roots, × module (its outer edge is a circle about its pivot)."""


class InternalTeethParams(ParamsModel):
    """``[teeth]``: the rack that cuts both (the ring's spaces as a gear-shaped hole)."""

    count: integer(ge=8, le=400)
    """Teeth on the pinion; the ring gets count × ring lobes / pinion lobes, which must be whole."""
    pressure_angle_deg: StandardRackPressureAngleDeg = 20.0
    """Pressure angle of the rack, degrees."""
    backlash: LengthOrZero = 0.2
    """Backlash of every mesh on the pitch curves, mm: gears' teeth are cut half of it thinner, a
    ring's spaces half of it wider.  Left out: 0.2 for exact parts; under a process
    (``process.kind``) the preset's (``process.fit``), else the smallest that keeps every mesh's
    worst case free (the bands, certified)."""

    @property
    def pressure_angle(self) -> float:
        return math.radians(self.pressure_angle_deg)


class NcInternalParams(ParamsModel):
    """A noncircular pinion in a noncircular ring (issue 38, the internal pair)."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["nc-internal"] = "nc-internal"
    pinion: PinionCurve
    ring: RingParams
    teeth: InternalTeethParams
    bore: BoreParams = BoreParams()
    """The pinion's shaft hole (the ring turns in a bearing round its outer edge)."""
    process: ProcessParams = ProcessParams()
    """How the parts are made: the mesh's band (its least play certified over the whole cycle)."""
    output: OutputParams = OutputParams()

    @property
    def pinion_lobes(self) -> int:
        return self.pinion.lobes

    @property
    def ring_teeth(self) -> int:
        return self.teeth.count * self.ring.lobes // self.pinion.lobes

    @property
    def pressure_angle(self) -> float:
        return self.teeth.pressure_angle

    @property
    def backlash(self) -> float:
        return self.teeth.backlash

    @model_validator(mode="after")
    def _counts(self) -> NcInternalParams:
        problems = Problems()
        n1, n2, z = self.pinion.lobes, self.ring.lobes, self.teeth.count
        if n2 <= n1:
            problems.add("ring.lobes", n2, f"must exceed the pinion's {n1} lobes (a ring turns slower than its pinion)")
        elif (z * n2) % n1:
            step = n1 // math.gcd(n1, n2)
            problems.add(
                "teeth.count",
                z,
                f"the ring's {z}·{n2}/{n1} teeth must be whole: give a multiple of {step} "
                f"(e.g. {max(step, z - z % step)} or {z - z % step + step})",
            )
        distinct_names(problems, [("pinion.name", self.pinion.name), ("ring.name", self.ring.name)], prefix="")
        problems.raise_any()
        return self
