"""Gear trains on a carrier (seed 001): speeds by the method of stopping, checked against a
fixed-frame velocity analysis; toothed parts (an internal ring where a mesh is internal, a
compound ring with external and internal teeth where ``[train.compound]`` says so), phased so
that a tooth meets a space at every contact, and the interference proof."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from ..geometry.rings import circle_ring
from ..profiles import CarrierTrainParams
from ..tolerances import budget
from ..trains import carrier as CT
from . import compound_ring as CR
from .budget import check_backlash, check_teeth_work
from .chart_data import Blocks
from .finish import Contact, Draft, PartSpec
from .parts import Placement

__all__ = ["TrainLayout", "design", "layout"]

TWO_PI = 2 * math.pi
RPM = TWO_PI / 60
UNITS = {"length": "mm", "speed": "rad/s", "acceleration": "rad/s^2"}


@dataclass(frozen=True)
class TrainLayout:
    """Where the gears sit on the carrier and which pitch radius each mesh uses (mm)."""

    radii: tuple[float, ...]
    """Each gear's pitch radius (the compound gear's external teeth)."""
    sides: tuple[tuple[float, float], ...]
    """Each mesh's pitch radii: the gear before it, the gear after it (the compound gear's
    internal teeth where the gear after it turns inside them)."""
    centres: tuple[float, ...]
    """Centres on the carrier's x axis, gear 1 at 0."""
    ring: tuple[bool, ...]
    """Which gears are rings (internal teeth only)."""


def layout(p: CarrierTrainParams) -> TrainLayout:
    """Radii of each mesh side, centres on the carrier's x axis from them, and the rings."""
    radii = tuple(m * z / 2 for z, m in zip(p.teeth, p.modules))
    inner = None if p.compound is None else p.inner_module * p.inner_teeth / 2
    sides = tuple((inner if k == p.compound else radii[k], radii[k + 1]) for k in range(len(p.meshes)))
    ring = [False] * len(radii)
    outer_for: dict[int, int] = {}  # gear → a neighbour it meets with external teeth
    for k, mesh in enumerate(p.meshes):
        if mesh == "external":
            outer_for.setdefault(k, k + 1)
            outer_for.setdefault(k + 1, k)
            continue
        big = k if k == p.compound or radii[k] > radii[k + 1] else k + 1
        outer_for.setdefault(2 * k + 1 - big, big)
        if k != p.compound:
            ring[big] = True
        if p.compound is not None and big == k + 1:
            raise DesignError(
                f"train.meshes: with [train.compound], {p.names[big]} cannot be a ring round {p.names[k]}, the gear "
                "before it; in every internal mesh the gear after turns inside the gear before"
            )
    for j, other in outer_for.items():
        if ring[j]:
            compound = 0 < j < len(p.meshes) and p.meshes[j - 1 : j + 1] == ("external", "internal")
            raise DesignError(
                f"train.meshes: {p.names[j]} would need internal teeth (to mesh inside) and external teeth "
                f"(for {p.names[other]}) on the same pitch circle"
                + ("; give it both toothings with [train.compound]" if compound else "")
            )
    centres = [0.0]
    for mesh, (r_from, r_to) in zip(p.meshes, sides):
        centres.append(centres[-1] + (r_from + r_to if mesh == "external" else r_from - r_to))
    return TrainLayout(radii, sides, tuple(centres), tuple(ring))


def _gear_part(p: CarrierTrainParams, k: int, ring: bool) -> PartSpec:
    """Gear k as a part; a ring gear is a rim minus a gear-shaped hole whose teeth are the
    ring's tooth spaces (rack addendum and dedendum swapped); the compound gear, its external
    teeth minus such a hole."""
    if k == p.compound:
        return CR.compound_part(p)
    out = p.output
    z, m = p.teeth[k], p.modules[k]
    pitch = circle_ring(m * z / 2, budget(out.tolerance).fine)
    teeth = CR.toothing(p, z, m, internal=ring)  # tooth (or, on a ring, space) at angle 0
    if ring:
        rim = circle_ring(m * z / 2 + 3.75 * m, budget(out.tolerance).fine)
        return PartSpec(p.names[k], rim, hole=teeth, marks=(pitch,))
    return PartSpec(p.names[k], teeth, bore=p.bore, wall=m, marks=(pitch,))


