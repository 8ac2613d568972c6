"""The teeth stage for a pair: plan, cut both gears, prove the mesh, measure the play."""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np
import shapely

from ..errors import DesignError
from ..findings import Finding, finding
from ..geometry.outline import Outline, arc_steps, rotate
from ..geometry.verify import nearest, thin
from ..pitch.gear import GearData
from ..pitch.pair import PairData
from ..threads import side_by_side
from ..tolerances import DEFAULT, Budget, Tolerances, designed_play
from .contact import ContactData, contact_along
from .frame import ArcFrame, arc_frame
from .gear import ToothedGear, cut_teeth
from .mesh import MeshData, backlash_range, mesh_check, nudge_arc
from .overcut import RackOvercut, concave_spans, rack_overcut
from .plan import ToothPlan, plan_teeth, tooth_count
from .rack import Rack, RackParams
from .relief import MAX_RELIEF_MODULES, Relief, relieve
from .sampling import Stopped

__all__ = ["ToothSpec", "ToothedPairData", "cut_pair", "refuse_corners", "undercut_free_module", "with_clearance"]


class ToothSpec(Protocol):
    """What the teeth stage reads of a profile's [teeth] table (mm, radians)."""

    module: float | None
    count: int | None
    pressure_angle: float
    addendum: float
    dedendum: float
    tip_radius: float
    profile_shift: float
    backlash: float
    clearance: float


@dataclass(frozen=True)
class ToothedPairData:
    plan: ToothPlan
    gears: tuple[ToothedGear, ToothedGear]
    """Outlines within the tolerance (thinned from the fine cut): meshes, checks, flat DXF."""
    fine: tuple[np.ndarray, np.ndarray]
    """The outer rings cut at tolerance × fine_fraction, for fitting DXF arcs."""
    frames: tuple[ArcFrame, ArcFrame]
    mesh: MeshData
    backlash_range: tuple[float, float]
    """Smallest and largest measured play on the pitch curve over a cycle, mm."""
    module_limits: tuple[float, float]
    """Largest module that cuts each gear without undercut (∞ if no convex stretch)."""
    identical_deviation: float | None
    """Largest distance between gear 2 and gear 1 turned onto it, mm (identical pairs)."""
    findings: tuple[Finding, ...]
    relief: Relief | None = None
    """Gear 1's trim by the mate's sweep (None where the rack's teeth mesh as cut)."""
    overcut: tuple[RackOvercut | None, RackOvercut | None] = (None, None)
    """How far a rack or hob would cut beyond each gear's outline (None where its pitch curve is
    convex: there the outline is what a rack leaves)."""
    contact: ContactData | None = None  # always set by cut_pair
    """Contact ratio and working pressure angle along the cycle (:mod:`.contact`)."""


def refuse_corners(gears: Sequence[GearData]) -> None:
    """A :class:`DesignError` for the first gear whose pitch curve has corners."""
    for gear in gears:
        if gear.shape.corners:
            where = ", ".join(f"{math.degrees(c.phi):.2f}°" for c in gear.shape.corners)
            raise DesignError(
                f"{gear.name} has corners (at φ = {where}): a rack cannot roll round a corner, so "
                "teeth need a smooth pitch curve — blend the corners (e.g. gear1.blend_width_deg)"
            )


def undercut_free_module(min_curvature_radius: float, rack: RackParams) -> float:
    """m such that the straight rack flank never reaches below its fold point ρ·sin²α.

    The flank ends (m·(h_f − ρ_f(1 − sin α) − x)) below the pitch curve; the envelope folds at
    ρ_c·sin²α, so m ≤ ρ_c·sin²α/(h_f − ρ_f(1 − sin α) − x).  For a circle ρ_c = z·m/2 gives the
    textbook z ≥ 2/sin²α ≈ 17.1 at 20°.
    """
    depth = rack.dedendum - rack.tip_radius * (1 - math.sin(rack.pressure_angle)) - rack.profile_shift
    if depth <= 0 or not math.isfinite(min_curvature_radius):
        return math.inf
    return min_curvature_radius * math.sin(rack.pressure_angle) ** 2 / depth


def _thinned(gear: ToothedGear, tolerance: float) -> ToothedGear:
    """The same gear with its outline thinned to ``tolerance`` (and its root indices moved)."""
    ring = thin(gear.outline.outer, tolerance)
    roots = gear.outline.outer[gear.space_root]
    return replace(gear, outline=Outline((ring,)), space_root=_nearest(ring, roots))


