"""What the papers say about a gear pair beyond its pitch curves: seed 004's comparative
statements about elliptic gears, and seed 002's shoe and vehicle speed for the wheel-walker."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..bodies import shoe as S
from ..errors import DesignError
from ..findings import Finding, finding
from ..pitch import elliptic_claims as E
from ..pitch import walker as W
from ..pitch import walker_polar as WP
from ..profiles import EllipseParams, GearPairParams, WalkerParams
from ..tolerances import budget
from .chart_data import Blocks, ChartData, ShoeChart, WalkerPitchChart
from .pair_pitch import PairDesign

__all__ = ["PaperExtras", "paper_extras", "SHOE_POSES"]

SHOE_POSES = tuple(math.radians(a) for a in (-45, -22.5, 0, 22.5, 45))
"""Hub angles at which the shoe is drawn standing (the stance quarter)."""


@dataclass(frozen=True)
class PaperExtras:
    """Report blocks, findings and chart data the papers add to a pair; the shoe's ring (mm,
    counter-clockwise, crank pin B1 at the origin) for the walker."""

    data: Blocks
    findings: tuple[Finding, ...]
    charts: dict[str, ChartData]
    """What the papers' charts are drawn from, by what they show (``gear_pair`` names the files)."""
    shoe: np.ndarray | None = None
    geometry: W.WalkerGeometry | None = None


def _claims(checks: list[dict], where: str) -> list[Finding]:
    return [finding(c["code"], c["message"], where) for c in checks if not c["holds"]]


def paper_extras(params: GearPairParams, pitch: PairDesign) -> PaperExtras:
    """The papers' extras for this pair (empty for pairs the papers do not discuss)."""
    g = params.gear1
    omega = params.driver_rpm * 2 * math.pi / 60
    # the paper's comparisons are about eccentric ellipses (a circle has no acceleration to compare)
    if isinstance(g, EllipseParams) and g.pivot == "centre" and params.claim is not None and g.b < 0.999 * g.a:
        checks = E.comparative_checks(g.a, g.b, omega)
        return PaperExtras(
            {"paper_claims": checks},
            tuple(_claims(checks, "claim")),
            {"elliptic_type2": E.type2_comparison(g.a, g.b, omega).as_dict()},
        )
    if isinstance(g, WalkerParams) and pitch.walker is not None:
        geometry = W.WalkerGeometry(L=params.center_distance, a=g.a, b=g.b, c=g.c)
        law = W.ratio_law(geometry, blend_width=g.blend_width)
        ring = _shoe(geometry, g.a, budget(params.output.tolerance).fine)
        speed = S.speed_comparison(geometry, i_paper=pitch.walker.i_paper, law=law)
        placed = S.ring_stance_check(geometry, ring)
        placed["holds"] = placed["hub_height_mm"] <= params.output.tolerance and (
            placed["contact_across_mm"] <= placed["chord_mm"]
        )
        shoe = {"profile": S.shoe_profile(geometry).as_dict(), "stance": S.stance_check(geometry), "placed": placed}
        found = []
        if not shoe["stance"]["holds"] or not placed["holds"]:
            found.append(
                finding("paper-claim", "the shoe does not stand as eqs. 1–6 say (see report shoe.stance)", "shoe")
            )
        charts = {
            "walker_speed": speed,
            "walker_pitch": WalkerPitchChart(WP.paper_polar(geometry, pitch.walker.i_paper), WP.pair_polar(pitch.pair)),
            # the shoe standing: (hub angle, turn, crank pin B1 from the hub) at each of SHOE_POSES
            "shoe": ShoeChart(ring, [(phi, phi, S.crank_pin(geometry, phi)[0]) for phi in SHOE_POSES], geometry.K),
        }
        summary = {k: {f: v[f] for f in v if f != "v"} for k, v in speed.items() if isinstance(v, dict)}
        return PaperExtras({"shoe": shoe, "vehicle_speed": summary}, tuple(found), charts, ring, geometry)
    return PaperExtras({}, (), {})


def _shoe(geometry: W.WalkerGeometry, a: float, tolerance: float) -> np.ndarray:
    """The shoe's ring, or a DesignError naming gear1.a and the largest a whose shoe takes the post."""
    try:
        return S.shoe_ring(geometry, tolerance=tolerance)
    except ValueError as exc:
        cause = str(exc)

    def fits(x: float) -> bool:
        try:
            S.shoe_ring(replace(geometry, a=x), tolerance=max(tolerance, 0.01))
        except ValueError:
            return False
        return True

    good, bad = geometry.b, a  # the shoe shrinks as the crank axes part; a = b is the walker's least
    if not fits(good):
        raise DesignError(f"gear1.a = {a:g}: the walker's shoe cannot be made ({cause})")
    while bad - good > 0.01 * good:
        mid = 0.5 * (good + bad)
        good, bad = (mid, bad) if fits(mid) else (good, mid)
    raise DesignError(
        f"gear1.a = {a:g}: the walker's shoe is too small for its 20 mm post (the sole's back must pass "
        f"10 mm below the crank pin B1); with b = {geometry.b:g} and c = {geometry.c:g}, "
        f"use gear1.a ≤ {math.floor(good):g} mm"
    )
