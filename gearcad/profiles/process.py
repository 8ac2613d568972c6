"""``[process]``: how the parts will be made and assembled, and how far that strays.

Every length is mm.  A value left out takes its process's default (:data:`DEFAULTS`), taken from
published figures (README, "How parts are made"): the band of every mesh (its play over these
tolerances) is computed from them, and a pair whose profile leaves ``teeth.backlash`` out gets the
backlash that keeps the worst case free.
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import model_validator

from .common import ParamsModel
from .values import Problems, choice, number

__all__ = ["ProcessParams", "DEFAULTS", "KINDS", "FDM_FITS"]

KINDS = ("none", "laser", "fdm", "cnc")

Small = number("a length in mm", ge=0, le=5)
Tool = number("a tool diameter in mm", ge=0, le=25)

DEFAULTS: dict[str, dict[str, float]] = {
    # laser: 3 mm plywood cuts 0.20 mm wide (acrylic 0.15, MDF 0.18) and the width varies by about
    # ±0.05 mm over a sheet, along curves, X against Y (laserengravingservice.co.uk,
    # cutlasercut.com); holes placed by hand ±0.1 mm
    "laser": {"kerf": 0.2, "kerf_variation": 0.05, "center_distance_tolerance": 0.1, "max_play": 0.5},
    # FDM: about ±0.2 mm on a dimension, so ±0.1 mm on each edge (get3dprints, printparams);
    # elephant foot 0.2 mm on the first layers (PrusaSlicer's elephant_foot_compensation for its
    # printers); printed holes ±0.2 mm
    "fdm": {"xy_variation": 0.1, "elephant_foot": 0.2, "center_distance_tolerance": 0.2, "max_play": 1.0},
    # CNC router: a 1/8 in (3.175 mm) end mill; its path is offset by the tool's radius like a
    # beam's, and the tool's own radius is the smallest root fillet (an assumption, not a
    # published figure: ±0.025 mm per edge)
    "cnc": {"tool_diameter": 3.175, "xy_variation": 0.025, "center_distance_tolerance": 0.05, "max_play": 0.5},
    "none": {},
}
"""Each process's defaults for the keys the profile leaves out; any other key defaults to 0."""

FDM_FITS: dict[str, tuple[float, float]] = {
    "tight": (0.22, 0.08),
    "standard": (0.32, 0.14),
    "loose": (0.44, 0.22),
}
"""The FDM fits makers publish for printed gear sets (issue 38): (normal backlash, tip clearance), mm."""


class ProcessParams(ParamsModel):
    """``[process]``: the maker's process and its tolerances (mm; left out: the process's default)."""

    kind: choice(*KINDS) = "none"
    """How the parts are made: "laser", "fdm" (printed), "cnc" (router) or "none" (exact parts)."""
    kerf: Small | None = None
    """Laser: the beam's width (default output.kerf if set, else 0.2); the cut paths are offset by half.
    It wins over output.kerf (both set and different: warning kerf-ignored)."""
    kerf_variation: Small | None = None
    """Laser: how far the kerf strays either way over a sheet (± mm of width; default 0.05)."""
    xy_compensation: number("a length in mm", ge=-2, le=2) | None = None
    """FDM/CNC: each edge comes out this much outside the drawn one (mm; negative: inside; default 0)."""
    xy_variation: Small | None = None
    """FDM/CNC: how far each edge strays either way (± mm; default 0.1 printed, 0.025 milled)."""
    elephant_foot: Small | None = None
    """FDM: how much further the first layers bulge out (mm; default 0.2): only ever less play."""
    tool_diameter: Tool | None = None
    """CNC: the end mill's diameter (default 3.175): its path is offset by the radius, the teeth's
    root fillets are cut with at least its radius (the rack's tip rounded so), and a tooth space,
    hole or inside corner it cannot reach is refused in one line naming this key."""
    center_distance_tolerance: Small | None = None
    """±Δa: how far the assembled centre distance strays (mm; default 0.1 laser, 0.2 FDM, 0.05 CNC)."""
    bore_play: Small | None = None
    """Diametral play of each shaft in its bore (mm; default 0): adds half of each to ±Δa."""
    max_play: Small | None = None
    """Worst-case play a maker still accepts (mm on the pitch curve; default 0.5, FDM 1.0): more warns."""
    fit: choice(*FDM_FITS) | None = None
    """FDM: the makers' fit preset, "tight", "standard" or "loose": a normal backlash of 0.22, 0.32
    or 0.44 mm and a tip clearance of 0.08, 0.14 or 0.22 mm.  Where the profile leaves
    teeth.backlash out, the preset's backlash (over cos α, on the pitch curve) is cut instead of the
    one gearcad would choose, and the bands say whether it holds under the tolerances above; the
    tip clearance is checked against the radial room the teeth leave (noncircular internal pairs
    and planetary sets; other mechanisms refuse it)."""

    @model_validator(mode="after")
    def _fit(self) -> ProcessParams:
        if self.fit is not None and self.kind != "fdm":
            problems = Problems()
            problems.add("fit", self.fit, f"a printer's fit preset needs process.kind = 'fdm', not {self.kind!r}")
            problems.raise_any()
        return self

    def preset(self, pressure_angle: float) -> tuple[float, float] | None:
        """The fit preset's (backlash on the pitch curve, tip clearance), mm; None without one."""
        if self.fit is None:
            return None
        normal, tip = FDM_FITS[self.fit]
        return normal / math.cos(pressure_angle), tip

    def value(self, key: str) -> float:
        """The key's value, or the process's default for it (0 when none applies)."""
        given: Any = getattr(self, key)
        return float(given) if given is not None else DEFAULTS[self.kind].get(key, 0.0)

    def cutter(self, output_kerf: float) -> float:
        """The width the cut paths are offset by half of: the beam's (laser; output.kerf when
        the profile sets that and not process.kerf) or the tool's (CNC); else output.kerf."""
        if self.kind == "laser":
            return float(self.kerf) if self.kerf is not None else (output_kerf or self.value("kerf"))
        if self.kind == "cnc":
            return self.value("tool_diameter")
        return output_kerf

    def edge(self, chamfer: float = 0.0) -> tuple[float, float, float]:
        """How far each made edge lies outside the drawn one: (nominal, smallest, largest), mm.
        A chamfer of the solids' edges takes the elephant foot off, as far as it goes."""
        if self.kind == "laser":
            spread = self.value("kerf_variation") / 2
            return 0.0, -spread, spread
        nominal, spread = self.value("xy_compensation"), self.value("xy_variation")
        foot = max(0.0, self.value("elephant_foot") - chamfer) if self.kind == "fdm" else 0.0
        return nominal, nominal - spread, nominal + spread + foot

    def tool_radius(self) -> float:
        """A router's tool radius (mm; 0 for any other process): the smallest root fillet, and the
        smallest inside corner radius, its parts can have."""
        return self.value("tool_diameter") / 2 if self.kind == "cnc" else 0.0

    def center_spread(self) -> float:
        """±Δa with the bores' play (half of each bore's diametral play), mm."""
        return self.value("center_distance_tolerance") + self.value("bore_play")
