"""A noncircular gear pair (``mechanism = "gear-pair"``, the default)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import model_validator

from .common import BoreParams, OutputParams, ParamsModel, distinct_names
from .curves import Curve, Lobes, MotionParams, RatioParams, WalkerParams
from .process import ProcessParams
from .values import (
    LARGEST_LENGTH,
    SMALLEST_LENGTH,
    Flag,
    Length,
    LengthOrZero,
    Must,
    PartName,
    PressureAngleDeg,
    Problems,
    Speed,
    Text,
    integer,
    number,
)

__all__ = ["Gear2Params", "PairParams", "ClaimParams", "TeethParams", "GearPairParams"]

CenterDistance = Annotated[
    Length | Literal["solve"],
    Must(f'a length in mm from {SMALLEST_LENGTH:g} to {LARGEST_LENGTH:g} or "solve"', whole=True),
]
Module = number("a module in mm", ge=SMALLEST_LENGTH, le=LARGEST_LENGTH)
ToothCount = integer(ge=6, le=2000)
Addendum = number("a coefficient (× module)", gt=0, le=2)
Dedendum = number("a coefficient (× module)", gt=0, le=3)
TipRadius = number("a coefficient (× module)", ge=0, le=0.6)
ProfileShift = number("a coefficient (× module)", ge=-0.8, le=0.8)
HelixAngleDeg = number("an angle in degrees", ge=0, le=45)
MaxPressureAngleDeg = number("an angle in degrees", gt=0, lt=90)


class Gear2Params(ParamsModel):
    """``[gear2]``: the mate, whose pitch curve is computed from gear 1 and the centre distance."""

    name: PartName = "gear2"
    """The mate's name: its files are named after it."""
    lobes: Lobes | None = None
    """Lobes of the mate (default: gear1's; 1 for a walker wheel): it turns lobes1/lobes2 of a turn per driver turn."""


class PairParams(ParamsModel):
    """``[pair]``: how the two gears are set up and driven."""

    center_distance: CenterDistance = "solve"
    """Distance between the pivots, mm, or "solve" to find the one at which the mate closes."""
    driver: Text | None = None
    """The name of the gear that is driven steadily (default: gear1's, filled in by the pair)."""
    driver_rpm: Speed = 60.0
    """Speed of the driver, rev/min."""


class ClaimParams(ParamsModel):
    """``[claim]``: a paper's claim to check, that the driver meshes with an identical copy here."""

    center_distance: Length
    """The claimed centre distance, mm."""
    source: Text = ""
    """Where the claim comes from."""


class TeethParams(ParamsModel):
    """``[teeth]``: the generating rack and how many teeth (exactly one of module / count)."""

    module: Module | None = None
    """Module, mm (rounded so that a whole number of teeth fits); or give count."""
    count: ToothCount | None = None
    """Teeth on gear 1; or give module."""
    pressure_angle_deg: PressureAngleDeg = 20.0
    """Pressure angle of the rack, degrees."""
    max_pressure_angle_deg: MaxPressureAngleDeg = 45.0
    """Largest working pressure angle of the pair (the rack's plus the tilt of the pitch curves'
    tangent off the perpendicular to the line of centres, atan(r'/r)) before a `pressure-angle`
    warning, degrees: beyond about 45° most of the tooth force pushes the shafts apart."""
    addendum: Addendum = 1.0
    """Rack addendum, × module."""
    dedendum: Dedendum = 1.25
    """Rack dedendum, × module (≥ addendum, so the mate's tips have room)."""
    tip_radius: TipRadius = 0.38
    """Radius of the rack's tip rounding, × module."""
    profile_shift: ProfileShift = 0.0
    """Profile shift of gear 1, × module; gear 2 gets the opposite, so the centre distance stays."""
    backlash: LengthOrZero = 0.0
    """Backlash of the pair on the pitch curves, mm.  Left out, gearcad chooses it: under a
    [process] the smallest that keeps the band's worst case free; with none 6·tol/cos α (what
    the writing tolerance can take, 4·tol/cos α, and the mesh proof's allowed bite), less what
    teeth.clearance leaves."""
    clearance: LengthOrZero = 0.0
    """Every toothed outline is offset inwards by this, mm."""
    helix_angle_deg: HelixAngleDeg = 0.0
    """Helix angle β of the teeth, degrees (0: straight teeth); with β > 0, module is the normal
    module and the solids are lofted through twisted sections."""
    herringbone: Flag = False
    """The helix reverses at mid-height (needs helix_angle_deg > 0)."""

    @property
    def helix_angle(self) -> float:
        """β in radians."""
        return math.radians(self.helix_angle_deg)

    @property
    def pressure_angle(self) -> float:
        """The pressure angle in radians."""
        return math.radians(self.pressure_angle_deg)

    @model_validator(mode="after")
    def _rack(self) -> TeethParams:
        problems = Problems()
        if self.module is None and self.count is None:
            problems.missing("module", "give teeth.module (mm) or teeth.count (teeth on gear 1)")
        elif self.module is not None and self.count is not None:
            problems.add("count", self.count, "give teeth.module or teeth.count, not both")
        if self.herringbone and self.helix_angle_deg == 0:
            problems.add("herringbone", True, "needs teeth.helix_angle_deg > 0 (a herringbone is two opposite helices)")
        if self.dedendum < self.addendum:
            problems.add(
                "dedendum", self.dedendum, f"must be ≥ teeth.addendum = {self.addendum:g} (the mate's tips need room)"
            )
        problems.raise_any()
        return self


