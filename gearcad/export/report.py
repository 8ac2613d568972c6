"""report.json: every number a reviewer needs, in mm and radians."""

from __future__ import annotations

import json
import math
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ..design import DesignData, GearData

__all__ = ["report", "write_report", "SCHEMA_VERSION"]

SCHEMA_VERSION = 1


def _gear(g: GearData, lobes: int) -> dict:
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
        "concave_intervals": [list(i) for i in s.concave_intervals],
        "corners": [{"phi": c.phi, "turn": c.turn, "convex": c.convex} for c in s.corners],
    }


def _finite(value):
    """JSON has no NaN or infinity: such a value becomes null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_finite(v) for v in value]
    return value


def _teeth(t, i: int) -> dict:
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


def report(data: DesignData, teeth, parts, files: dict[str, dict]) -> dict:
    """The report as a JSON-ready dict (see README, "report.json")."""
    p, pair, kin = data.params, data.pair, data.kinematics
    n1, n2 = pair.lobes
    out = {
        "schema": SCHEMA_VERSION,
        "name": p.name,
        "mechanism": "gear-pair",
        "title": p.title,
        "units": {"length": "mm", "angle": "rad", "speed": "rad/s", "acceleration": "rad/s^2"},
        "tolerance": p.output.tolerance,
        "gears": [_gear(data.gears[0], n1), _gear(data.gears[1], n2)],
        "pair": {
            "center_distance": pair.center_distance,
            "lobes": [n1, n2],
            "closure_error": pair.closure_error,
            "rolling_residual": pair.rolling_residual,
            "contact_residual": pair.contact_residual,
            "slip_residual": pair.slip_residual,
            "ratio_min": data.ratio_range[0],
            "ratio_max": data.ratio_range[1],
            "mate_shape_difference": data.mate_shape_difference,
        },
        "kinematics": {
            "driver": (p.gear1_name, p.gear2_name)[kin.driver - 1],
            "driver_rpm": p.driver_rpm,
            "driver_speed": kin.driver_speed,
            "follower_speed_min": float(np.min(kin.speed)),
            "follower_speed_max": float(np.max(kin.speed)),
            "follower_acceleration_min": float(np.min(kin.acceleration)),
            "follower_acceleration_max": float(np.max(kin.acceleration)),
        },
        "warnings": [f.as_dict() for f in data.findings + (teeth.findings if teeth else ())],
        "files": files,
    }
    for gear, part in zip(out["gears"], parts):
        gear["part"] = {
            "area": part.outline.area,
            "vertices": part.outline.vertex_count,
            "holes": len(part.outline.rings) - 1,
        }
    out["output"] = {
        "thickness": p.output.thickness,
        "chamfer": p.output.chamfer,
        "kerf": p.output.kerf,
        "dxf": p.output.dxf,
        "layers": {"cut": p.output.cut_layer, "mark": p.output.mark_layer},
        "bore": p.bore.model_dump(),  # a pydantic model now, not a dataclass
    }
    if teeth is not None:
        for i in range(2):
            out["gears"][i]["teeth"] = _teeth(teeth, i)
        mesh = teeth.mesh
        out["pair"]["teeth"] = {
            "identical_parts": teeth.plan.identical,
            "identical_deviation": teeth.identical_deviation,
            "backlash_design": data.params.teeth.backlash,
            "clearance": data.params.teeth.clearance,
            "backlash_min": teeth.backlash_range[0],
            "backlash_max": teeth.backlash_range[1],
            "mesh": {
                "meshes": mesh.meshes,
                "positions": mesh.positions,
                "max_overlap": mesh.max_overlap,
                "allowed_overlap": mesh.allowed_overlap,
                "worst_phi": mesh.worst_phi,
                "nudge": mesh.nudge,
                "nudged_min_overlap": mesh.nudged_min_overlap,
            },
        }
    if data.claim is not None:
        c = data.claim
        out["claim"] = {
            "source": p.claim.source,
            "center_distance": c.center_distance,
            "holds": c.holds,
            "mate_turn": c.turn,
            "shortfall": c.shortfall,
            "shape_difference": c.shape_difference,
        }
    if data.walker is not None:
        out["walker"] = asdict(data.walker)
    return _finite(out)


def write_report(data: DesignData, teeth, parts, files: dict[str, dict], path: Path) -> None:
    text = json.dumps(report(data, teeth, parts, files), indent=2, ensure_ascii=False)
    path.write_text(text + "\n", encoding="utf-8")
