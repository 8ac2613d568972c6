"""Gears on a carrier, solved by the method of stopping (``mechanism = "carrier-train"``)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import model_validator

from .common import BoreParams, OutputParams, ParamsModel, distinct_names
from .values import FASTEST, Must, PartName, Problems, StandardRackPressureAngleDeg, Text, choice, integer, number

__all__ = ["TrainParams", "CarrierTrainParams"]

_RING_MARGIN = 12  # teeth: a ring closer in size to its pinion than this interferes with it

TrainModule = number("a module in mm", gt=0, le=50)
ToothCount = integer(ge=8, le=2000)
Teeth = Annotated[
    tuple[ToothCount, ...],
    Must("a list of at least two tooth counts, each an integer from 8 to 2000", items=(2, None)),
]
Meshes = Annotated[tuple[choice("external", "internal"), ...], Must("a list of 'external' or 'internal', one per mesh")]
Names = Annotated[tuple[PartName, ...], Must("a list of names, one for each gear")]
Rpm = number("a speed in rev/min", ge=-FASTEST, le=FASTEST)
Acceleration = number("an angular acceleration in rad/s²", ge=-1e9, le=1e9)


class TrainParams(ParamsModel):
    """``[train]``: the gears in order from gear 1 on the fixed axis, and how they are driven."""

    module: TrainModule
    """Module of every gear, mm."""
    teeth: Teeth
    """Tooth counts, gear 1 first."""
    meshes: Meshes | None = None
    """How each neighbouring pair meshes, "external" or "internal" (default: all external)."""
    names: Names | None = None
    """The gears' names, which name their files (default: gear1, gear2, …)."""
    gear1_rpm: Rpm = 0.0
    """Speed of gear 1, rev/min."""
    carrier_rpm: Rpm = 0.0
    """Speed of the carrier, rev/min."""
    gear1_eps: Acceleration = 0.0
    """Angular acceleration of gear 1, rad/s²."""
    carrier_eps: Acceleration = 0.0
    """Angular acceleration of the carrier, rad/s²."""
    pressure_angle_deg: StandardRackPressureAngleDeg = 20.0
    """Pressure angle of the rack, degrees."""

    @model_validator(mode="after")
    def _gears(self) -> TrainParams:
        problems = Problems()
        teeth, gears = self.teeth, len(self.teeth)
        meshes = self.meshes if self.meshes is not None else ("external",) * (gears - 1)
        names = self.names if self.names is not None else tuple(f"gear{k + 1}" for k in range(gears))
        if len(meshes) != gears - 1:
            problems.add(
                "meshes",
                list(meshes),
                f"must be a list of {gears - 1} entries, one for each neighbouring pair of the {gears} gears",
            )
        else:
            for k, mesh in enumerate(meshes):
                ring = k if teeth[k] > teeth[k + 1] else k + 1
                pinion = 2 * k + 1 - ring
                if mesh == "internal" and teeth[ring] - teeth[pinion] < _RING_MARGIN:
                    problems.add(
                        f"teeth[{ring}]",
                        teeth[ring],
                        f"an internal mesh needs the ring at least {_RING_MARGIN} teeth larger than its pinion "
                        f"train.teeth[{pinion}] = {teeth[pinion]} (train.meshes[{k}] is 'internal')",
                    )
        if len(names) != gears:
            problems.add("names", list(names), f"must be a list of {gears} names, one for each gear")
        distinct_names(problems, [(f"names[{k}]", name) for k, name in enumerate(names)], prefix="train.")
        problems.raise_any()
        # the instance is not yet visible to anyone: filling the defaults is construction
        object.__setattr__(self, "meshes", meshes)
        object.__setattr__(self, "names", names)
        return self


class CarrierTrainParams(ParamsModel):
    """Seed 001: gear 1 on the fixed axis, the others' centres on a turning carrier."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["carrier-train"] = "carrier-train"
    train: TrainParams
    bore: BoreParams = BoreParams()
    output: OutputParams = OutputParams()

    @property
    def module(self) -> float:
        return self.train.module

    @property
    def teeth(self) -> tuple[int, ...]:
        return self.train.teeth

    @property
    def meshes(self) -> tuple[str, ...]:
        return self.train.meshes

    @property
    def names(self) -> tuple[str, ...]:
        return self.train.names

    @property
    def gear1_rpm(self) -> float:
        return self.train.gear1_rpm

    @property
    def carrier_rpm(self) -> float:
        return self.train.carrier_rpm

    @property
    def gear1_eps(self) -> float:
        return self.train.gear1_eps

    @property
    def carrier_eps(self) -> float:
        return self.train.carrier_eps

    @property
    def pressure_angle(self) -> float:
        """The pressure angle in radians."""
        return math.radians(self.train.pressure_angle_deg)
