"""Gear pairs (seeds 004 and 002): pitch curves that roll and close, teeth, parts and the proof:
profile → :func:`~.pair_pitch.pitch_design` → teeth (:func:`~gearcad.teeth.pair.cut_pair`) → parts → Design."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from ..bodies import shoe as S
from ..geometry.arcfit import decimate
from ..pitch.discretize import polyline
from ..profiles import GearPairParams
from ..teeth.pair import ToothedPairData, cut_pair
from ..tolerances import DEFAULT, budget, designed_play
from .base import Motion, Table
from .budget import check_section_work, check_teeth_work
from .chart_data import Charts, MeshChart, PitchCurvesChart
from .finish import Contact, Draft, PartSpec
from .pair_papers import PaperExtras, paper_extras
from .pair_pitch import PairDesign, pitch_design
from .pair_report import details, report_data, summary
from .parts import Placement, check_bore

if TYPE_CHECKING:
    pass

__all__ = ["GearPairDetail", "design", "frames_for"]

UNITS = {"length": "mm", "angle": "rad", "speed": "rad/s", "acceleration": "rad/s^2"}


@dataclass(frozen=True)
class GearPairDetail:
    """The pair's own computed objects: pitch stage and (if toothed) teeth stage."""

    pitch: PairDesign
    teeth: ToothedPairData | None
    pitch_rings: tuple[np.ndarray, np.ndarray]
    """Each pitch curve as a polyline within the tolerance, about its pivot (mm)."""
    papers: PaperExtras | None = None
    """What the papers add: seed 004's statements, seed 002's shoe and vehicle speed."""


def _charts(pitch, teeth, rings, papers) -> Charts:
    """Chart file name → what it is drawn from: the pitch curves in mesh, the kinematics, the teeth
    in mesh, and what the papers add (seed 004's type-2 pair, seed 002's vehicle and shoe)."""
    charts: Charts = {"pitch_curves.png": PitchCurvesChart(pitch, rings), "kinematics.png": pitch}
    if teeth is not None:
        charts["mesh.png"] = MeshChart(pitch, teeth)
    extra = papers.charts if papers is not None and papers.charts else {}
    if "elliptic_type2" in extra:
        charts["elliptic_type2.png"] = extra["elliptic_type2"]
    if "walker_speed" in extra:
        charts["vehicle_speed.png"] = extra["walker_speed"]
        charts["paper_pitch_curves.png"] = extra["walker_pitch"]
    if "shoe" in extra:
        charts["shoe.png"] = extra["shoe"]
    return charts


def frames_for(cycle: float, teeth: int | None) -> int:
    """Enough frames that the driver turns at most ~1/3 of a tooth (or 5°) per frame, ≤ 180."""
    step = (2 * math.pi / teeth / 3) if teeth else math.radians(5)
    return int(min(180, max(24, math.ceil(cycle / step))))


def _normal_module_note(params: GearPairParams, pitch: PairDesign, teeth: ToothedPairData):
    from ..findings import finding

    m_n, beta, z1 = params.teeth.module, params.teeth.helix_angle, teeth.plan.teeth[0]
    straight = pitch.gears[0].perimeter / (math.pi * m_n)
    return finding(
        "teeth-fit",
        f"teeth.module = {m_n:g} mm is the normal module (helix_angle_deg = {math.degrees(beta):g}): the "
        f"transverse module m/cos β = {m_n / math.cos(beta):.4f} mm sets the perimeter, so {pitch.gears[0].name} "
        f"has {z1} teeth of transverse module {teeth.plan.module:.4f} mm, where straight teeth of module "
        f"{m_n:g} would fit {straight:.1f}; give teeth.count to choose the count",
        "teeth",
    )


