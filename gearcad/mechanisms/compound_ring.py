"""Seed 001's second scheme as a part: the compound ring of a carrier train (``[train.compound]``).

The compound gear carries external teeth, meshing the gear before it, and internal teeth, in
which the gear after it turns, each toothing with its own pitch radius and module.  Its part is
the external-toothed gear with a hole that is the internal toothing, made as a ring gear's is:
a gear cut by the rack with addendum and dedendum swapped, reversed.  Its speeds come from the
method of stopping with each mesh's own radii (:func:`..trains.compound.solve_chain`), checked in
the fixed frame (:func:`..trains.compound.chain_by_velocities`); the seed's formula for this
scheme has one radius for both toothings, which the report sets beside the true speed.
"""

from __future__ import annotations

import math

import numpy as np

from ..findings import Finding, finding
from ..geometry.rings import circle_ring
from ..pitch import shapes
from ..profiles import CarrierTrainParams
from ..teeth.frame import arc_frame
from ..teeth.gear import cut_teeth
from ..teeth.rack import Rack, RackParams
from ..tolerances import budget
from ..trains import compound as CP
from .finish import PartSpec

__all__ = ["toothing", "compound_part", "chain_meshes", "ring", "solve", "gear_entry", "report_block"]

RPM = 2 * math.pi / 60


def toothing(p: CarrierTrainParams, teeth: int, module: float, *, internal: bool) -> np.ndarray:
    """A toothed ring about the origin, sampled at the fine tolerance ((n, 2) float, mm): the
    gear's outline, tooth at angle 0; ``internal`` gives the hole of a ring whose teeth these
    are (rack addendum and dedendum swapped, clockwise), a tooth space at angle 0.  The teeth
    are half ``train.backlash`` thinner; a ring's hole, whose teeth are its spaces, half thicker
    (its rack so much narrower: the ring teeth's tip rounding no larger than the rack's tip takes)."""
    fine = budget(p.output.tolerance).fine
    tips = p.train.addendum  # the gears' tips (a ring's: the hole's roots), over or inside the pitch circle
    addendum, dedendum = (1.25, tips) if internal else (tips, 1.25)
    thinning = (-0.5 if internal else 0.5) * p.backlash
    tip = RackParams.tip_radius
    if thinning < 0:  # a narrower rack: its tip rounding (the ring teeth's tip) as large as its tip takes
        a = p.pressure_angle
        room = (math.pi * module / 4 + thinning / 2 - dedendum * module * math.tan(a)) / (1 / math.cos(a) - math.tan(a))
        tip = min(tip, 0.999 * room / module)
    rack = Rack.from_params(RackParams(module, p.pressure_angle, addendum, dedendum, tip_radius=tip, thinning=thinning))
    gear = cut_teeth(
        arc_frame(shapes.circle(module * teeth / 2)),
        rack,
        teeth,
        rack.pitch / 2,
        tolerance=fine,
        resize="a smaller train.module",
    )
    outer = gear.outline.outer
    return outer[::-1].copy() if internal else outer


def compound_part(p: CarrierTrainParams) -> PartSpec:
    """The compound gear: its external teeth, and the internal teeth as its hole; both pitch
    circles engraved."""
    k, fine = p.compound, budget(p.output.tolerance).fine
    m, m_in, z_in = p.modules[k], p.inner_module, p.inner_teeth
    outer = toothing(p, p.teeth[k], m, internal=False)
    hole = toothing(p, z_in, m_in, internal=True)
    marks = (circle_ring(m * p.teeth[k] / 2, fine), circle_ring(m_in * z_in / 2, fine))
    return PartSpec(p.names[k], outer, hole=hole, marks=marks)


def chain_meshes(kinds, sides) -> tuple[CP.Mesh, ...]:
    """The train as meshes of :mod:`..trains.compound`, each with its own pitch radii."""
    return tuple(CP.Mesh(kind, r_from, r_to) for kind, (r_from, r_to) in zip(kinds, sides))


def solve(p: CarrierTrainParams, meshes) -> tuple[CP.ChainData, np.ndarray]:
    """Speeds and accelerations by the method of stopping, and the speeds in the fixed frame."""
    omega1, carrier = p.gear1_rpm * RPM, p.carrier_rpm * RPM
    train = CP.solve_chain(meshes, omega1=omega1, epsilon1=p.gear1_eps, carrier=carrier, carrier_eps=p.carrier_eps)
    return train, CP.chain_by_velocities(meshes, omega1=omega1, carrier=carrier)


def ring(meshes, k: int) -> CP.CompoundRing:
    """Gear k, the compound one, with the gears before and after it, as the kinematics core's ring."""
    return CP.CompoundRing(meshes[k - 1].r_from, meshes[k - 1].r_to, meshes[k].r_from, meshes[k].r_to)


def gear_entry(p: CarrierTrainParams, meshes) -> dict:
    """What the report's "gears" entry of the compound gear adds: its internal toothing and wall."""
    k = p.compound
    return {
        "inner_teeth": p.inner_teeth,
        "inner_module": p.inner_module,
        "inner_pitch_radius": meshes[k].r_from,
        "wall": ring(meshes, k).wall(p.modules[k], p.inner_module),
    }


def report_block(p: CarrierTrainParams, meshes, train: CP.ChainData, direct: np.ndarray) -> tuple[dict, Finding]:
    """The "compound" report block — the inner gear's speed by stopping, in the fixed frame and by
    the seed's formula — and the finding that the seed's formula holds only for equal radii."""
    k = p.compound
    r_before, r_outer = meshes[k - 1].r_from, meshes[k - 1].r_to
    r_inner, r_inside = meshes[k].r_from, meshes[k].r_to
    carrier = p.carrier_rpm * RPM
    # the seed's ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3, with the gear before the ring as its gear 1
    seed = CP.seed_internal_formula(r_before, r_inside, omega1=float(train.omega[k - 1]), carrier=carrier)
    omega3 = float(train.omega[k + 1])
    block = {
        "gear": p.names[k],
        "inner_gear": p.names[k + 1],
        "r2_outer": r_outer,
        "r2_inner": r_inner,
        "radius_ratio": r_inner / r_outer,
        "omega3": omega3,
        "omega3_by_velocities": float(direct[k + 1]),
        "omega3_seed_formula": seed,
        "omega3_rpm": omega3 / RPM,
        "omega3_seed_formula_rpm": seed / RPM,
    }
    claim = finding(
        "paper-claim",
        f"seed 001's second scheme gives ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3, free of gear 2, which holds only when "
        f"{p.names[k]}'s two toothings share one pitch radius; with r2_inner/r2_outer = {r_inner:g}/{r_outer:g} = "
        f"{r_inner / r_outer:.4g} the relative speed scales by that ratio: {p.names[k + 1]} turns at "
        f"{omega3 / RPM:.4g} rpm, not the formula's {seed / RPM:.4g} rpm",
        "train.compound",
    )
    return block, claim
