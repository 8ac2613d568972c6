"""Gear trains on a carrier (seed 001): speeds by the method of stopping, checked against a
fixed-frame velocity analysis; toothed parts (an internal ring where a mesh is internal),
phased so that a tooth meets a space at every contact, and the interference proof."""

from __future__ import annotations

import math

import numpy as np

from ..errors import DesignError
from ..findings import finding
from ..geometry.rings import circle_ring
from ..pitch import shapes
from ..profiles import CarrierTrainParams
from ..teeth.frame import arc_frame
from ..teeth.gear import cut_teeth
from ..teeth.rack import Rack, RackParams
from ..tolerances import DEFAULT
from ..trains import carrier as CT
from .base import Assembly, Design, assembly_overlap
from .budget import check_teeth_work
from .parts import Placement, make_part

__all__ = ["design", "layout"]

TWO_PI = 2 * math.pi
RPM = TWO_PI / 60
UNITS = {"length": "mm", "speed": "rad/s", "acceleration": "rad/s^2"}


def layout(p: CarrierTrainParams) -> tuple[list[float], list[float], list[bool]]:
    """Radii, centres on the carrier's x axis, and which gears are rings (internal teeth)."""
    radii = [p.module * z / 2 for z in p.teeth]
    ring = [False] * len(radii)
    for k, mesh in enumerate(p.meshes):
        if mesh == "internal":
            ring[k if radii[k] > radii[k + 1] else k + 1] = True
    for k, mesh in enumerate(p.meshes):
        for j, other in ((k, k + 1), (k + 1, k)):
            if ring[j] and mesh == "external":
                raise DesignError(
                    f"train.meshes: {p.names[j]} would need internal teeth (to mesh inside) and external teeth "
                    f"(for {p.names[other]}) on the same pitch circle"
                )
    centres = [0.0]
    for k, mesh in enumerate(p.meshes):
        centres.append(centres[-1] + (radii[k] + radii[k + 1] if mesh == "external" else radii[k] - radii[k + 1]))
    return radii, centres, ring


def _gear_part(p: CarrierTrainParams, k: int, ring: bool):
    """Gear k as a part; a ring gear is a rim minus a gear-shaped hole whose teeth are the
    ring's tooth spaces (rack addendum and dedendum swapped)."""
    out = p.output
    fine = out.tolerance * DEFAULT.fine_fraction
    z, m = p.teeth[k], p.module
    r = m * z / 2
    addendum, dedendum = (1.25, 1.0) if ring else (1.0, 1.25)
    rack = Rack.from_params(RackParams(module=m, pressure_angle=p.pressure_angle, addendum=addendum, dedendum=dedendum))
    gear = cut_teeth(
        arc_frame(shapes.circle(r)), rack, z, rack.pitch / 2, tolerance=fine, resize="a smaller train.module"
    )  # tooth at angle 0
    pitch = circle_ring(r, fine)
    if ring:
        rim = circle_ring(r + 3.75 * m, fine)
        return make_part(p.names[k], rim, output=out, hole=gear.outline.outer[::-1].copy(), marks=(pitch,))
    return make_part(p.names[k], gear.outline.outer, output=out, bore=p.bore, wall=m, marks=(pitch,))


def _phases(p: CarrierTrainParams) -> list[float]:
    """Each gear's turn so that a tooth meets a space at every contact on the carrier line."""
    pitch_angle = [TWO_PI / z for z in p.teeth]
    angles = [0.0]
    for k, mesh in enumerate(p.meshes):
        feature = ((0.0 - angles[k]) / pitch_angle[k]) % 1.0  # 0: tooth (or ring space) at angle 0
        if mesh == "external":  # opposite senses at the contact: the pattern is mirrored
            angles.append(math.pi - ((0.5 - feature) % 1.0) * pitch_angle[k + 1])
        else:  # contact at angle 0 on both; a tooth enters a ring space (the hole gear's tooth)
            angles.append(-feature * pitch_angle[k + 1])
    return angles


def design(p: CarrierTrainParams) -> Design:
    """Speeds, accelerations, parts and assembly of a train on a carrier."""
    radii, centres, ring = layout(p)
    check_teeth_work([(z, p.module) for z in p.teeth], p.output.tolerance, keys="train.module / train.teeth")
    train = CT.solve_train(
        radii,
        p.meshes,
        omega1=p.gear1_rpm * RPM,
        epsilon1=p.gear1_eps,
        carrier=p.carrier_rpm * RPM,
        carrier_eps=p.carrier_eps,
    )
    direct = CT.solve_by_velocities(radii, p.meshes, omega1=p.gear1_rpm * RPM, carrier=p.carrier_rpm * RPM)
    difference = float(np.max(np.abs(direct - train.omega)))
    gears = [
        {
            "name": n,
            "teeth": z,
            "pitch_radius": r,
            "centre": c,
            "internal_teeth": g,
            "omega": float(w),
            "omega_rpm": float(w / RPM),
            "epsilon": float(e),
            "omega_relative_to_carrier": float(rel),
        }
        for n, z, r, c, g, w, e, rel in zip(
            p.names, p.teeth, radii, centres, ring, train.omega, train.epsilon, train.relative
        )
    ]
    parts = tuple(_gear_part(p, k, ring[k]) for k in range(len(radii)))
    placements = tuple(Placement(q.name, a, (c, 0.0)) for q, a, c in zip(parts, _phases(p), centres))
    by_name = {q.name: q for q in parts}
    neighbours = [(k, k + 1) for k in range(len(parts) - 1)]
    overlap = assembly_overlap(by_name, list(placements), neighbours)
    # turned a little either way, the second gear of each mesh must bite: they do touch
    nudge = [200 * p.output.tolerance / radii[k + 1] for k in range(len(parts) - 1)]
    nudged = min(
        max(
            assembly_overlap(
                by_name,
                [
                    placements[k],
                    Placement(placements[k + 1].part, placements[k + 1].angle + d, placements[k + 1].offset),
                ],
                [(0, 1)],
            )
            for d in (-nudge[k], nudge[k])
        )
        for k in range(len(parts) - 1)
    )
    assembly = Assembly(overlap, 2 * p.output.tolerance * 2.25 * p.module, nudged)
    findings = []
    if not assembly.fits:
        findings.append(
            finding("interference", f"neighbouring gears overlap by {overlap:.4g} mm² as assembled", "train")
        )
    data = {
        "train": {
            "module": p.module,
            "gear1_rpm": p.gear1_rpm,
            "carrier_rpm": p.carrier_rpm,
            "gear1_eps": p.gear1_eps,
            "carrier_eps": p.carrier_eps,
            "velocity_analysis_difference": difference,
            "assembly_overlap": overlap,
        },
        "gears": gears,
    }
    summary = ", ".join(f"{g['name']} {g['omega_rpm']:.4g} rpm" for g in gears)
    summary += f"; stopping vs velocities {difference:.1e} rad/s"
    return Design(
        params=p,
        mechanism="carrier-train",
        summary=summary,
        findings=tuple(findings),
        part_list=parts,
        placements=placements,
        assembly=assembly,
        data=data,
        units=UNITS,
        details=(f"assembly: max overlap {overlap:.3g} mm² (allowed {assembly.allowed:.3g}), nudged {nudged:.3g} mm²",),
    )
