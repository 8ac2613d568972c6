"""Gears on a carrier, solved by the method of stopping (``mechanism = "carrier-train"``)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from .common import BoreParams, OutputParams, ParamsModel, distinct_names
from .messages import show
from .process import ProcessParams
from .values import (
    FASTEST,
    SMALLEST_LENGTH,
    LengthOrZero,
    Must,
    PartName,
    Problems,
    StandardRackPressureAngleDeg,
    Text,
    choice,
    integer,
    number,
)

__all__ = ["CompoundParams", "TrainParams", "CarrierTrainParams", "compound_wall"]

_RING_MARGIN = 12  # teeth: a ring closer in size to its pinion than this interferes with it
_DEDENDUM = 1.25  # modules: the standard rack's dedendum, which sets every root circle
_WALL = 2.0  # modules (the larger of the two): material a compound ring keeps between its root circles

TrainModule = number("a module in mm", ge=SMALLEST_LENGTH, le=50)
TrainAddendum = number("a coefficient (× module)", ge=0.5, le=1.25)
_MOST_TEETH = 2000
_MOST_GEARS = 24  # each gear is cut, placed and proved against its mate: ~0.1 s each, a train in seconds
ToothCount = integer(ge=8, le=_MOST_TEETH)
Teeth = Annotated[
    tuple[ToothCount, ...],
    Must(f"a list of 2 to {_MOST_GEARS} tooth counts, each an integer from 8 to 2000", items=(2, _MOST_GEARS)),
]
Meshes = Annotated[
    tuple[choice("external", "internal"), ...],
    Must("a list of 'external' or 'internal', one per mesh", items=(0, _MOST_GEARS - 1)),
]
Names = Annotated[tuple[PartName, ...], Must("a list of names, one for each gear", items=(0, _MOST_GEARS))]
Rpm = number("a speed in rev/min", ge=-FASTEST, le=FASTEST)
Acceleration = number("an angular acceleration in rad/s²", ge=-1e9, le=1e9)
GearRef = Annotated[
    Annotated[int, Field(strict=True, ge=1, le=2000)] | PartName,
    Must("a gear's name (train.names), or its place in train.teeth counting from 1", whole=True),
]


def compound_wall(teeth: int, module: float, inner_teeth: int, inner_module: float) -> float:
    """Material (mm) a compound ring keeps between its external teeth's root circle
    (r_out − 1.25·m) and its internal teeth's root circle (r_in + 1.25·m_in)."""
    return (module * teeth / 2 - _DEDENDUM * module) - (inner_module * inner_teeth / 2 + _DEDENDUM * inner_module)


class CompoundParams(ParamsModel):
    """``[train.compound]``: one gear with two toothings (seed 001's second scheme).

    Its external teeth (``train.teeth``, ``train.module``) mesh the gear before it; its internal
    teeth (``inner_teeth``, ``inner_module``) mesh the gear after it, which turns inside it.
    The gears after it are cut with ``inner_module``.
    """

    gear: GearRef
    """The gear with both toothings: its name, or its place in train.teeth counting from 1."""
    inner_teeth: ToothCount
    """Teeth of its internal toothing."""
    inner_module: TrainModule | None = None
    """Module of its internal toothing and of every gear after it, mm (default: train.module)."""


class TrainParams(ParamsModel):
    """``[train]``: the gears in order from gear 1 on the fixed axis, and how they are driven."""

    module: TrainModule
    """Module of every gear, mm (with [train.compound]: up to the compound gear's external teeth)."""
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
    backlash: LengthOrZero = 0.0
    """Backlash of every mesh on the pitch circles, mm: each gear's teeth are cut half of it
    thinner (a ring's spaces half of it wider). Default 0; left out with a [process] named,
    gearcad chooses the smallest that keeps every mesh's worst case free."""
    addendum: TrainAddendum = 1.0
    """Every gear's tip height over its pitch circle (a ring's teeth inside it), × module; the roots
    stay 1.25 deep, so the tips keep (1.25 − addendum)·m of radial clearance.  Left out with a
    [process] whose worst case brings the tips into the mates' roots, gearcad chooses it shorter
    (tip relief, down to 0.8)."""
    compound: CompoundParams | None = None
    """One gear with external and internal teeth (seed 001's second scheme)."""

    @property
    def compound_index(self) -> int | None:
        """The compound gear's place in ``teeth`` counting from 0, None without one."""
        return None if self.compound is None else _gear_index(self.compound.gear, self.names)

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
        compound = None
        if self.compound is not None and len(meshes) == gears - 1 and len(names) == gears:
            compound = _check_compound(self.compound, self.module, teeth, meshes, names, problems)
        if len(meshes) == gears - 1:
            for k, mesh in enumerate(meshes):
                if k == compound:  # its internal teeth are the compound's own, checked there
                    continue
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
        if self.compound is not None and self.compound.inner_module is None:
            object.__setattr__(self, "compound", self.compound.model_copy(update={"inner_module": self.module}))
        return self


