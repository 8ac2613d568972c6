"""Builds of the mechanisms beyond gear pairs: roller bodies, the rolling wheel, carrier trains.

Each ``build_*`` computes the mechanism, checks it against its paper and an independent
method, and — given a folder — writes its report, charts and parts (``folder=None`` for
``gearcad check``).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from .arcfit import decimate
from .bodies import rollers as RB
from .build import Part, part_drawing
from .diagnostics import Finding, finding
from .errors import DesignError
from .export import charts_more
from .export.dxf import write_dxf
from .export.mesh import SolidItem, extrude, write_3mf, write_stl
from .outline import Outline, rotate
from .parts import circle_ring, with_bore
from .pitch import shapes
from .profiles import CarrierTrainParams, RollerBodyParams, RollingWheelParams
from .teeth.frame import arc_frame
from .teeth.gear import cut_teeth
from .teeth.rack import Rack, RackParams
from .tolerances import DEFAULT
from .trains import carrier as CT
from .trains import rack_drive as RD

__all__ = ["OtherResult", "build_roller_body", "build_rolling_wheel", "build_carrier_train"]

TWO_PI = 2 * math.pi


@dataclass(frozen=True)
class OtherResult:
    name: str
    summary: str
    report: dict
    findings: tuple[Finding, ...]
    files: dict
    seconds: float


def _write_parts(folder: Path, parts: list, placements: list, out, report_files: dict) -> None:
    """Each part's DXF/STL/3MF, and the assembly (DXF and 3MF) from (part, angle, offset)."""
    solids = {}
    for part in parts:
        if "dxf" in out.formats:
            path = folder / f"{part.name}.dxf"
            n = write_dxf(path, part_drawing([part], out, placed=False), flavour=out.dxf)
            report_files[path.name] = {"bytes": path.stat().st_size, "kind": "dxf", "vertices": n}
        if {"stl", "3mf"} & set(out.formats):
            solid = extrude(part.outline, out.thickness, name=part.name, chamfer=out.chamfer)
            solids[part.name] = solid
            for fmt in ("stl", "3mf"):
                if fmt in out.formats:
                    path = folder / f"{part.name}.{fmt}"
                    count = write_stl(path, solid) if fmt == "stl" else write_3mf(path, [SolidItem(solid)])
                    report_files[path.name] = {
                        "bytes": path.stat().st_size,
                        "kind": fmt,
                        "triangles": count,
                        "volume": solid.volume,
                    }
    placed = []
    for part, angle, offset in placements:
        turn = lambda ring, a=angle: rotate(ring, a)  # noqa: E731
        placed.append(
            Part(
                part.name,
                tuple(offset),
                Outline(tuple(turn(r) for r in part.outline.rings)),
                Outline(tuple(turn(r) for r in part.fine.rings)),
                turn(part.pitch),
                turn(part.pitch_fine),
            )
        )
    if "dxf" in out.formats:
        path = folder / "assembly.dxf"
        n = write_dxf(path, part_drawing(placed, out, placed=True), flavour=out.dxf)
        report_files[path.name] = {"bytes": path.stat().st_size, "kind": "dxf", "vertices": n}
    if "3mf" in out.formats:
        path = folder / "assembly.3mf"
        items = [SolidItem(solids[p.name], a, (o[0], o[1], 0.0)) for p, a, o in placements]
        triangles = write_3mf(path, items)
        report_files[path.name] = {"bytes": path.stat().st_size, "kind": "3mf", "triangles": triangles}


def _part(name: str, ring_fine: np.ndarray, mark_fine: np.ndarray, tol: float, bore, *, module=None):
    fine_tol = tol * DEFAULT.fine_fraction
    outer = decimate(ring_fine, tol - fine_tol)
    mark = decimate(mark_fine, tol - fine_tol)
    return Part(
        name,
        (0.0, 0.0),
        with_bore(outer, bore, tol, part=name, module=module),
        with_bore(ring_fine, bore, fine_tol, part=name, module=module),
        mark,
        mark_fine,
    )