def _pressure_angle(params: GearPairParams, pitch: PairDesign, alpha: float) -> tuple:
    """A ``pressure-angle`` warning where the pair's working pressure angle (``alpha``, the
    rack's transverse one, plus the pitch curves' tilt) exceeds ``teeth.max_pressure_angle_deg``:
    how far, where (the driver's angle), and over which stretches of gear 1's turn."""
    from ..findings import finding
    from ..teeth.contact import working_pressure

    limit = params.teeth.max_pressure_angle_deg
    pair, (one, two) = pitch.pair, (g.name for g in pitch.gears)
    w = working_pressure(pair, alpha, math.radians(limit))
    if not w.above:
        return ()
    largest = math.degrees(w.largest)
    if pitch.kinematics.driver == 2:  # the driver is gear 2: its angle where gear 1 stands at φ1
        turn = float(pair.angle_map(np.array([w.phi1]))[0]) % (2 * math.pi)
        where = f"driver angle {math.degrees(turn):.1f}° ({two}; {one} at {math.degrees(w.phi1):.1f}°)"
    else:
        where = f"driver angle {math.degrees(w.phi1):.1f}° ({one})"
    spans = ", ".join(f"{math.degrees(a):.1f}°–{math.degrees(b):.1f}°" for a, b in w.above)
    total = sum((b - a) % (2 * math.pi) or 2 * math.pi for a, b in w.above)
    return (
        finding(
            "pressure-angle",
            f"{one}/{two}: the working pressure angle reaches {largest:.1f}° at {where}, {largest - limit:.1f}° over "
            f"teeth.max_pressure_angle_deg = {limit:g}; above it over {math.degrees(total):.0f}° of {one}'s turn "
            f"({spans}): the tooth force pushes the shafts apart more than it turns the mate",
            "teeth",
        ),
    )


def _teeth(params: GearPairParams, pitch: PairDesign, tol, b):
    """The pair's teeth (None without), its twisted sections and their mesh proofs (None unless
    helical): cut, checked for work and bore, and proven."""
    if params.teeth is None:
        return None, None, None
    out = params.output
    helical = proofs = None
    beta = params.teeth.helix_angle
    if beta > 0:  # only helical pairs pay for the sections' module
        from ..teeth.helical import pair_sections, section_mesh
        from ..teeth.helix import transverse_teeth
    spec = transverse_teeth(params.teeth, beta) if beta > 0 else params.teeth
    module = spec.module or pitch.gears[0].perimeter / (math.pi * spec.count)
    check_teeth_work([(g.perimeter / (math.pi * module), module) for g in pitch.gears], out.tolerance)
    alike = pitch.mate_shape_difference is not None and pitch.mate_shape_difference < 1e-6
    turn, fillet = pitch.mate_rotation if alike else None, params.process.tool_radius()
    teeth = cut_pair(pitch.pair, pitch.gears, spec, mate_rotation=turn, tol=tol, budget=b, min_fillet=fillet)
    if beta > 0:
        for i, g in enumerate(pitch.gears):  # the bore first: cheap, where the sections are not
            check_bore(g.name, teeth.fine[i], params.bore, out.tolerance, teeth.plan.module)
        helical = pair_sections(
            teeth,
            helix_angle=beta,
            herringbone=params.teeth.herringbone,
            face_width=out.thickness,
            tolerance=out.tolerance,
            clearance=params.teeth.clearance,
            chamfer=out.chamfer,
            names=(pitch.gears[0].name, pitch.gears[1].name),
            check_work=partial(check_section_work, thickness=out.thickness, helix_angle=beta),
        )
        play = designed_play(backlash=spec.backlash, clearance=spec.clearance, pressure_angle=spec.pressure_angle)
        proofs = section_mesh(pitch.pair, helical, teeth.frames, tolerance=out.tolerance, play=play)
        if params.teeth.module is not None:  # say why the count is not what module alone suggests
            teeth = replace(teeth, findings=(*teeth.findings, _normal_module_note(params, pitch, teeth)))
    return teeth, helical, proofs