def _gear_index(ref: int | str, names: tuple[str, ...]) -> int | None:
    """A gear given by name or by its place counting from 1, as a place counting from 0."""
    if isinstance(ref, int):
        return ref - 1 if ref <= len(names) else None
    folded = [n.casefold() for n in names]
    return folded.index(ref.casefold()) if ref.casefold() in folded else None


def _teeth_for(length: float, per_tooth: float) -> int | None:
    """Teeth to add (or take away) so that a radius moves by ``length`` mm at ``per_tooth`` mm a
    tooth; None when no tooth count could."""
    steps = length / per_tooth if per_tooth > 0 else math.inf
    return math.ceil(steps - 1e-9) if steps <= _MOST_TEETH else None


def _check_compound(compound, module, teeth, meshes, names, problems: Problems) -> int | None:
    """The compound gear's place (counting from 0) if it can carry both toothings; problems otherwise."""
    gears = len(teeth)
    k = _gear_index(compound.gear, names)
    if k is None:
        allowed = ", ".join(repr(n) for n in names)
        problems.add("compound.gear", compound.gear, f"must be one of the gears' names ({allowed}) or 1 to {gears}")
        return None
    fits = [j for j in range(1, gears - 1) if meshes[j - 1] == "external" and meshes[j] == "internal"]
    if k not in fits:
        which = ", ".join(repr(names[j]) for j in fits) or "none: no 'external' mesh is followed by an 'internal' one"
        problems.add(
            "compound.gear",
            compound.gear,
            "must be a gear meshed 'external' with the gear before it and 'internal' with the gear after it, "
            f"which turns inside it (train.meshes = {show(list(meshes))}; it allows {which})",
        )
        return None
    inner_module = compound.inner_module if compound.inner_module is not None else module
    z_in, z_next = compound.inner_teeth, teeth[k + 1]
    if z_in - z_next < _RING_MARGIN:
        problems.add(
            "compound.inner_teeth",
            z_in,
            f"must be at least {_RING_MARGIN} teeth more than the gear turning inside it, "
            f"train.teeth[{k + 1}] = {z_next}: give at least {z_next + _RING_MARGIN}",
        )
    wall = compound_wall(teeth[k], module, z_in, inner_module)
    need = _WALL * max(module, inner_module)
    if wall < need - 1e-9:
        # the wall falls by inner_module/2 per inner tooth and grows by module/2 per outer tooth
        fewer, more = _teeth_for(need - wall, inner_module / 2), _teeth_for(need - wall, module / 2)
        outer = f"train.teeth[{k}] ≥ {teeth[k] + more}" if more is not None and teeth[k] + more <= _MOST_TEETH else None
        if fewer is not None and z_in - fewer >= z_next + _RING_MARGIN:
            fix = f"give at most {z_in - fewer} inner teeth" + (f" (or {outer})" if outer else "")
        elif outer:
            fix = f"no fewer inner teeth clear train.teeth[{k + 1}] = {z_next}: give {outer}"
        else:
            fix = "no tooth counts fit these modules: give a larger train.module"
        problems.add(
            "compound.inner_teeth",
            z_in,
            f"the wall of {names[k]} between its outer and inner root circles is {wall:.4g} mm; it must be "
            f"≥ {_WALL:g}·max(train.module, train.compound.inner_module) = {need:.4g} mm: {fix}",
        )
    return k


class CarrierTrainParams(ParamsModel):
    """Seed 001: gear 1 on the fixed axis, the others' centres on a turning carrier."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["carrier-train"] = "carrier-train"
    train: TrainParams
    bore: BoreParams = BoreParams()
    process: ProcessParams = ProcessParams()
    """How the parts are made and assembled, with its tolerances (the mesh's band)."""
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

    @property
    def backlash(self) -> float:
        """Backlash of every mesh on the pitch circles, mm."""
        return self.train.backlash

    @property
    def compound(self) -> int | None:
        """The place (counting from 0) of the gear with external and internal teeth, None without one."""
        return self.train.compound_index

    @property
    def inner_teeth(self) -> int | None:
        """Teeth of the compound gear's internal toothing."""
        return None if self.train.compound is None else self.train.compound.inner_teeth

    @property
    def inner_module(self) -> float | None:
        """Module of the compound gear's internal toothing, mm."""
        return None if self.train.compound is None else self.train.compound.inner_module

    @property
    def modules(self) -> tuple[float, ...]:
        """Each gear's module, mm (the compound gear's external toothing; every gear after it is
        cut with the inner module)."""
        k = self.compound
        return tuple(self.train.module if k is None or j <= k else self.inner_module for j in range(len(self.teeth)))