def _nearest(ring: np.ndarray, points: np.ndarray) -> np.ndarray:
    return nearest(points, ring)[0]


def with_clearance(gear: ToothedGear, clearance: float, tolerance: float) -> ToothedGear:
    """The outline offset inwards by ``clearance`` (round joins sampled from the tolerance).

    Every flank moves in by the clearance, so a tooth keeps a tip land only while the clearance
    is under half its tip land: beyond that the teeth wear down to bumps, which is refused (a
    tooth already pointed may lose up to 0.1 module of height)."""
    if clearance <= 0:
        return gear
    module = gear.rack.params.module
    largest = max(float(np.min(gear.tip_thickness)), 0.2 * module) / 2
    segments = max(2, arc_steps(clearance, tolerance, np.pi / 2))  # shapely counts segments per quarter
    shrunk = shapely.Polygon(gear.outline.outer).buffer(-clearance, join_style="round", quad_segs=segments)
    if clearance >= largest or shrunk.geom_type != "Polygon" or shrunk.is_empty:
        raise DesignError(
            f"teeth.clearance = {clearance:g}: the offset would wear the teeth down to bumps; the largest "
            f"clearance these teeth take is {largest:.3f} mm (half the thinnest tip land)"
        )
    ring = np.asarray(shapely.geometry.polygon.orient(shrunk, 1.0).exterior.coords)[:-1]
    return replace(gear, outline=Outline((ring,)), space_root=_nearest(ring, gear.outline.outer[gear.space_root]))


def _rack(params: ToothSpec, module: float, shift: float, min_fillet: float = 0.0) -> Rack:
    """The generating rack; its tip rounded with at least ``min_fillet`` mm (a router's tool
    radius: the root fillet it cuts is then no tighter than the tool), refused in one line
    naming process.tool_diameter where the rack's tip has no room for it."""
    tip = max(params.tip_radius, min_fillet / module)
    rack = RackParams(
        module=module,
        pressure_angle=params.pressure_angle,
        addendum=params.addendum,
        dedendum=params.dedendum,
        tip_radius=tip,
        profile_shift=shift,
        thinning=params.backlash / 2,
    )
    if tip == params.tip_radius:
        return Rack.from_params(rack)
    a = params.pressure_angle
    room = math.pi * module / 4 - shift * module * math.tan(a) + params.backlash / 4
    room += (shift - params.dedendum) * module * math.tan(a)  # the rack tooth's half width at its tip line
    largest = max(room, 0.0) * math.cos(a) / (1 - math.sin(a))  # the fillet the tip has room for
    if min_fillet > largest:
        raise DesignError(
            f"process.tool_diameter = {2 * min_fillet:g}: the tool cannot reach the roots of teeth of module "
            f"{module:.4g} mm; at most {2 * largest:.3f} mm fits their tooth spaces (the root fillet is the tool's "
            f"radius), or teeth.module ≥ {module * min_fillet / largest:.3g} mm for this tool"
            if largest > 0
            else f"process.tool_diameter = {2 * min_fillet:g}: the rack tooth comes to a point before its tip line"
        )
    return Rack.from_params(rack)


def _planned(pair: PairData, params: ToothSpec, tol: Tolerances, identical: float | None):
    """Both pitch curves by arc length and the teeth planned on them (the count checked on the
    first before the mate's map is made), or a one-line refusal."""
    counted = dict(module=params.module, count=params.count, identical_rotation=identical)
    first = arc_frame(pair.gear1, tol=tol)
    tooth_count(first, pair.lobes, **counted)  # a count that cannot be refuses before the mate's map
    frames = (first, arc_frame(pair.gear2, tol=tol))
    plan = plan_teeth(*frames, pair.lobes, **counted)
    if params.backlash >= math.pi * plan.module / 2:
        raise DesignError(
            f"teeth.backlash = {params.backlash:g}: it would thin every tooth to under half its thickness; "
            f"the largest backlash module {plan.module:.4g} takes is {math.pi * plan.module / 2:.3f} mm"
        )
    return frames, plan


def _identical_deviation(fine, identical: float) -> float:
    """Both gears are cut by the same code from the same curve, so their vertices coincide when
    they are the same part: the largest vertex-to-nearest-vertex distance says so."""
    turned = rotate(fine[0].outline.outer, -identical)
    return float(np.max(nearest(fine[1].outline.outer, turned)[1]))


