"""A gear pair's report blocks, its summary and its detail lines, from its pitch and teeth stages
(``gear_pair.design`` and the early stages draw them)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..pitch.gear import GearData
from ..profiles import GearPairParams
from ..teeth.pair import ToothedPairData
from .chart_data import Blocks
from .pair_motion import motion_block, motion_phrase
from .pair_pitch import PairDesign

if TYPE_CHECKING:
    from ..teeth.helical import HelicalSections

__all__ = ["report_data", "summary", "details"]


def _gear_block(g: GearData, lobes: int) -> dict:
    s = g.shape
    return {
        "name": g.name,
        "curve": g.curve.name,
        "pivot": list(g.pivot),
        "lobes": lobes,
        "r_min": g.r_min,
        "r_max": g.r_max,
        "perimeter": g.perimeter,
        "convex": s.convex,
        "convexity_margin_min": s.min_margin,
        "min_curvature_radius": s.min_curvature_radius,
        "min_concave_radius": s.min_concave_radius,
        "concave_intervals": [list(i) for i in s.concave_intervals],
        "corners": [{"phi": c.phi, "turn": c.turn, "convex": c.convex} for c in s.corners],
    }


def _teeth_block(t: ToothedPairData, i: int) -> dict:
    gear, plan = t.gears[i], t.plan
    folded = gear.undercut_depth > 0
    return {
        "count": gear.teeth,
        "module": plan.module,
        "requested_module": plan.requested_module,
        "pressure_angle": gear.rack.params.pressure_angle,
        "profile_shift": gear.rack.params.profile_shift,
        "undercut": gear.undercut,
        "undercut_flanks": int(np.count_nonzero(folded)),
        "undercut_depth": float(max(np.max(gear.undercut_depth), 0.0)),
        "undercut_phi": [float(a) for a in gear.flank_phi[folded]],
        "trimmed_spaces": int(np.count_nonzero(gear.space_loops)),
        "min_tip_thickness": float(np.min(gear.tip_thickness)),
        "pointed_teeth": int(len(gear.pointed)),
        "module_limit_undercut": t.module_limits[i],
        "vertices": gear.outline.vertex_count,
        "area": gear.outline.area,
    }


def _helix_block(params: GearPairParams, teeth: ToothedPairData, helical: HelicalSections, proofs) -> dict:
    from ..teeth.helix import helix_data

    out, s = params.output, helical.spacing
    h = helix_data(
        teeth.plan.module,
        params.teeth.helix_angle,
        face_width=out.thickness,
        herringbone=params.teeth.herringbone,
        normal_pressure_angle=params.teeth.pressure_angle,
    )
    first = helical.gears[0]
    return {
        "helix_angle": h.helix_angle,
        "herringbone": h.herringbone,
        "hands": [g.hand for g in helical.gears],
        "normal_module": h.normal_module,
        "transverse_module": h.transverse_module,
        "normal_pressure_angle": h.normal_pressure_angle,
        "transverse_pressure_angle": h.transverse_pressure_angle,
        "axial_pitch": h.axial_pitch,
        "overlap_ratio": h.overlap_ratio,
        "total_shift": h.total_shift,
        "mirror_parts": teeth.plan.identical,
        "sections": len(first.heights),
        "section_vertices": [int(g.rings.shape[1]) for g in helical.gears],
        "section_spacing": s.spacing,
        "spacing_bound": s.bound,
        "spacing_floor": s.floor,
        "loft_deviation": None if math.isnan(s.measured) else s.measured,
        "section_deviation": max(g.deviation for g in helical.gears),
        "mesh_levels": [
            {
                "z": z,
                "meshes": m.meshes,
                "max_overlap": m.max_overlap,
                "max_depth": m.max_depth,
                "nudged_min_overlap": m.nudged_min_overlap,
            }
            for z, m in proofs
        ],
    }


def _pair_teeth_block(params: GearPairParams, pitch: PairDesign, teeth: ToothedPairData, helical) -> Blocks:
    """The pair's ``teeth`` block: its play, contact and the mesh proof over the cycle."""
    mesh = teeth.mesh
    return {
        "identical_parts": teeth.plan.identical and helical is None,
        "identical_deviation": teeth.identical_deviation,
        "backlash_design": params.teeth.backlash,
        "clearance": params.teeth.clearance,
        "backlash_min": teeth.backlash_range[0],
        "backlash_max": teeth.backlash_range[1],
        "contact": teeth.contact.as_dict(),
        "mesh": {
            "meshes": mesh.meshes,
            "positions": mesh.positions,
            "max_overlap": mesh.max_overlap,
            "allowed_overlap": mesh.allowed_overlap,
            "worst_phi": mesh.worst_phi,
            "nudge": mesh.nudge,
            "nudged_min_overlap": mesh.nudged_min_overlap,
            "max_depth": mesh.max_depth,
            "allowed_depth": mesh.allowed_depth,
            "depth_at": dict(zip(("gear1_angle", "tooth", "height"), mesh.depth_at)),
        },
        "relief": None if teeth.relief is None else {"gear": pitch.gears[0].name, **vars(teeth.relief)},
    }


