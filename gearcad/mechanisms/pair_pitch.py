"""A gear pair's pitch stage: profile parameters → the pair of pitch curves that rolls and closes.

``pitch_design(params)`` builds the driver curve, synthesises the mate that truly rolls and
closes, measures every check a reviewer needs, and tests the papers' own constructions alongside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from ..findings import Finding, finding
from ..pitch import shapes
from ..pitch import walker as W
from ..pitch.curve import TWO_PI, PitchCurve, radius_range
from ..pitch.gear import GearData, gear_data
from ..pitch.kinematics import KinematicsData, kinematics
from ..pitch.motion import MotionFit, law_functions
from ..pitch.pair import (
    ClaimData,
    PairData,
    angle_map,
    conjugate_pair,
    identical_mate_claim,
    rolling_residuals,
    shape_difference,
    solve_center_distance,
)
from ..profiles import (
    CircleParams,
    EllipseParams,
    GearPairParams,
    MotionParams,
    OvalParams,
    RatioParams,
    SamplesParams,
    WalkerParams,
)
from ..tolerances import DEFAULT, Tolerances
from .budget import MAX_SAMPLE_ORDER, MAX_SAMPLE_WORK, SAMPLE_NOISE

__all__ = ["WalkerData", "PairDesign", "pitch_design", "driver_curve", "shape_findings"]


@dataclass(frozen=True)
class WalkerData:
    """The wheel-walker paper's construction next to the pair that rolls."""

    i_paper: float
    paper_iterations: int
    i: float
    """i of the pair that rolls and closes 4:1, without blending."""
    i_blended: float
    blend_width: float
    blend_ratio_deviation: float
    """Largest |k_blended − k|/k over a turn: what the blend costs in ratio."""
    paper_turn_per_quarter: float
    """How far the paper's pinion would have to turn per quarter turn of the wheel if it
    rolled without slip (it is meant to turn exactly 2π), rad."""
    paper_slip: float
    """Largest slip of the paper's pinion on its wheel with θ = 4φ, mm per rad of wheel."""
    paper_table_offset: float
    """Largest |r_H(paper) − r_H(rolling)| over the wheel, mm."""
    speed_variation: float
    """(max − min)/mean of the vehicle speed ω_H·dX01/dφ for the built pair."""


@dataclass(frozen=True)
class PairDesign:
    """The pitch curves of a pair that rolls and closes, with every measure and the papers' checks."""

    params: GearPairParams
    gears: tuple[GearData, GearData]
    pair: PairData
    ratio_range: tuple[float, float]
    kinematics: KinematicsData
    mate_shape_difference: float | None
    """min over rotations of max |r2 − r1|: 0 for a self-conjugate (identical) pair, mm;
    None when the lobes differ (the gears cannot be alike)."""
    mate_rotation: float | None
    """The rotation δ of that best fit: r2(θ) ≈ r1(θ + δ), rad."""
    findings: tuple[Finding, ...]
    claim: ClaimData | None = None
    walker: WalkerData | None = None
    motion: MotionFit | None = None
    """The law fitted to a required motion (``curve = "motion"``)."""


def driver_curve(params: GearPairParams) -> tuple[PitchCurve, W.RatioLaw | MotionFit | None]:
    """Gear 1's pitch curve from its parameters (and the walker's ratio law, or the law fitted to
    a required motion, if any)."""
    g = params.gear1
    if isinstance(g, EllipseParams):
        curve = shapes.ellipse_focus(g.a, g.b) if g.pivot == "focus" else shapes.ellipse_centre(g.a, g.b)
        return curve, None
    if isinstance(g, OvalParams):
        return shapes.oval(g.a, g.b), None
    if isinstance(g, CircleParams):
        return shapes.circle(g.radius), None
    if isinstance(g, SamplesParams):
        return (
            shapes.from_samples(
                "curve from samples",
                g.radii,
                lobes=g.lobes,
                negligible=params.output.tolerance * SAMPLE_NOISE,
                max_order=MAX_SAMPLE_ORDER,
                key="gear1.radii",
                smoothing=g.smoothing,
                max_work=MAX_SAMPLE_WORK,
            ),
            None,
        )
    if isinstance(g, RatioParams):
        k, dk, d2k = shapes.harmonic_ratio(g.mean, g.harmonics)
        return shapes.from_ratio("curve from a ratio law", k, dk, d2k, params.center_distance, lobes=g.lobes), None
    if isinstance(g, WalkerParams):
        law = W.ratio_law(_walker_geometry(params), blend_width=g.blend_width)
        return W.wheel_curve(law), law
    if isinstance(g, MotionParams):
        from .pair_motion import motion_law

        fit = motion_law(params)
        k, dk, d2k = law_functions(fit)
        return shapes.from_ratio("curve from a motion", k, dk, d2k, params.center_distance, lobes=g.lobes), fit
    raise TypeError(f"unknown curve parameters {g!r}")  # pragma: no cover