class GearPairParams(ParamsModel):
    """A driver with a given pitch curve and the mate that rolls on it, with or without teeth."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["gear-pair"] = "gear-pair"
    gear1: Curve
    """The driver's pitch curve."""
    gear2: Gear2Params = Gear2Params()
    pair: PairParams = PairParams()
    claim: ClaimParams | None = None
    teeth: TeethParams | None = None
    """Teeth cut by a rack; without [teeth] the parts are the pitch curves."""
    bore: BoreParams = BoreParams()
    process: ProcessParams = ProcessParams()
    """How the parts are made and assembled, with its tolerances (the mesh's band)."""
    output: OutputParams = OutputParams()

    @property
    def gear1_name(self) -> str:
        return self.gear1.name

    @property
    def gear2_name(self) -> str:
        return self.gear2.name

    @property
    def gear2_lobes(self) -> int:
        if self.gear2.lobes is not None:
            return self.gear2.lobes
        return 1 if isinstance(self.gear1, WalkerParams) else self.gear1.lobes

    @property
    def center_distance(self) -> float | None:
        """The centre distance in mm, None to solve it from closure."""
        value = self.pair.center_distance
        return None if value == "solve" else value

    @property
    def driver(self) -> int:
        """1 or 2: which gear is driven steadily."""
        return 2 if self.pair.driver == self.gear2.name else 1

    @property
    def driver_rpm(self) -> float:
        return self.pair.driver_rpm

    @model_validator(mode="after")
    def _pair(self) -> GearPairParams:
        problems = Problems()
        gear1, lobes1, lobes2 = self.gear1, self.gear1.lobes, self.gear2_lobes
        distinct_names(problems, [("gear1.name", gear1.name), ("gear2.name", self.gear2.name)])
        driver = self.pair.driver
        if driver is not None and driver not in (gear1.name, self.gear2.name):
            problems.add(
                "pair.driver", driver, f"must be one of {gear1.name!r}, {self.gear2.name!r} (the gears' names)"
            )
        if isinstance(gear1, RatioParams | WalkerParams | MotionParams) and self.center_distance is None:
            problems.add(
                "pair.center_distance",
                "solve",
                f"must be a length in mm for a {gear1.curve} gear: its law fixes the shape, "
                "the centre distance its size",
            )
        if isinstance(gear1, WalkerParams) and lobes2 != 1:
            problems.add(
                "gear2.lobes",
                lobes2,
                "must be 1 for a walker wheel: its law turns the pinion once per quarter turn of the wheel "
                "(4:1), so the pinion has one lobe",
            )
        if self.claim is not None and lobes2 != lobes1:
            problems.add(
                "claim.center_distance",
                self.claim.center_distance,
                f"an identical-mate claim needs gear2.lobes = gear1's lobes = {lobes1}, got {lobes2}",
            )
        mean = None
        if isinstance(gear1, RatioParams):
            mean = _closing_mean(gear1, lobes2, problems)
        problems.raise_any()
        # the instance is not yet visible to anyone: filling in defaults is construction
        if mean is not None and gear1.mean is None:
            object.__setattr__(self, "gear1", gear1.model_copy(update={"mean": mean}))
        if driver is None:
            object.__setattr__(self, "pair", self.pair.model_copy(update={"driver": gear1.name}))
        return self


def _closing_mean(law: RatioParams, mate_lobes: int, problems: Problems) -> float | None:
    """The mean a ratio law must have to close (n1/n2); the law must also stay positive."""
    need = law.lobes / mate_lobes
    if law.mean is not None and not math.isclose(law.mean, need, rel_tol=1e-12):
        problems.add(
            "gear1.mean",
            law.mean,
            f"the law cannot close: with gear1.lobes = {law.lobes} and gear2.lobes = {mate_lobes} the mate "
            f"turns 2π·{law.lobes}/{mate_lobes} per driver turn, so the mean ratio must be {need:g} "
            "(or leave gear1.mean out)",
        )
        return None
    samples = 4096
    low, at = math.inf, 0.0
    for j in range(samples):
        phi = 2 * math.pi * j / samples
        k = need + sum(c * math.cos(n * phi) + s * math.sin(n * phi) for n, c, s in law.harmonics)
        if not k >= low:
            low, at = k, phi
            if math.isnan(k):  # coefficients so large that the sum overflows
                break
    if not low > 0.02 * need:
        problems.add(
            "gear1.harmonics",
            [list(term) for term in law.harmonics],
            f"the ratio law falls to {low:.4g} at φ1 = {math.degrees(at):.1f}°; it must stay above 2% of its "
            f"mean {need:g} (the mate would need an infinite radius)",
        )
    return need