def report_data(
    params: GearPairParams, pitch: PairDesign, teeth: ToothedPairData | None, helical=None, proofs=None
) -> Blocks:
    """The pair's report blocks: its gears, the pair and its kinematics; the teeth, helix, claim,
    walker and fitted motion where the pair has them."""
    pair, kin = pitch.pair, pitch.kinematics
    n1, n2 = pair.lobes
    data = {
        "gears": [_gear_block(pitch.gears[0], n1), _gear_block(pitch.gears[1], n2)],
        "pair": {
            "center_distance": pair.center_distance,
            "lobes": [n1, n2],
            "closure_error": pair.closure_error,
            "rolling_residual": pair.rolling_residual,
            "contact_residual": pair.contact_residual,
            "slip_residual": pair.slip_residual,
            "ratio_min": pitch.ratio_range[0],
            "ratio_max": pitch.ratio_range[1],
            "mate_shape_difference": pitch.mate_shape_difference,
        },
        "kinematics": {
            "driver": (params.gear1_name, params.gear2_name)[kin.driver - 1],
            "driver_rpm": params.driver_rpm,
            "driver_speed": kin.driver_speed,
            "follower_speed_min": float(np.min(kin.speed)),
            "follower_speed_max": float(np.max(kin.speed)),
            "follower_acceleration_min": float(np.min(kin.acceleration)),
            "follower_acceleration_max": float(np.max(kin.acceleration)),
        },
    }
    if teeth is not None:
        for i, overcut in enumerate(teeth.overcut):
            data["gears"][i]["teeth"] = _teeth_block(teeth, i)
            data["gears"][i]["rack_overcut"] = None if overcut is None else overcut.as_dict()
        data["pair"]["teeth"] = _pair_teeth_block(params, pitch, teeth, helical)
    if helical is not None:
        data["pair"]["teeth"]["helix"] = _helix_block(params, teeth, helical, proofs)
    if pitch.claim is not None:
        c = pitch.claim
        data["claim"] = {
            "source": params.claim.source,
            "center_distance": c.center_distance,
            "holds": c.holds,
            "mate_turn": c.turn,
            "shortfall": c.shortfall,
            "shape_difference": c.shape_difference,
        }
    if pitch.walker is not None:
        data["walker"] = dict(vars(pitch.walker))
    if pitch.motion is not None or getattr(params.gear1, "smoothing", 0) > 0:
        from .pair_motion import fitted_blocks

        fitted_blocks(data, params, pitch.gears[0].curve, pitch.motion)
    return data


def summary(pitch: PairDesign, teeth: ToothedPairData | None, findings: int, params: GearPairParams) -> str:
    pair = pitch.pair
    text = (
        f"E = {pair.center_distance:.6f} mm, closure {pair.closure_error:.1e} rad, "
        f"rolling {pair.rolling_residual:.1e} mm"
    )
    if pitch.motion is not None:
        text += ", " + motion_phrase(motion_block(pitch.motion, params))
    if teeth is not None:
        z1, z2 = teeth.plan.teeth
        text += f", {z1}/{z2} teeth m = {teeth.plan.module:.4f}, {'meshes' if teeth.mesh.meshes else 'INTERFERES'}"
    return f"{text}, {findings} warning(s)"


def details(pitch: PairDesign, teeth: ToothedPairData | None) -> list[str]:
    lines = [
        f"{g.name}: r {g.r_min:.4f}…{g.r_max:.4f} mm, perimeter {g.perimeter:.6f} mm, "
        f"{'convex' if g.shape.convex else 'not convex'}, min radius of curvature {g.shape.min_curvature_radius:.4g} mm"
        + (f" (concave {g.shape.min_concave_radius:.4g} mm)" if math.isfinite(g.shape.min_concave_radius) else "")
        for g in pitch.gears
    ]
    lo, hi = pitch.ratio_range
    one, two = (g.name for g in pitch.gears)
    line = f"ratio ω2/ω1 = ω({two})/ω({one}) {lo:.6g}…{hi:.6g} against {one}'s angle"
    if pitch.kinematics.driver == 2:  # the kinematics are per driver turn: say the inverse too
        line += f"; ω({one})/ω({two}) {1 / hi:.6g}…{1 / lo:.6g} per driver ({two}) turn, as charted"
    lines.append(line)
    if pitch.walker is not None:
        w = pitch.walker
        lines.append(
            f"walker: i (paper's method) = {w.i_paper:.6f}, i (rolls and closes) = {w.i:.6f}"
            + (f", i (blended) = {w.i_blended:.6f}" if w.blend_width else "")
        )
    if teeth is not None:
        for g, t in zip(pitch.gears, teeth.gears):
            lines.append(
                f"{g.name}: {t.teeth} teeth, thinnest tip land {t.tip_thickness.min():.3f} mm, "
                f"{'undercut' if t.undercut else 'no undercut'}, {t.outline.vertex_count} vertices"
            )
        lines += [o.sentence(g.name) for g, o in zip(pitch.gears, teeth.overcut) if o is not None]
        lo, hi = teeth.backlash_range
        lines.append(
            f"mesh: max overlap {teeth.mesh.max_overlap:.3g} mm² (allowed {teeth.mesh.allowed_overlap:.3g}), "
            f"depth {teeth.mesh.max_depth * 1e3:.3g} µm (allowed {teeth.mesh.allowed_depth * 1e3:.3g}), "
            f"backlash {lo:.4f}…{hi:.4f} mm; {teeth.contact.sentence()}"
        )
    return lines