def _finish(folder, name, report, findings, files, start, summary) -> OtherResult:
    report["warnings"] = [f.as_dict() for f in findings]
    report["files"] = files
    if folder is not None:
        files["report.json"] = {"kind": "json"}
        (folder / "report.json").write_text(json.dumps(report, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    return OtherResult(name, summary, report, tuple(findings), files, time.perf_counter() - start)


# --------------------------------------------------------------------------- roller bodies


def _oscillation(p: RollerBodyParams) -> RB.Oscillation:
    if p.direction == "series":
        osc = RB.Oscillation(p.f, p.g)
    else:
        osc = RB.harmonic(p.direction, p.amplitude, p.m)
    osc.check()
    return osc


def build_roller_body(p: RollerBodyParams, folder: Path | None) -> OtherResult:
    start = time.perf_counter()
    osc = _oscillation(p)
    r = p.roller_radius
    findings: list[Finding] = []
    limits = {}
    if p.direction != "series":
        for m in (3, 6, 9, 12, 15):
            limits[m] = (
                RB.amplitude_limit(p.direction, m, r=r, test="convex"),
                RB.amplitude_limit(p.direction, m, r=r, test="simple"),
            )
    simple, convex = RB.is_simple(osc, r=r), RB.is_convex(osc, r=r)
    if not simple:
        limit = f" (largest simple amplitude for m = {p.m}: {limits[p.m][1]:.6f})" if limits else ""
        raise DesignError(f"body.amplitude = {p.amplitude:g}: the body contour crosses itself or has cusps{limit}")
    if not convex:
        findings.append(finding("concave", "the body contour has concave stretches (it is not an 'oval')", "body"))
    # kinematics of the centre at uniform rotation, numerically over one turn, against eq. 11
    w = p.rpm * TWO_PI / 60
    t = np.linspace(0.0, TWO_PI / w, 20001)
    _, vel, acc = RB.point_motion(osc, 0.0, 0.0, w=w, t=t)
    vmax, amax = float(np.max(np.hypot(*vel.T))) * p.scale, float(np.max(np.hypot(*acc.T))) * p.scale
    report = {
        "schema": 1,
        "name": p.name,
        "title": p.title,
        "mechanism": "roller-body",
        "units": {
            "length": "mm (body lengths in units of R in 'body_units')",
            "speed": "mm/s",
            "acceleration": "mm/s^2",
        },
        "body": {
            "scale": p.scale,
            "roller_radius": r,
            "direction": p.direction,
            "amplitude": p.amplitude,
            "m": p.m,
            "convex": convex,
            "simple": simple,
            "amplitude_limit_convex": limits[p.m][0] if limits else None,
            "amplitude_limit_simple": limits[p.m][1] if limits else None,
        },
        "centre": {"rpm": p.rpm, "w": w, "v_max": vmax, "a_max": amax},
    }
    if p.direction == "horizontal":
        v_closed, a_closed = RB.centre_extremes(p.amplitude * p.scale, p.m, w)
        report["centre"].update(v_max_closed_form=v_closed, a_max_closed_form=a_closed)
    if limits:
        ms = np.array(sorted(limits))
        conv = np.array([limits[m][0] for m in ms])
        k, logc = np.polyfit(np.log(ms), np.log(conv), 1)
        report["limits"] = {
            "m": ms.tolist(),
            "convex": conv.tolist(),
            "simple": [limits[m][1] for m in ms],
            "paper_by_eye": [0.15, 0.05, 0.025, 0.01, 0.005],
            "paper_regression": [1.74 * m**-2.07 for m in ms],
            "power_law_convex": {"coefficient": float(math.exp(logc)), "exponent": float(k)},
        }
    files: dict = {}
    tol = p.output.tolerance
    summary = (
        f"{'convex' if convex else 'not convex'}, "
        + (f"amplitude limits convex {limits[p.m][0]:.5f} / simple {limits[p.m][1]:.5f} R, " if limits else "")
        + f"centre Vmax {vmax:.4g} mm/s"
    )
    teeth = _toothed_body(osc, p) if p.roller_teeth else None
    if teeth is not None:
        report["teeth"] = {k: v for k, v in teeth.items() if not k.startswith("_")}
        summary += f", {teeth['body_teeth']}/{teeth['roller_teeth']} teeth m = {teeth['module']:.4f}"
        if teeth["roller_radius"] != r:
            findings.append(
                finding(
                    "teeth-fit",
                    f"roller radius {r:g} R adjusted to {teeth['roller_radius']:.6f} R so that the body carries "
                    f"a whole number of teeth ({teeth['body_teeth']}) of the rollers' module",
                    "body",
                )
            )
        r = teeth["roller_radius"]
    if folder is not None:
        # enough samples that chords sag at most a quarter of the tolerance where the contour
        # (or the roller path) bends most: sag ≈ κ·ds²/8
        probe = np.linspace(0, TWO_PI, 4096, endpoint=False)
        kappa = float(np.max(np.abs(RB.contour_curvature(osc, probe, r=r)))) / p.scale
        ds = math.sqrt(8 * tol * DEFAULT.fine_fraction / max(kappa, 1e-12))
        length = float(np.sum(np.hypot(*np.diff(RB.contour(osc, probe, r=r), axis=0).T))) * p.scale
        tau = np.linspace(0, TWO_PI, max(256, int(math.ceil(2 * length / ds))), endpoint=False)
        body = RB.contour(osc, tau, r=r)[::-1] * p.scale  # τ runs clockwise: reverse for CCW
        path = np.column_stack([np.sin(tau) + RB._series(osc.f, tau), np.cos(tau) + RB._series(osc.g, tau)])[::-1]
        centres = [(p.scale * math.sin(a), p.scale * math.cos(a)) for a in (0.0, TWO_PI / 3, 2 * TWO_PI / 3)]
        fine = tol * DEFAULT.fine_fraction
        if teeth is None:
            parts = [
                _part("body", body, path * p.scale, tol, p.bore),
                _part("roller", circle_ring(r * p.scale, fine), circle_ring(r * p.scale, fine), tol, _no_bore()),
            ]
            turns = [0.0, 0.0, 0.0]
        else:
            parts = [
                _part("body", teeth["_body_ring"], body, tol, p.bore, module=teeth["module"]),
                _part("roller", teeth["_roller_ring"], circle_ring(r * p.scale, fine), tol, _no_bore()),
            ]
            turns = teeth["_roller_turns"]
        placements = [(parts[0], 0.0, (0.0, 0.0))] + [(parts[1], a, c) for a, c in zip(turns, centres)]
        body_polygon = _placed_polygon(parts[0], 0.0, (0.0, 0.0))
        overlap = max(
            float(body_polygon.intersection(_placed_polygon(parts[1], a, c)).area) for a, c in zip(turns, centres)
        )
        report["assembly_overlap"] = overlap
        if teeth is not None:
            # turned a little either way, every roller must bite into the body: they do touch
            nudge = 200 * tol / (r * p.scale)
            report["assembly_nudged_overlap"] = min(
                max(float(body_polygon.intersection(_placed_polygon(parts[1], a + d, c)).area) for d in (-nudge, nudge))
                for a, c in zip(turns, centres)
            )
        if teeth is not None and (
            overlap > 2 * tol * 2.25 * teeth["module"]
            or report["assembly_nudged_overlap"] <= 2 * tol * 2.25 * teeth["module"]
        ):
            findings.append(
                finding("interference", f"the body and a roller overlap by {overlap:.4g} mm² as assembled", "body")
            )
        _write_parts(folder, parts, placements, p.output, files)
        if p.output.charts:
            if limits:
                charts_more.limits_chart(report["limits"], p, folder / "amplitude_limits.png")
                files["amplitude_limits.png"] = {"kind": "png"}
            charts_more.field_chart(osc, p, folder / "velocity_field.png")
            files["velocity_field.png"] = {"kind": "png"}
    return _finish(folder, p.name, report, findings, files, start, summary)


def _placed_polygon(part, angle: float, centre) -> shapely.Polygon:
    rings = [rotate(r, angle) + np.asarray(centre) for r in part.outline.rings]
    return shapely.Polygon(rings[0], rings[1:])


def _toothed_body(osc: RB.Oscillation, p: RollerBodyParams) -> dict:
    """Teeth on the body, the rollers as pinions of pitch radius r (one generating rack).

    The rollers' count fixes the module (m = 2r/z_r); the body's contour is the roller path P
    moved in by r, so its perimeter is P_path − 2πr, and a whole body count z_b needs
    r = P_path·z_r / (2π(z_r + z_b)) — the roller radius is adjusted to it.
    """
    from .teeth.frame import ParametricFrame

    z_r = p.roller_teeth
    u = np.linspace(0, TWO_PI, 2048, endpoint=False)

    def path_points(tau):
        return np.column_stack([np.sin(tau) + RB._series(osc.f, tau), np.cos(tau) + RB._series(osc.g, tau)])

    path = ParametricFrame(path_points(-u))  # τ runs clockwise; u = −τ counter-clockwise
    body0 = path.perimeter - TWO_PI * p.roller_radius
    m0 = 2 * p.roller_radius / z_r
    z_b = max(3, int(round(body0 / (math.pi * m0))))
    r = path.perimeter * z_r / (TWO_PI * (z_r + z_b))
    if not RB.is_simple(osc, r=r):
        raise DesignError(f"teeth.roller_count = {z_r}: the roller radius it needs ({r:.4f} R) breaks the contour")
    module = 2 * r * p.scale / z_r
    frame = ParametricFrame(RB.contour(osc, -u, r=r) * p.scale)
    if not math.isclose(frame.perimeter, z_b * math.pi * module, rel_tol=1e-9):
        raise DesignError("the body's perimeter does not fit its teeth (the contour is not a parallel of its path)")
    fine = p.output.tolerance * DEFAULT.fine_fraction
    rack = Rack.from_params(RackParams(module=module, pressure_angle=p.pressure_angle))
    body = cut_teeth(frame, rack, z_b, rack.pitch / 2, tolerance=fine)
    roller = cut_teeth(arc_frame(shapes.circle(r * p.scale)), rack, z_r, rack.pitch / 2, tolerance=fine)
    turns = []
    for k in range(3):
        tau = TWO_PI * k / 3
        s_k = float(frame.arc_at(np.array([-tau]))[0])
        space = ((s_k - rack.pitch / 2) / rack.pitch) % 1.0  # 0 where a body space is centred
        centre = path_points(np.array([tau]))[0] * p.scale
        contact = RB.contour(osc, np.array([tau]), r=r)[0] * p.scale
        theta = math.atan2(*(contact - centre)[::-1])
        # the two curves run opposite ways at the contact, so the tooth pattern is mirrored: a
        # body space centre `space` pitches behind the contact needs a roller tooth centre as far
        # ahead; the roller's spaces sit at arc r·(angle − turn) = pitch/2 + j·pitch
        turns.append(theta - (rack.pitch / 2 + ((0.5 - space) % 1.0) * rack.pitch) / (r * p.scale))
    return {
        "body_teeth": z_b,
        "roller_teeth": z_r,
        "module": module,
        "roller_radius": r,
        "requested_roller_radius": p.roller_radius,
        "body_undercut": body.undercut,
        "roller_undercut": roller.undercut,
        "_body_ring": body.outline.outer,
        "_roller_ring": roller.outline.outer,
        "_roller_turns": turns,
    }


def _no_bore():
    from .parts import BoreParams

    return BoreParams()


# --------------------------------------------------------------------------- rolling wheel


def build_rolling_wheel(p: RollingWheelParams, folder: Path | None) -> OtherResult:
    start = time.perf_counter()
    d = RD.RackDrive(p.r, p.R, p.L, p.H)
    beta0 = float(RD.inclination(d))
    l0 = float(RD.rack_length(d))
    beta_end = float(RD.inclination(d, p.L - p.travel))
    phi1_end = RD._contour_state(d, beta_end)[0] if abs(beta_end - beta0) > 0 else p.travel / p.R * 2 * p.R / p.r
    phi1 = np.linspace(0.0, phi1_end, 401)
    by_contour = RD.law_by_contour(d, phi1)
    by_rates = RD.law_by_rates(d, phi1)
    difference = float(np.max(np.abs(by_contour - by_rates)))
    w1 = p.driver_rpm * TWO_PI / 60
    L = p.L - p.R * by_contour
    w2, w3, e2 = RD.rates(d, L, omega1=w1)
    paper_e2 = RD.paper_eps2(d, L, omega1=w1)
    findings = []
    paper_l = RD.paper_rack_length(d)
    if abs(paper_l - l0) > 1e-9 * l0:
        findings.append(
            finding(
                "paper-formula",
                f"printed eq. 2 (l² = L² + H² + (R − r)²) gives l = {paper_l:.4f} mm; eq. 1 gives "
                f"l² = L² + H² − (R − r)², l = {l0:.4f} mm (used)",
                "drive",
            )
        )
    scale = float(np.max(np.abs(e2))) or 1.0
    gap = float(np.max(np.abs(paper_e2 - e2)))
    if gap > 1e-9 * scale:
        findings.append(
            finding(
                "paper-formula",
                "printed eq. 9 lacks a factor 1/(1 + cos β) in its second term: its ε2 differs from the derivative of "
                f"eq. 8 by up to {gap:.4g} rad/s² here ({100 * gap / scale:.0f}% "
                "of the largest ε2); the corrected form is used",
                "drive",
            )
        )
    if difference > 1e-9:
        findings.append(finding("not-closed", f"the two motion laws differ by {difference:.3g} rad", "drive"))
    report = {
        "schema": 1,
        "name": p.name,
        "title": p.title,
        "mechanism": "rolling-wheel",
        "units": {"length": "mm", "angle": "rad", "speed": "rad/s", "acceleration": "rad/s^2"},
        "drive": {"r": p.r, "R": p.R, "L": p.L, "H": p.H, "travel": p.travel, "driver_rpm": p.driver_rpm},
        "geometry": {
            "beta_start": beta0,
            "beta_end": beta_end,
            "rack_length_start": l0,
            "rack_length_paper_eq2": paper_l,
            "beta_paper_eq10": RD.paper_inclination(d),
        },
        "motion": {
            "phi1_end": float(phi1_end),
            "phi2_end": float(by_contour[-1]),
            "law_difference": difference,
            "omega2_min": float(w2.min()),
            "omega2_max": float(w2.max()),
            "omega3_min": float(w3.min()),
            "omega3_max": float(w3.max()),
            "eps2_min": float(e2.min()),
            "eps2_max": float(e2.max()),
            "ratio_start": float(w2[0] / w1),
            "ratio_horizontal_rack": p.r / (2 * p.R),
        },
    }
    files: dict = {}
    if folder is not None:
        tol = p.output.tolerance
        ft = tol * DEFAULT.fine_fraction
        parts = [
            _part("wheel1", circle_ring(p.r, ft), circle_ring(p.r, ft), tol, _no_bore()),
            _part("wheel2", circle_ring(p.R, ft), circle_ring(p.R, ft), tol, _no_bore()),
        ]
        _write_parts(folder, parts, [(parts[0], 0.0, (p.L, p.H)), (parts[1], 0.0, (0.0, 0.0))], p.output, files)
        if p.output.charts:
            charts_more.rolling_chart(phi1, by_contour, by_rates, w2, e2, w3, p, folder / "motion.png")
            files["motion.png"] = {"kind": "png"}
    summary = (
        f"β {math.degrees(beta0):.3f}°→{math.degrees(beta_end):.3f}°, ω2/ω1 {w2.min() / w1:.5f}…"
        f"{w2.max() / w1:.5f}, motion laws agree to {difference:.1e} rad"
    )
    return _finish(folder, p.name, report, findings, files, start, summary)


# --------------------------------------------------------------------------- carrier trains


def _train_layout(p: CarrierTrainParams):
    """Radii, centres on the carrier's x axis, and each gear's kind (external / ring)."""
    radii = [p.module * z / 2 for z in p.teeth]
    ring = [False] * len(radii)
    for k, mesh in enumerate(p.meshes):
        if mesh == "internal":
            big = k if radii[k] > radii[k + 1] else k + 1
            ring[big] = True
    for k, mesh in enumerate(p.meshes):
        for j in (k, k + 1):
            other = k + 1 if j == k else k
            if ring[j] and mesh == "external":
                raise DesignError(
                    f"train.meshes: {p.names[j]} would need internal teeth (to mesh inside) and external teeth "
                    f"(for {p.names[other]}) on the same pitch circle"
                )
    centres = [0.0]
    for k, mesh in enumerate(p.meshes):
        step = radii[k] + radii[k + 1] if mesh == "external" else radii[k] - radii[k + 1]
        centres.append(centres[-1] + step)
    return radii, centres, ring


def _gear_rings(p: CarrierTrainParams, k: int, ring: bool, tol: float):
    """Gear k's outline (fine) and its pitch circle; a ring gear is a rim minus a gear-shaped
    hole whose teeth are the ring's tooth spaces (rack addendum and dedendum swapped)."""
    z, m = p.teeth[k], p.module
    r = m * z / 2
    frame = arc_frame(shapes.circle(r))
    if ring:
        rack = Rack.from_params(RackParams(module=m, pressure_angle=p.pressure_angle, addendum=1.25, dedendum=1.0))
    else:
        rack = Rack.from_params(RackParams(module=m, pressure_angle=p.pressure_angle))
    gear = cut_teeth(frame, rack, z, rack.pitch / 2, tolerance=tol)  # a tooth (or ring space) at angle 0
    return gear, circle_ring(r, tol)


def build_carrier_train(p: CarrierTrainParams, folder: Path | None) -> OtherResult:
    start = time.perf_counter()
    radii, centres, ring = _train_layout(p)
    rpm = TWO_PI / 60
    train = CT.solve_train(
        radii,
        p.meshes,
        omega1=p.gear1_rpm * rpm,
        epsilon1=p.gear1_eps,
        carrier=p.carrier_rpm * rpm,
        carrier_eps=p.carrier_eps,
    )
    direct = CT.solve_by_velocities(radii, p.meshes, omega1=p.gear1_rpm * rpm, carrier=p.carrier_rpm * rpm)
    difference = float(np.max(np.abs(direct - train.omega)))
    findings = []
    report = {
        "schema": 1,
        "name": p.name,
        "title": p.title,
        "mechanism": "carrier-train",
        "units": {"length": "mm", "speed": "rad/s", "acceleration": "rad/s^2"},
        "train": {
            "module": p.module,
            "gear1_rpm": p.gear1_rpm,
            "carrier_rpm": p.carrier_rpm,
            "gear1_eps": p.gear1_eps,
            "carrier_eps": p.carrier_eps,
            "velocity_analysis_difference": difference,
        },
        "gears": [
            {
                "name": n,
                "teeth": z,
                "pitch_radius": r,
                "centre": c,
                "internal_teeth": g,
                "omega": float(w),
                "omega_rpm": float(w / rpm),
                "epsilon": float(e),
                "omega_relative_to_carrier": float(rel),
            }
            for n, z, r, c, g, w, e, rel in zip(
                p.names, p.teeth, radii, centres, ring, train.omega, train.epsilon, train.relative
            )
        ],
    }
    files: dict = {}
    if folder is not None:
        tol = p.output.tolerance
        ft = tol * DEFAULT.fine_fraction
        parts, angles, gears = [], [], []
        for k in range(len(radii)):
            gear, pitch = _gear_rings(p, k, ring[k], ft)
            gears.append(gear)
            if ring[k]:
                rim = circle_ring(radii[k] + 3.75 * p.module, ft)
                outer = rim
                hole = gear.outline.outer[::-1]
                part = Part(
                    p.names[k],
                    (0.0, 0.0),
                    Outline((decimate(outer, tol - ft), decimate(hole, tol - ft))),
                    Outline((outer, hole)),
                    decimate(pitch, tol - ft),
                    pitch,
                )
            else:
                part = _part(p.names[k], gear.outline.outer, pitch, tol, p.bore, module=p.module)
            parts.append(part)
        # phase each gear so a tooth meets a space at every contact on the carrier line
        pitch_angle = [TWO_PI / z for z in p.teeth]
        angles = [0.0]
        for k, mesh in enumerate(p.meshes):
            feature = ((0.0 - angles[k]) / pitch_angle[k]) % 1.0  # 0 tooth (or ring space) at angle 0
            if mesh == "external":
                # opposite senses at the contact: the pattern is mirrored (tooth meets space)
                angles.append(math.pi - ((0.5 - feature) % 1.0) * pitch_angle[k + 1])
            else:  # contact at angle 0 on both; a tooth enters a ring space (the hole gear's tooth)
                angles.append(-feature * pitch_angle[k + 1])
        placements = [(part, a, (c, 0.0)) for part, a, c in zip(parts, angles, centres)]
        overlap = 0.0
        for k in range(len(parts) - 1):
            a = _placed_polygon(parts[k], angles[k], (centres[k], 0.0))
            b = _placed_polygon(parts[k + 1], angles[k + 1], (centres[k + 1], 0.0))
            overlap = max(overlap, float(a.intersection(b).area))
        report["train"]["assembly_overlap"] = overlap
        if overlap > 2 * tol * 2.25 * p.module:
            findings.append(
                finding("interference", f"neighbouring gears overlap by {overlap:.4g} mm² as assembled", "train")
            )
        _write_parts(folder, parts, placements, p.output, files)
        if p.output.charts:
            charts_more.train_chart(report, parts, angles, centres, folder / "train.png")
            files["train.png"] = {"kind": "png"}
    summary = ", ".join(f"{g['name']} {g['omega_rpm']:.4g} rpm" for g in report["gears"])
    summary += f"; stopping vs velocities {difference:.1e} rad/s"
    return _finish(folder, p.name, report, findings, files, start, summary)
