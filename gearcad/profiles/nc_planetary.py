"""The carrier-less noncircular planetary (``mechanism = "nc-planetary"``): a lobed sun, N
identical planets rolling on it, a lobed ring round them, no carrier (issue 38)."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import model_validator

from .common import BoreParams, OutputParams, ParamsModel, distinct_names
from .nc_internal import InternalTeethParams
from .process import ProcessParams
from .values import Length, PartName, Problems, Text, integer, number

__all__ = ["PlanetarySetParams", "SetTeethParams", "NcPlanetaryParams"]


class PlanetarySetParams(ParamsModel):
    """``[set]``: the planets' pitch curve r = radius·(1 + e·cos(lobes·θ)), how many, the ring."""

    lobes: integer(ge=2, le=12)
    """Lobes of the sun and of each planet (n)."""
    e: number("an eccentricity", ge=0, lt=0.5)
    """The planets' lobe depth e; below 1/(n² + 1) (convex). The sun's own e is solved so that
    the ring closes exactly (docs/mechanisms.md)."""
    radius: Length
    """The planets' mean pitch radius R, mm."""
    planets: integer(ge=3, le=12)
    """How many planets (N): N must divide gcd(lobes, ring_lobes)."""
    ring_lobes: integer(ge=3, le=72) | None = None
    """Lobes of the ring (default 3·lobes, the circular set's)."""
    sun: PartName = "sun"
    """The sun's name: its files are named after it."""
    planet: PartName = "planet"
    """The planets' name."""
    ring: PartName = "ring"
    """The ring's name."""
    wall: number("a coefficient (× module)", ge=1.5, le=20) = 3.75
    """The ring's wall outside its tooth roots, × module."""
    retention: Literal["bands", "none"] = "bands"
    """How the planets are held axially: "bands" (default) makes every part two stacked straight tooth
    bands, the upper one the lower one turned over (each tooth a quarter pitch off a symmetry line, so
    the bands' teeth stand half a pitch apart and a planet cannot slide out of sun and ring), and the
    plate holds the set assembled, printed in place; "none": one band, the parts laid apart."""


class SetTeethParams(InternalTeethParams):
    """``[teeth]``: the rack that cuts sun, planets and ring (the ring's spaces as a gear-shaped hole)."""

    count: integer(ge=8, le=400)
    """Teeth on the sun (a multiple of set.lobes); each planet has as many, the ring
    count × ring_lobes / lobes."""


class NcPlanetaryParams(ParamsModel):
    """A carrier-less noncircular planetary set, closed exactly."""

    name: PartName = "profile"
    """The profile's name: its output folder (default: the file's name)."""
    title: Text = ""
    """A title for charts and the report."""
    mechanism: Literal["nc-planetary"] = "nc-planetary"
    set: PlanetarySetParams
    teeth: SetTeethParams
    bore: BoreParams = BoreParams()
    """The sun's shaft hole (the planets float; the ring turns in a bearing round its outer edge)."""
    process: ProcessParams = ProcessParams()
    """How the parts are made: the bands of the sun–planet and planet–ring meshes (least play
    certified over the whole cycle)."""
    output: OutputParams = OutputParams()

    @property
    def ring_lobes(self) -> int:
        return self.set.ring_lobes if self.set.ring_lobes is not None else 3 * self.set.lobes

    @property
    def pressure_angle(self) -> float:
        return self.teeth.pressure_angle

    @property
    def backlash(self) -> float:
        return self.teeth.backlash

    @model_validator(mode="after")
    def _set(self) -> NcPlanetaryParams:
        problems = Problems()
        n, big_n, ring = self.set.lobes, self.set.planets, self.ring_lobes
        limit = 1.0 / (n * n + 1)
        if self.set.e >= limit:
            problems.add("set.e", self.set.e, f"must be below 1/(n² + 1) = {limit:.4g} for {n} lobes (convex planets)")
        g = math.gcd(n, ring)
        if g % big_n:
            works = [d for d in range(3, g + 1) if g % d == 0]
            fix = "use " + " or ".join(map(str, works)) + " planets" if works else "choose lobes sharing a factor ≥ 3"
            problems.add(
                "set.planets",
                big_n,
                f"must divide gcd(set.lobes, ring lobes) = gcd({n}, {ring}) = {g} to be assembled evenly: {fix}",
            )
        if self.teeth.count % n:
            z = self.teeth.count
            problems.add(
                "teeth.count",
                z,
                f"must be a multiple of set.lobes = {n} (each lobe carries whole teeth): e.g. {max(n, z - z % n)} or "
                f"{z - z % n + n}",
            )
        names = [("set.sun", self.set.sun), ("set.planet", self.set.planet), ("set.ring", self.set.ring)]
        distinct_names(problems, names, prefix="")
        problems.raise_any()
        return self