def _phases(p: CarrierTrainParams) -> list[float]:
    """Each gear's turn so that a tooth meets a space at every contact on the carrier line; the
    compound gear meets the gear after it with its internal teeth, of their own pitch angle."""
    pitch_angle = [TWO_PI / z for z in p.teeth]
    angles = [0.0]
    for k, mesh in enumerate(p.meshes):
        own = TWO_PI / p.inner_teeth if k == p.compound else pitch_angle[k]
        feature = ((0.0 - angles[k]) / own) % 1.0  # 0: tooth (or ring space) at angle 0
        if mesh == "external":  # opposite senses at the contact: the pattern is mirrored
            angles.append(math.pi - ((0.5 - feature) % 1.0) * pitch_angle[k + 1])
        else:  # contact at angle 0 on both; a tooth enters a ring space (the hole gear's tooth)
            angles.append(-feature * pitch_angle[k + 1])
    return angles


def _speeds(p: CarrierTrainParams, lay: TrainLayout):
    """Speeds by the method of stopping and in the fixed frame; with a compound gear, the
    "compound" report block and the finding about the seed's formula."""
    omega1, carrier = p.gear1_rpm * RPM, p.carrier_rpm * RPM
    if p.compound is None:
        train = CT.solve_train(
            lay.radii, p.meshes, omega1=omega1, epsilon1=p.gear1_eps, carrier=carrier, carrier_eps=p.carrier_eps
        )
        return train, CT.solve_by_velocities(lay.radii, p.meshes, omega1=omega1, carrier=carrier), None, []
    meshes = CR.chain_meshes(p.meshes, lay.sides)
    train, direct = CR.solve(p, meshes)
    block, claim = CR.report_block(p, meshes, train, direct)
    return train, direct, (meshes, block), [claim]


def _gear_blocks(p: CarrierTrainParams, lay, train) -> list[Blocks]:
    """The report's entry of each gear: its teeth, where it sits and how it turns."""
    radii, centres, ring = lay.radii, lay.centres, lay.ring
    return [
        {
            "name": n,
            "teeth": z,
            "module": m,
            "pitch_radius": r,
            "centre": c,
            "internal_teeth": g,
            "omega": float(w),
            "omega_rpm": float(w / RPM),
            "epsilon": float(e),
            "omega_relative_to_carrier": float(rel),
        }
        for n, z, m, r, c, g, w, e, rel in zip(
            p.names, p.teeth, p.modules, radii, centres, ring, train.omega, train.epsilon, train.relative
        )
    ]


def design(p: CarrierTrainParams) -> Draft[None]:
    """Speeds, accelerations, parts and assembly of a train on a carrier."""
    lay = layout(p)
    radii, centres, ring = lay.radii, lay.centres, lay.ring
    toothings = list(zip(p.teeth, p.modules))
    keys = "train.module / train.teeth"
    if p.compound is not None:
        toothings.append((p.inner_teeth, p.inner_module))
        keys += " / train.compound"
    check_teeth_work(toothings, p.output.tolerance, keys=keys)
    check_backlash(p.backlash, min(m for _, m in toothings), "train.backlash")
    train, direct, compound, findings = _speeds(p, lay)
    difference = float(np.max(np.abs(direct - train.omega)))
    gears = _gear_blocks(p, lay, train)
    if compound is not None:
        gears[p.compound].update(internal_teeth=True, **CR.gear_entry(p, compound[0]))
    parts = tuple(_gear_part(p, k, ring[k]) for k in range(len(radii)))
    placements = tuple(Placement(q.name, a, (c, 0.0)) for q, a, c in zip(parts, _phases(p), centres))
    # each mesh: the second gear is nudged on its own pitch circle (the compound's inner one)
    contacts = tuple(
        Contact(k, k + 1, module=p.modules[k + 1], radius=r_to, touch="mesh", play=p.backlash)
        for k, (_, r_to) in enumerate(lay.sides)
    )
    data: Blocks = {
        "train": {
            "module": p.module,
            "gear1_rpm": p.gear1_rpm,
            "carrier_rpm": p.carrier_rpm,
            "gear1_eps": p.gear1_eps,
            "carrier_eps": p.carrier_eps,
            "backlash": p.backlash,
            "velocity_analysis_difference": difference,
        },
        "gears": gears,
    }
    if compound is not None:
        data["compound"] = compound[1]
    summary = ", ".join(f"{g['name']} {g['omega_rpm'] + 0.0:.4g} rpm" for g in gears)  # + 0.0: never '-0 rpm'
    summary += f"; stopping vs velocities {difference:.1e} rad/s"
    if compound is not None:
        summary += f"; the seed's ω3 formula {compound[1]['omega3_seed_formula_rpm']:.4g} rpm"
    return Draft(
        params=p,
        mechanism="carrier-train",
        summary=summary,
        findings=tuple(findings),
        parts=parts,
        placements=placements,
        contacts=contacts,
        data=data,
        units=UNITS,
        charts={"train.png": data} if p.output.charts else {},
        where="train",
    )