def _cut_both(frames, plan, params: ToothSpec, min_fillet: float, fine_tol: float) -> tuple:
    """Both gears cut side by side at the fine tolerance (opposite profile shifts), their flank
    clearance taken off; a gear that cannot be cut calls off its mate's cut and raises."""
    shifts = (params.profile_shift, -params.profile_shift)
    stop = threading.Event()  # a gear that cannot be cut calls off its mate's cut

    def cut(frame, z, phase, shift):
        try:
            gear = cut_teeth(
                frame, _rack(params, plan.module, shift, min_fillet), z, phase, tolerance=fine_tol, stop=stop
            )
            return with_clearance(gear, params.clearance, fine_tol)
        except BaseException:
            stop.set()
            raise

    with side_by_side() as pool:  # the two gears side by side
        jobs = [pool.submit(cut, *job) for job in zip(frames, plan.teeth, plan.phases, shifts)]
        failed = [e for e in (job.exception() for job in jobs) if e is not None and not isinstance(e, Stopped)]
        if failed:
            raise failed[0]
        return tuple(job.result() for job in jobs)


def _overcuts(frames, fine, gears, tolerance: float) -> tuple:
    """Where the rack's tip cuts into each gear's concave stretches beyond the tolerance (None
    where it does not)."""
    return tuple(
        rack_overcut(
            frames[i],
            g.rack,
            g.teeth,
            g.phase,
            g.outline.outer,
            concave_spans(frames[i], gears[i].shape.concave_intervals),
            tolerance=tolerance,
        )
        for i, g in enumerate(fine)
    )


def cut_pair(
    pair: PairData,
    gears: Sequence[GearData],
    params: ToothSpec,
    *,
    mate_rotation: float | None = None,
    tol: Tolerances = DEFAULT,
    budget: Budget | None = None,
    relief: bool = True,
    min_fillet: float = 0.0,
) -> ToothedPairData:
    """Teeth on both gears of a rolling pair, proven to mesh.

    ``mate_rotation`` is δ with r2(θ) = r1(θ + δ) when gear 2 is gear 1 turned (a self-conjugate
    pair), None otherwise: then the teeth are planned so the two gears are one part.
    ``relief`` trims gear 1 by the mate's sweep where the proof finds the rack-cut pair too deep
    (:mod:`.relief`); False keeps the rack's teeth as cut.  ``min_fillet`` (mm) is the smallest
    root fillet: a router's tool radius.  ``budget`` is the design's (made once per design and
    passed down); left out, the budget of ``tol.outline_mm``.
    """
    refuse_corners(gears)
    # a self-conjugate noncircular pair: gear 2 is gear 1 turned, and the count must make the
    # toothed gears one part too (a circle's mate is the same part at any count and turn)
    identical = None if gears[0].round else mate_rotation
    frames, plan = _planned(pair, params, tol, identical)
    b = budget if budget is not None else Budget(tol.outline_mm, tol.fine_fraction)
    fine = _cut_both(frames, plan, params, min_fillet, b.fine)
    toothed = tuple(_thinned(g, b.fit) for g in fine)
    mesh, play_range = _prove(pair, toothed, frames, params, plan.module, b.tolerance)
    trim = None
    if mesh.too_deep and relief and not plan.identical and mesh.max_depth <= MAX_RELIEF_MODULES * plan.module:
        relieved, trim = relieve(pair, fine[0], toothed, frames, mesh, deep=np.array(mesh.too_deep))
        fine, toothed = (relieved, fine[1]), (_thinned(relieved, b.fit), toothed[1])
        mesh, play_range = _prove(pair, toothed, frames, params, plan.module, b.tolerance)
    limits = tuple(
        undercut_free_module(g.shape.min_curvature_radius, toothed[i].rack.params) for i, g in enumerate(gears)
    )
    overcut = _overcuts(frames, fine, gears, b.tolerance)
    deviation = _identical_deviation(fine, identical) if plan.identical else None
    return ToothedPairData(
        plan=plan,
        gears=toothed,
        fine=tuple(g.outline.outer for g in fine),
        frames=frames,
        mesh=mesh,
        backlash_range=play_range,
        module_limits=limits,
        identical_deviation=deviation,
        findings=tuple(
            _findings(gears, plan, toothed, mesh, limits)
            + _relief_findings(gears, trim)
            + [finding("rack-overcut", o.sentence(g.name), g.name) for g, o in zip(gears, overcut) if o and o.cannot]
        ),
        relief=trim,
        overcut=overcut,
        contact=contact_along(pair, (toothed[0].rack, toothed[1].rack)),
    )