def _walker_geometry(params: GearPairParams) -> W.WalkerGeometry:
    g = params.gear1
    return W.WalkerGeometry(L=params.center_distance, a=g.a, b=g.b, c=g.c)


def shape_findings(gear: GearData) -> list[Finding]:
    out = []
    for c in gear.shape.corners:
        kind = "convex corner" if c.convex else "notch (concave corner)"
        out.append(
            finding(
                "corner",
                f"{gear.name}: {kind} at φ = {math.degrees(c.phi):.3f}°, the tangent turns "
                f"{math.degrees(c.turn):+.3f}°",
                gear.name,
            )
        )
    for lo, hi in gear.shape.concave_intervals:
        out.append(
            finding(
                "concave",
                f"{gear.name}: concave between φ = {math.degrees(lo):.2f}° and {math.degrees(hi):.2f}° "
                f"(r² + 2r'² − r·r'' < 0)",
                gear.name,
            )
        )
    return out


def _check_center_distance(params: GearPairParams, curve: PitchCurve, tol: Tolerances) -> None:
    e = params.center_distance
    r_max = radius_range(curve)[1]
    if e <= r_max:
        raise DesignError(
            f"pair.center_distance = {e:g}: must exceed {params.gear1_name}'s largest radius {r_max:.6g} mm"
        )
    if isinstance(params.gear1, (RatioParams, WalkerParams, MotionParams)):
        return  # the law closes by construction (checked in the profile, measured below)
    target = TWO_PI * curve.lobes / params.gear2_lobes
    turn = angle_map(curve, e, tol=tol).turn
    if abs(turn - target) > tol.closure_rad:
        solved = solve_center_distance(curve, target, tol=tol)
        raise DesignError(
            f"pair.center_distance = {e:g}: the pair does not close there (the mate turns "
            f"{math.degrees(turn):.4f}° of the {math.degrees(target):.4f}° it needs per driver "
            f'turn); use "solve" — it closes at {solved:.9g} mm'
        )


def _walker(
    params: GearPairParams, law: W.RatioLaw, pair: PairData, kin: KinematicsData, tol: Tolerances
) -> tuple[WalkerData, list[Finding]]:
    g = _walker_geometry(params)
    i_paper, iterations = W.paper_ratio_constant(g)
    true_law = W.ratio_law(g)
    phi = np.linspace(0.0, TWO_PI, 8193)
    deviation = float(np.max(np.abs(law.k(phi) - true_law.k(phi)) / true_law.k(phi)))
    # The paper's pair: wheel from eq. 10 with its i, pinion from eq. 12, assembled with θ = 4φ.
    paper_law = W.RatioLaw(g=g, i=i_paper, half_width=0.0, poly=(0.0, 0.0, 0.0))
    paper_wheel = W.wheel_curve(paper_law)
    paper_pinion = W.paper_pinion(i_paper, g)
    # The paper turns the pinion by θ = 4φ while the wheel turns by φ.
    contact, slip = rolling_residuals(
        paper_wheel, paper_pinion, g.L, lambda p: 4 * p, lambda p: np.full_like(p, 4.0), phi
    )
    turn_quarter = angle_map(paper_wheel, g.L, tol=tol).turn / 4
    assert contact < 1e-9, "eqs. 10 and 12 keep r + r_H = L by construction"
    offset = float(np.max(np.abs(paper_wheel.r(phi) - W.wheel_curve(true_law).r(phi))))
    # Vehicle speed v = ω_H · dX01/dφ at the wheel's angle within its quarter (eq. 6).
    quarter = (kin.follower_angle + np.pi / 4) % (np.pi / 2) - np.pi / 4
    v = kin.speed * W.shoe_functions(quarter, g)["dX01"]
    data = WalkerData(
        i_paper=i_paper,
        paper_iterations=iterations,
        i=true_law.i,
        i_blended=law.i,
        blend_width=2 * law.half_width,
        blend_ratio_deviation=deviation,
        paper_turn_per_quarter=turn_quarter,
        paper_slip=slip,
        paper_table_offset=offset,
        speed_variation=float((v.max() - v.min()) / v.mean()),
    )
    found = [
        finding(
            "not-closed",
            f"the paper's pair (i = {i_paper:.6f}, θ = 4φ) does not close: rolling without slip "
            f"its pinion would turn {math.degrees(turn_quarter):.4f}° per quarter turn of the "
            f"wheel instead of 360°; the pair that rolls and closes has i = {true_law.i:.6f}",
            "walker",
        ),
        finding(
            "slips",
            f"the paper's pinion slips on its wheel by up to {slip:.4g} mm per rad of wheel "
            f"(equal arc lengths are necessary for rolling, not sufficient); its radii differ "
            f"from the rolling pair's by up to {offset:.4f} mm",
            "walker",
        ),
    ]
    if law.half_width > 0:
        found.append(
            finding(
                "blend",
                f"seams blended over {math.degrees(2 * law.half_width):g}° of wheel angle: the ratio "
                f"deviates from the required law by up to {100 * deviation:.3f}% (i = {law.i:.6f})",
                params.gear1_name,
            )
        )
    return data, found


