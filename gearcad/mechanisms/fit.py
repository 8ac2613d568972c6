"""Parts that fit when made: the process's cutter width and backlash applied to a profile, and
the band of every mesh checked against it (see :mod:`.band`).

``made(params)`` is the profile as it will be cut: a laser's kerf (or a router's tool) offsets
the cut paths, and a gear pair whose profile leaves ``teeth.backlash`` out gets the backlash that
keeps the worst case of the process's tolerance stack free (the closed form for a spur pair:
4·δ/cos α for the edges, 2·Δa·tan α for the centres; the band then measures it, and a pair whose
band still jams is cut once more with what it lacks).  ``with_bands(design)`` adds the bands to
the report, the checks' lines and the findings (``jams`` is an error; ``loose``,
``backlash-fixed`` warn).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..findings import finding
from ..geometry.arcfit import ArcRing
from .band import Band, PairGeometry, pair_band
from .base import Design
from .parts import Part

__all__ = [
    "assembly_marks",
    "backlash_takes",
    "chose_backlash",
    "made",
    "needed_backlash",
    "pair_bands",
    "pair_geometry",
    "with_bands",
]


def _process(params):
    return getattr(params, "process", None)


def needed_backlash(params) -> float:
    """The backlash the closed form asks for under the profile's process (mm; 0 with none)."""
    process, teeth = _process(params), getattr(params, "teeth", None)
    if process is None or process.kind == "none" or teeth is None:
        return 0.0
    alpha = teeth.pressure_angle
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    return 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 4 * params.output.tolerance


def chose_backlash(params) -> bool:
    """Whether gearcad chooses this profile's backlash (a process named, teeth.backlash left out)."""
    process, teeth = _process(params), getattr(params, "teeth", None)
    return (
        process is not None
        and process.kind != "none"
        and params.mechanism == "gear-pair"
        and teeth is not None
        and "backlash" not in teeth.model_fields_set
    )


def backlash_takes(params) -> bool:
    """Whether the teeth keep over half their thickness (a quarter pitch) at the backlash: where
    the band asks for more, the tips reach the mate's roots and no backlash frees them."""
    teeth = params.teeth
    module = teeth.module or 0.0
    return not module or teeth.backlash < 0.8 * math.pi * module / 2


def made(params, extra: float = 0.0):
    """The profile as it will be cut: ``output.kerf`` the process's cutter width, and (a gear
    pair that leaves ``teeth.backlash`` out) the backlash its process needs, plus ``extra``."""
    process = _process(params)
    if process is None or process.kind == "none":
        return params
    update = {"output": params.output.model_copy(update={"kerf": process.cutter(params.output.kerf)})}
    if chose_backlash(params):
        update["teeth"] = params.teeth.model_copy(update={"backlash": needed_backlash(params) + extra})
    return params.model_copy(update=update)


def pair_geometry(design: Design, positions: int | None = None) -> PairGeometry | None:
    """A toothed gear pair's geometry as the band measures it, at ``positions`` driver angles over
    one cycle (default: one per driver tooth, 12 to 48); ``None`` for any other design."""
    detail = design.detail
    teeth = getattr(detail, "teeth", None)
    if design.mechanism != "gear-pair" or teeth is None:
        return None
    pair = detail.pitch.pair
    positions = positions or min(48, max(12, teeth.plan.teeth[0]))
    phi1 = np.linspace(0.0, pair.cycle, positions, endpoint=False)
    first = teeth.gears[0]
    arc = teeth.frames[0].arc(phi1 % (2 * np.pi))
    return PairGeometry(
        rings=tuple(g.outline.outer for g in teeth.gears),
        center_distance=pair.center_distance,
        phi1=phi1,
        phi2=pair.angle_map(phi1),
        r1=pair.gear1.r(phi1 % (2 * np.pi)),
        module=teeth.plan.module,
        pressure_angle=design.params.teeth.pressure_angle,
        teeth=np.floor((arc - first.phase) / first.rack.pitch).astype(int) % first.teeth,
    )


def pair_bands(design: Design) -> tuple[Band, ...]:
    """The band of a toothed gear pair under its profile's process (none: the nominal play only)."""
    params, detail = design.params, design.detail
    geometry = pair_geometry(design)
    if geometry is None:
        return ()
    process = params.process
    names = f"{detail.pitch.gears[0].name}/{detail.pitch.gears[1].name}"
    tol = params.output.tolerance
    return (
        pair_band(
            geometry,
            edge=process.edge(params.output.chamfer),
            spread=process.center_spread(),
            tol=tol,
            backlash=params.teeth.backlash,
            name=names,
        ),
    )