def _kinematics_table(pitch: PairDesign) -> Table:
    """``kinematics.csv``: the follower's angle, ratio, speed and acceleration against the driver's."""
    kin = pitch.kinematics
    return Table(
        "kinematics.csv",
        ("driver_angle_rad", "follower_angle_rad", "ratio", "follower_speed_rad_s", "follower_acceleration_rad_s2"),
        np.column_stack([kin.driver_angle, kin.follower_angle, kin.ratio, kin.speed, kin.acceleration]),
    )


def design(params: GearPairParams) -> Draft[GearPairDetail]:
    """Design, tooth, make and prove the pair a profile describes."""
    out = params.output
    tol = replace(DEFAULT, outline_mm=out.tolerance)
    b = budget(out.tolerance)  # made once for the design and passed down
    fine_tol = b.fine
    pitch = pitch_design(params, tol=tol)
    teeth, helical, proofs = _teeth(params, pitch, tol, b)
    pitch_fine = [polyline(g.curve, fine_tol) for g in pitch.gears]
    wall = teeth.plan.module if teeth is not None else 0.0
    # a twisted solid's caps are its end sections: the chamfer must fit them too (as the loft checks)
    caps = [tuple(g.rings[[0, -1]]) for g in helical.gears] if helical is not None else [(), ()]
    parts = [
        PartSpec(g.name, teeth.fine[i], bore=params.bore, wall=wall, marks=(pitch_fine[i],), caps=caps[i])
        if teeth is not None
        else PartSpec(g.name, pitch_fine[i], bore=params.bore)
        for i, g in enumerate(pitch.gears)
    ]
    placements = tuple(Placement(g.name, 0.0, g.pivot) for g in pitch.gears)
    if teeth is not None:  # proven over the whole cycle (and on every section of twisted teeth)
        contact = Contact(0, 1, module=teeth.plan.module, nudge=False, touch="mesh")
        meshes = (teeth.mesh,) + tuple(m for _, m in proofs or ())
    else:  # pitch curves roll on each other: they touch along about the smaller radius
        contact, meshes = Contact(0, 1, length=pitch.gears[0].r_min, touch="rolling"), ()
    papers = paper_extras(params, pitch)
    if papers.shoe is not None:  # the walker's leg, standing at hub angle 0 below the wheel's pivot
        parts.append(PartSpec("shoe", papers.shoe))
        placements += (Placement("shoe", 0.0, tuple(S.crank_pin(papers.geometry, 0.0)[0])),)
    findings = pitch.findings + (teeth.findings if teeth is not None else ()) + papers.findings
    if teeth is not None:
        findings += _pressure_angle(params, pitch, teeth.gears[0].rack.params.pressure_angle)
    cycle = pitch.pair.cycle
    phi1 = np.linspace(0.0, cycle, frames_for(cycle, teeth.plan.teeth[0] if teeth else None), endpoint=False)
    rings = tuple(decimate(r, b.fit) for r in pitch_fine)
    return Draft(
        params=params,
        mechanism="gear-pair",
        summary=summary(pitch, teeth, len(findings), params),
        findings=findings,
        parts=tuple(parts),
        placements=placements,
        contacts=(contact,),
        proofs=meshes,
        data={**report_data(params, pitch, teeth, helical, proofs), **papers.data},
        sections={} if helical is None else {p.name: g for p, g in zip(parts, helical.gears)},
        units=UNITS,
        detail=GearPairDetail(pitch, teeth, rings, papers),
        details=tuple(details(pitch, teeth)),
        motion=Motion((parts[0].name, parts[1].name), np.column_stack([-phi1, pitch.pair.angle_map(phi1)])),
        tables=(_kinematics_table(pitch),),
        where="pair",
        placed="meshing parts touch"
        if papers.shoe is None
        else "the gears touch in mesh; the leg (shoe) works in a plane of its own, drawn over the wheel",
        charts=_charts(pitch, teeth, rings, papers),
    )
