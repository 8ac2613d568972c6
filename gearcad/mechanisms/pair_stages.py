"""A gear pair's early stages: the pitch curves alone (``pitch``), or with the teeth judged by
closed form (``teeth``) — no outline cut, no mesh proof, no arc fitting, no parts.

``pitch``: closure, centre distance, ratio range, radii, perimeter, curvature, convexity and the
rolling residuals.  The focus-pivoted elliptic pair (1:1, centre distance solved) is taken from
its closed form (:mod:`gearcad.pitch.focus_pair`); every other pair from the same synthesis the
full design runs, less its papers' extras, kinematics tables and likeness search.

``teeth``: the tooth counts and module the full design would choose (the same
:func:`~gearcad.teeth.plan.tooth_count`), and for each gear the equivalent spur gear at its
smallest radius of curvature ρ (Litvin's local pitch circle): undercut when m exceeds
ρ·sin²α/(h_f − ρ_f(1 − sin α) − x) or where the curve is concave (the rack's path crosses
itself there: the full cut measures how deep), and the involute tip land 2r_a(s/2ρ + inv α − inv α_a)
there, pointed when it is ≤ 0.  The report says ``"stage"`` and claims nothing else.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import DesignError
from ..findings import Finding
from ..pitch.curve import TWO_PI, PitchCurve
from ..pitch.focus_pair import FocusPair, focus_pair
from ..pitch.gear import gear_data
from ..pitch.motion import MotionFit
from ..pitch.pair import shape_difference
from ..profiles import EllipseParams, GearPairParams
from ..stages import STAGES
from ..teeth.pair import refuse_corners, undercut_free_module
from ..teeth.plan import tooth_count
from ..teeth.rack import Rack, RackParams
from ..tolerances import DEFAULT
from .base import Design
from .budget import check_teeth_work
from .pair_pitch import shape_findings, synthesise

__all__ = ["STAGES", "staged_design", "tip_land"]


@dataclass(frozen=True)
class _Pitch:
    """What the teeth stage needs from the pitch stage, however it was found."""

    blocks: list[dict]
    pair: dict
    curves: tuple[PitchCurve | FocusPair, PitchCurve | FocusPair]
    lobes: tuple[int, int]
    identical_rotation: float | None
    findings: tuple[Finding, ...]
    extra: dict = field(default_factory=dict)
    """More report blocks (the fitted motion's)."""


def _is_focus_pair(params: GearPairParams) -> bool:
    g = params.gear1
    return (
        isinstance(g, EllipseParams)
        and g.pivot == "focus"
        and params.gear2_lobes == 1
        and params.center_distance in (None, 2 * g.a)
        and g.b < g.a  # a circle about its centre is not this pair's limit case
    )


def _gear(name, curve, pivot, lobes, r_min, r_max, perimeter, margin, rho, shape=None) -> dict:
    return {
        "name": name,
        "curve": curve,
        "pivot": list(pivot),
        "lobes": lobes,
        "r_min": r_min,
        "r_max": r_max,
        "perimeter": perimeter,
        "convex": shape.convex if shape else True,
        "convexity_margin_min": margin,
        "min_curvature_radius": rho,
        "concave_intervals": [list(i) for i in shape.concave_intervals] if shape else [],
        "corners": [{"phi": c.phi, "turn": c.turn, "convex": c.convex} for c in shape.corners] if shape else [],
    }


def _pair_block(e, lobes, closure, contact, slip, ratio, method) -> dict:
    return {
        "center_distance": e,
        "lobes": list(lobes),
        "closure_error": closure,
        "rolling_residual": max(contact, slip),
        "contact_residual": contact,
        "slip_residual": slip,
        "ratio_min": ratio[0],
        "ratio_max": ratio[1],
        "method": method,
    }


def _focus_pitch(params: GearPairParams) -> _Pitch:
    g = params.gear1
    f = focus_pair(g.a, g.b)
    blocks = [
        _gear(
            name,
            f"ellipse a={g.a:g} b={g.b:g} about a focus",
            pivot,
            1,
            f.r_min,
            f.r_max,
            f.perimeter,
            f.convexity_margin_min,
            f.min_curvature_radius,
        )
        for name, pivot in ((params.gear1_name, (0.0, 0.0)), (params.gear2_name, (f.center_distance, 0.0)))
    ]
    # ψ(2π) = 2π exactly: the closed form's branch count, no integration to miss it
    pair = _pair_block(
        f.center_distance, (1, 1), 0.0, f.contact_residual, f.slip_residual, f.ratio_range, "closed form"
    )
    return _Pitch(blocks, pair, (f, f), (1, 1), 0.0, ())


def _synthesised_pitch(params: GearPairParams, tol, likeness: bool) -> _Pitch:
    curve, law, pair = synthesise(params, tol)
    gears = (
        gear_data(params.gear1_name, pair.gear1, (0.0, 0.0), tol=tol),
        gear_data(params.gear2_name, pair.gear2, (pair.center_distance, 0.0), tol=tol),
    )
    k = pair.angle_map.slope(np.linspace(0.0, TWO_PI, 4097))
    blocks = [
        _gear(
            g.name,
            g.curve.name,
            g.pivot,
            n,
            g.r_min,
            g.r_max,
            g.perimeter,
            g.shape.min_margin,
            g.shape.min_curvature_radius,
            g.shape,
        )
        for g, n in zip(gears, pair.lobes)
    ]
    block = _pair_block(
        pair.center_distance,
        pair.lobes,
        pair.closure_error,
        pair.contact_residual,
        pair.slip_residual,
        (float(k.min()), float(k.max())),
        "synthesis",
    )
    rotation = None
    if likeness and pair.lobes[0] == pair.lobes[1] and not gears[0].round:
        difference, delta = shape_difference(pair.gear1, pair.gear2)
        rotation = delta if difference < 1e-6 else None
    if likeness:
        refuse_corners(gears)  # a rack cannot roll round a corner: the cut's refusal
    findings = tuple(f for g in gears for f in shape_findings(g))
    extra = {"gears": blocks}
    if isinstance(law, MotionFit) or getattr(params.gear1, "smoothing", 0) > 0:
        from .pair_motion import fitted_blocks

        fitted_blocks(extra, params, curve, law)
    del extra["gears"]  # filled in place
    return _Pitch(blocks, block, (pair.gear1, pair.gear2), pair.lobes, rotation, findings, extra)


def tip_land(rho: float, rack: RackParams) -> float:
    """Involute tip land (mm) of the spur gear of pitch radius ``rho`` the rack cuts: the arc
    thickness 2r_a(s/(2ρ) + inv α − inv α_a) at the tip radius r_a = ρ + (x + h_a)m."""
    m, a, x = rack.module, rack.pressure_angle, rack.profile_shift
    s = math.pi * m / 2 + 2 * x * m * math.tan(a) - rack.thinning  # the tooth on the pitch circle
    r_tip = rho + (x + rack.addendum) * m
    base = rho * math.cos(a)
    if not math.isfinite(rho):
        return s - 2 * (x + rack.addendum) * m * math.tan(a)  # a rack's own tooth: straight flanks
    a_tip = math.acos(min(base / r_tip, 1.0))
    inv = (math.tan(a) - a) - (math.tan(a_tip) - a_tip)
    return 2 * r_tip * (s / (2 * rho) + inv)


def _teeth(params: GearPairParams, pitch: _Pitch, tol) -> list[dict]:
    spec = params.teeth
    if spec.helix_angle > 0:
        from ..teeth.helix import transverse_teeth

        spec = transverse_teeth(spec, spec.helix_angle)
    frame = _FocusFrame(pitch.curves[0]) if isinstance(pitch.curves[0], FocusPair) else None
    if frame is None:
        from ..teeth.frame import arc_frame

        frame = arc_frame(pitch.curves[0], tol=tol)
    module = spec.module or frame.perimeter / (math.pi * spec.count)
    perimeters = [b["perimeter"] for b in pitch.blocks]
    check_teeth_work([(p / (math.pi * module), module) for p in perimeters], params.output.tolerance)
    identical = pitch.identical_rotation
    z1 = tooth_count(frame, pitch.lobes, module=spec.module, count=spec.count, identical_rotation=identical)
    n1, n2 = pitch.lobes
    counts = (z1, z1 * n2 // n1)
    module = frame.perimeter / (math.pi * z1)
    if spec.backlash >= math.pi * module / 2:
        raise DesignError(
            f"teeth.backlash = {spec.backlash:g}: it would thin every tooth to under half its thickness; "
            f"the largest backlash module {module:.4g} takes is {math.pi * module / 2:.3f} mm"
        )
    out = []
    for i, block in enumerate(pitch.blocks):
        shift = spec.profile_shift * (1 if i == 0 else -1)
        rack = RackParams(
            module, spec.pressure_angle, spec.addendum, spec.dedendum, spec.tip_radius, shift, spec.backlash / 2
        )
        Rack.from_params(rack)  # the same refusals as the cut (a rack tooth too deep, a fillet too wide)
        rho = block["min_curvature_radius"]
        limit = undercut_free_module(rho, rack)
        land = tip_land(rho, rack)
        out.append(
            {
                "count": counts[i],
                "module": module,
                "requested_module": spec.module,
                "pressure_angle": spec.pressure_angle,
                "profile_shift": shift,
                "undercut": module > limit or not block["convex"],
                "module_limit_undercut": limit,
                "min_tip_thickness": land,
                "pointed": land <= 0,
                "method": "equivalent spur gear at the smallest radius of curvature",
            }
        )
    return out


@dataclass(frozen=True)
class _FocusFrame:
    """What :func:`tooth_count` reads of an arc-length frame, from the ellipse's closed form."""

    pair: FocusPair

    @property
    def perimeter(self) -> float:
        return self.pair.perimeter

    def arc(self, phi) -> np.ndarray:
        return self.pair.arc(phi)


def _blind(pitch) -> list[dict]:
    """The failures the teeth stage cannot see for this pair (its report's ``stage_blind``).

    The closed form judges each gear's teeth at its smallest convex radius of curvature; where a
    pitch curve is concave (the rack's path crosses itself) or follows a required motion (whose
    fitted law is often concave and always asymmetric), only the full stage's mesh proof finds
    teeth that overlap in mesh (``interference``) or whose play falls below zero (``jams``)."""
    why = [f"{b['name']} is concave" for b in pitch.blocks if not b.get("convex", True)]
    if "motion" in pitch.extra:
        why.append("the pitch curves follow a required motion")
    if not why:
        return []
    return [
        {"code": code, "why": f"{'; '.join(why)}: only the full stage's mesh proof finds {what}"}
        for code, what in (("interference", "teeth overlapping in mesh"), ("jams", "play below zero"))
    ]


def staged_design(params: GearPairParams, stage: str) -> Design:
    """The pair's ``pitch`` or ``teeth`` stage as a :class:`Design` with no parts."""
    tol = replace(DEFAULT, outline_mm=params.output.tolerance)
    toothed = stage == "teeth" and params.teeth is not None
    pitch = _focus_pitch(params) if _is_focus_pair(params) else _synthesised_pitch(params, tol, toothed)
    data = {"gears": pitch.blocks, "pair": pitch.pair, **pitch.extra}
    p = pitch.pair
    summary = (
        f"stage {stage}: E = {p['center_distance']:.6f} mm, closure {p['closure_error']:.1e} rad, "
        f"rolling {p['rolling_residual']:.1e} mm, ratio {p['ratio_min']:.6g}…{p['ratio_max']:.6g}"
    )
    if "motion" in pitch.extra:
        from .pair_motion import motion_phrase

        summary += ", " + motion_phrase(pitch.extra["motion"])
    if toothed:
        for block, teeth in zip(pitch.blocks, _teeth(params, pitch, tol)):
            block["teeth"] = teeth
        t1, t2 = (b["teeth"] for b in pitch.blocks)
        flags = [
            w
            for w, on in (("undercut", t1["undercut"] or t2["undercut"]), ("pointed", t1["pointed"] or t2["pointed"]))
            if on
        ]
        summary += f", {t1['count']}/{t2['count']} teeth m = {t1['module']:.4f}" + (
            f" ({', '.join(flags)})" if flags else ""
        )
        data["stage_blind"] = _blind(pitch)
    return Design(
        params=params,
        mechanism="gear-pair",
        summary=f"{summary}, {len(pitch.findings)} warning(s)",
        findings=pitch.findings,
        part_list=(),
        placements=(),
        assembly=None,
        data=data,
        units={"length": "mm", "angle": "rad"},
        stage=stage,
    )