def _prove(pair, toothed, frames, params, module: float, tolerance: float) -> tuple[MeshData, tuple[float, float]]:
    """The mesh proof and the play; interference counts as negative play (its depth along the
    normal, over cos α on the pitch curve)."""
    play = designed_play(backlash=params.backlash, clearance=params.clearance, pressure_angle=params.pressure_angle)
    # the mesh proof and the play measurement are independent, and shapely's vectorised GEOS
    # calls release the GIL: run them side by side on the machine's two cores
    with side_by_side() as pool:
        mesh_job = pool.submit(mesh_check, pair, toothed, frames, tolerance=tolerance, play=play)
        limit = 2 * nudge_arc(module=module, tolerance=tolerance, play=play)
        play_job = pool.submit(backlash_range, pair, toothed, frames, limit=limit)
        mesh, play_range = mesh_job.result(), play_job.result()
    if mesh.max_depth > mesh.allowed_depth:
        play_range = (-mesh.max_depth / math.cos(params.pressure_angle), play_range[1])
    return mesh, play_range


def _relief_findings(pitch, trim: Relief | None) -> list[Finding]:
    if trim is None:
        return []
    name = pitch[0].name
    return [
        finding(
            "relief",
            f"{name}: {trim.teeth} teeth trimmed by {pitch[1].name}'s sweep ({trim.positions} positions) where "
            f"the rack's envelope cut {trim.depth_before * 1e3:.3g} µm into it; {trim.area:.3g} mm² removed",
            name,
        )
    ]


def _findings(pitch, plan, gears, mesh, limits) -> list[Finding]:
    out = []
    for gear_data, gear, limit in zip(pitch, gears, limits):
        name = gear_data.name
        if gear.undercut:
            folded = gear.undercut_depth > 0
            parts = []
            if np.any(folded):
                k = int(np.argmax(gear.undercut_depth))
                parts.append(
                    f"{int(np.count_nonzero(folded))} of {2 * gear.teeth} flanks reach up to "
                    f"{gear.undercut_depth[k]:.3f} mm below their fold point (worst at φ = "
                    f"{math.degrees(gear.flank_phi[k]):.1f}°; no undercut needs a module ≤ {limit:.3f} mm)"
                )
            looped = np.nonzero(gear.space_loops)[0]
            if len(looped):
                angles = (gear.tooth_phi[looped[:4]] - np.pi / gear.teeth) % (2 * np.pi)
                where = ", ".join(f"{math.degrees(a):.1f}°" for a in angles)
                parts.append(
                    f"the rack's path crosses itself in {len(looped)} tooth spaces (near φ = {where}"
                    f"{', …' if len(looped) > 4 else ''}); the outline keeps what the rack leaves"
                )
            out.append(finding("undercut", f"{name}: " + "; ".join(parts), name))
        thinnest = float(np.min(gear.tip_thickness))
        if thinnest < 0.2 * plan.module:
            pointed = len(gear.pointed)
            out.append(
                finding(
                    "pointed",
                    f"{name}: {pointed} pointed teeth, thinnest tip land {max(thinnest, 0):.3f} mm "
                    f"(under 0.2·m = {0.2 * plan.module:.3f} mm); use a smaller addendum, a profile shift "
                    "or more teeth"
                    if pointed
                    else f"{name}: thinnest tip land {thinnest:.3f} mm, under 0.2·m = {0.2 * plan.module:.3f} mm",
                    name,
                )
            )
    if not mesh.meshes:
        out.append(
            finding(
                "interference",
                f"the toothed pair overlaps by up to {mesh.max_overlap:.4g} mm² in mesh (allowed "
                f"{mesh.allowed_overlap:.4g} mm², at driver angle {math.degrees(mesh.worst_phi):.1f}°)"
                if mesh.max_overlap > mesh.allowed_overlap
                else f"the toothed pair cuts {mesh.max_depth * 1e3:.3g} µm deep into each other in mesh (allowed "
                f"{mesh.allowed_depth * 1e3:.3g} µm, from the writing tolerance), at driver angle "
                f"{math.degrees(mesh.depth_at[0]):.2f}°, tooth {mesh.depth_at[1]} of {pitch[0].name}, "
                f"{mesh.depth_at[2]:+.3f} mm from its pitch curve"
                if mesh.max_depth > mesh.allowed_depth
                else f"the nudged mesh test found a position without contact ({mesh.nudged_min_overlap:.3g} mm²)",
                "pair",
            )
        )
    return out