def with_bands(design: Design, bands: tuple[Band, ...]) -> Design:
    """The design with its bands in the report, the checks' lines and the findings."""
    if not bands:
        return design
    process = design.params.process
    findings, lines = list(design.findings), list(design.details)
    fixed = "backlash" in design.params.teeth.model_fields_set
    for b in bands:
        lines.append(
            f"band {b.mesh} ({process.kind}): play {b.nominal[0]:.4f}…{b.nominal[1]:.4f} mm as drawn, "
            f"{b.band[0]:.4f}…{b.band[1]:.4f} mm made; {'fits' if b.fits else 'JAMS'}"
        )
        where = f"tooth {b.worst_tooth} of the driver at driver angle {math.degrees(b.worst_phi):.1f}°"
        if not b.fits:
            findings.append(
                finding(
                    "jams",
                    f"{b.mesh}: the play falls to {b.band[0]:.4f} mm at {where} (edges {b.edge[2]:+.3f} mm, "
                    f"centres −{b.center_spread:.3f} mm); it fits with teeth.backlash "
                    f"+{b.needed_backlash:.3f} mm, or the centres {b.as_dict()['center_distance_change']:.3f} mm "
                    f"apart, or the parts {b.needed_backlash * math.cos(b.pressure_angle) / 4:.3f} mm smaller "
                    "on each edge (if the tips reach the mate's roots, only the centres or smaller parts help)",
                    b.mesh,
                )
            )
            if fixed:
                need = design.params.teeth.backlash + b.needed_backlash
                findings.append(
                    finding("backlash-fixed", f"{b.mesh}: teeth.backlash = {need:.3f} mm keeps the worst case free")
                )
        limit = process.value("max_play")
        if process.kind != "none" and limit and b.band[1] > limit:
            findings.append(
                finding("loose", f"{b.mesh}: the play may reach {b.band[1]:.3f} mm (process.max_play = {limit:g})")
            )
    data = {**design.data, "bands": [b.as_dict() for b in bands], "process": _process_block(process)}
    return replace(design, findings=tuple(findings), details=tuple(lines), data=data)


def _process_block(process) -> dict:
    keys = ("kerf_variation", "xy_compensation", "xy_variation", "elephant_foot", "tool_diameter")
    return {
        "kind": process.kind,
        **{k: process.value(k) for k in keys},
        "center_distance_tolerance": process.value("center_distance_tolerance"),
        "bore_play": process.value("bore_play"),
        "max_play": process.value("max_play"),
    }


def _dot(centre: np.ndarray, radius: float) -> ArcRing:
    """A small engraved diamond, counter-clockwise: four straight edges, exact in every DXF
    encoding and never split (arcs as small as this would be, for bulge-ignoring readers)."""
    x, y = centre
    return ArcRing(np.array([[x + radius, y], [x, y + radius], [x - radius, y], [x, y - radius]]), np.zeros(4))


def assembly_marks(design: Design, parts: tuple[Part, ...]) -> tuple[Part, ...]:
    """The parts with an engraved dot (a diamond, MARK layer) on each gear of a toothed pair where the two
    meet in the assembly's phase: on the line of centres at driver angle 0, two modules inside
    the pitch curve.  Turn the gears so the dots face each other and they mesh as designed."""
    teeth = getattr(design.detail, "teeth", None)
    if design.mechanism != "gear-pair" or teeth is None:
        return parts
    pair, m = design.detail.pitch.pair, teeth.plan.module
    r1 = float(pair.gear1.r(0.0))
    toward = pair.center_distance - r1
    phi2 = float(pair.angle_map(np.array([0.0]))[0])
    spots = (
        np.array([r1 - 2 * m, 0.0]),
        (toward - 2 * m) * np.array([-math.cos(phi2), math.sin(phi2)]),
    )
    out = list(parts)
    for i, spot in enumerate(spots):
        part = out[i]
        hole = part.pivot_diameter / 2
        if np.hypot(*spot) - 0.25 * m > hole + 0.5 * m:  # clear of the bore
            out[i] = replace(part, mark=part.mark + (_dot(spot, 0.25 * m),))
    return tuple(out)