def synthesise(params: GearPairParams, tol: Tolerances = DEFAULT):
    """The driver's curve, its ratio law (or None) and the conjugate pair the profile describes;
    a given centre distance is checked against the curve first."""
    curve, law = driver_curve(params)
    if params.center_distance is not None:
        _check_center_distance(params, curve, tol)
    pair = conjugate_pair(
        curve,
        mate_lobes=params.gear2_lobes,
        center_distance=params.center_distance,
        mate_name=params.gear2_name,
        tol=tol,
    )
    return curve, law, pair


def _claim(params: GearPairParams, curve, pair, gears, tol: Tolerances):
    """The profile's claim of an identical mate at its centre distance, checked (None without a
    claim), and a finding for each way it fails."""
    if params.claim is None:
        return None, []
    findings: list[Finding] = []
    if params.claim.center_distance <= gears[0].r_max:
        raise DesignError(
            f"claim.center_distance = {params.claim.center_distance:g}: must exceed {params.gear1_name}'s "
            f"largest radius {gears[0].r_max:.6g} mm (the mate's pivot would lie on or inside the driver)"
        )
    claim = identical_mate_claim(curve, params.claim.center_distance, tol=tol)
    if not claim.holds:
        src = f" ({params.claim.source})" if params.claim.source else ""
        findings.append(
            finding(
                "not-closed",
                f"claim{src}: at E = {claim.center_distance:g} mm the mate falls short by "
                f"{math.degrees(claim.shortfall):.4f}° per turn ({claim.shortfall:.6g} rad); the pair "
                f"built closes at E = {pair.center_distance:.9g} mm",
                "claim",
            )
        )
        findings.append(
            finding(
                "not-identical",
                f"claim{src}: an identical mate at E = {claim.center_distance:g} mm misses the "
                f"contact by up to {claim.shape_difference:.4f} mm; the built mate is computed",
                "claim",
            )
        )
    return claim, findings


def pitch_design(params: GearPairParams, *, tol: Tolerances = DEFAULT) -> PairDesign:
    """Build and check the pitch curves of the pair a profile describes."""
    curve, law, pair = synthesise(params, tol)
    if pair.closure_error > tol.closure_rad or pair.rolling_residual > tol.rolling_mm:
        spike = shapes.spike_note(params.gear1.radii, "gear1.radii") if isinstance(params.gear1, SamplesParams) else ""
        if spike:  # a misreading in measured radii: the sample to correct, not a bug
            raise DesignError(
                f"{spike} The pair through it fails its checks (closure {pair.closure_error:.3g} rad, rolling "
                f"{pair.rolling_residual:.3g} mm); correct that sample, or give gear1.smoothing"
            )
        raise DesignError(  # never expected: a synthesis that fails its own checks is a bug to report
            f"the synthesised pair fails its checks (closure {pair.closure_error:.3g} rad, rolling "
            f"{pair.rolling_residual:.3g} mm); please report this profile"
        )
    gears = (
        gear_data(params.gear1_name, pair.gear1, (0.0, 0.0), tol=tol),
        gear_data(params.gear2_name, pair.gear2, (pair.center_distance, 0.0), tol=tol),
    )
    findings: list[Finding] = []
    for gear in gears:
        findings += shape_findings(gear)
    phi = np.linspace(0.0, TWO_PI, 4097)
    k = pair.angle_map.slope(phi)
    omega = params.driver_rpm * TWO_PI / 60
    kin = kinematics(pair, driver=params.driver, speed=omega)
    claim, found = _claim(params, curve, pair, gears, tol)
    findings += found
    walker = None
    if isinstance(law, W.RatioLaw):
        walker, extra = _walker(params, law, pair, kin, tol)
        findings += extra
    likeness = shape_difference(pair.gear1, pair.gear2) if pair.lobes[0] == pair.lobes[1] else (None, None)
    return PairDesign(
        params=params,
        gears=gears,
        pair=pair,
        ratio_range=(float(k.min()), float(k.max())),
        kinematics=kin,
        mate_shape_difference=likeness[0],
        mate_rotation=likeness[1],
        findings=tuple(findings),
        claim=claim,
        walker=walker,
        motion=law if isinstance(law, MotionFit) else None,
    )
