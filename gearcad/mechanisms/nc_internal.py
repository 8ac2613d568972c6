"""A noncircular pinion rolling inside a noncircular ring about fixed centres (issue 38).

The pinion's pitch curve is any curve that needs no centre distance (ellipse, oval, circle,
samples); the ring's is its internal conjugate (:mod:`gearcad.pitch.internal`), closed with the
ring's lobes by solving the centre distance.  Both are cut by one rack: the pinion as a gear pair's
driver is, the ring as a gear-shaped hole — the rack with addendum and dedendum swapped rolled on
the ring's pitch curve, reversed — whose teeth are the ring's spaces.  By Camus's theorem the two
are conjugate: the rack's pitch line rolls on both pitch curves at their common contact, so its
flanks envelope a pinion flank and a ring flank that touch.  The mesh is proved by overlap area
and depth at positions over the whole cycle, and nudged either way it must bite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from ..findings import Finding, finding
from ..geometry.depth import overlap_depths
from ..geometry.rings import circle_ring
from ..pitch import shapes
from ..pitch.curve import PitchCurve, convexity, perimeter, radius_range
from ..pitch.discretize import polyline
from ..pitch.internal import InternalPairData, internal_pair
from ..profiles.nc_internal import NcInternalParams
from ..teeth.frame import arc_frame
from ..teeth.gear import cut_teeth
from ..teeth.rack import Rack, RackParams
from ..tolerances import budget
from .base import Motion
from .finish import Contact, Draft, PartSpec
from .parts import Placement

__all__ = ["MeshProof", "design", "pinion_curve", "whole_proof"]

UNITS = {"length": "mm", "angle": "rad"}
RPM = 2 * math.pi / 60


def pinion_curve(p: NcInternalParams) -> PitchCurve:
    """The pinion's pitch curve from its parameters."""
    g = p.pinion
    if g.curve == "ellipse":
        return shapes.ellipse_focus(g.a, g.b) if g.pivot == "focus" else shapes.ellipse_centre(g.a, g.b)
    if g.curve == "oval":
        return shapes.oval(g.a, g.b)
    if g.curve == "circle":
        return shapes.circle(g.radius)
    return shapes.from_samples(
        "curve from samples",
        g.radii,
        lobes=g.lobes,
        negligible=p.output.tolerance * 1e-3,
        max_order=256,
        key="pinion.radii",
        smoothing=g.smoothing,
    )


def _rack(module: float, alpha: float, backlash: float, *, internal: bool) -> Rack:
    """The rack of the pinion, or (``internal``) of the ring's gear-shaped hole: addendum and
    dedendum swapped, half the backlash wider spaces, its tip rounding no larger than its narrower
    tip takes (as a circular ring's, :func:`.compound_ring.toothing`)."""
    addendum, dedendum = (1.25, 1.0) if internal else (1.0, 1.25)
    thinning = (-0.5 if internal else 0.5) * backlash
    tip = RackParams.tip_radius
    if thinning < 0:
        room = (math.pi * module / 4 + thinning / 2 - dedendum * module * math.tan(alpha)) / (
            1 / math.cos(alpha) - math.tan(alpha)
        )
        tip = min(tip, 0.999 * room / module)
    return Rack.from_params(RackParams(module, alpha, addendum, dedendum, tip_radius=tip, thinning=thinning))


@dataclass(frozen=True)
class MeshProof:
    """The mesh proved at ``positions`` pinion angles over one cycle (a :class:`~.finish.Proof`)."""

    positions: int
    max_overlap: float
    allowed_overlap: float
    nudged_min_overlap: float
    max_depth: float
    worst_phi: float
    least_play: float = math.nan
    """Least free play (arc on the ring's pitch curve at the contact, mm) at the nudged positions:
    the ring turned each way until it first touches the pinion (bisection to 1e-4 of the nudge)."""


def whole_proof(material, placed, positions: int, at: np.ndarray, nudge: np.ndarray, module: float):
    """The whole-outline proof of a part turning against ``material`` (a prepared polygon):
    ``placed(indices, turns)`` -> its polygons at those positions turned so much more.  Returns
    the overlap area and depth at every position, and at the positions ``at`` the least of the
    overlaps with the part turned ±``nudge`` (it must bite) and the free turn each way summed
    (the part turned until it first touches, 12 bisections of the nudge), rad."""
    every = np.arange(positions)
    assembled = placed(every, np.zeros(positions))
    touch = np.nonzero(shapely.intersects(material, assembled))[0]
    areas, depth = np.zeros(positions), np.zeros(positions)
    if len(touch):
        found = overlap_depths(assembled[touch], np.array([material] * len(touch), dtype=object), step=0.1 * module)
        areas[touch], depth[touch] = found.area, found.depth
    ahead = shapely.area(shapely.intersection(material, placed(at, nudge)))
    back = shapely.area(shapely.intersection(material, placed(at, -nudge)))
    free = np.zeros(len(at))
    for sign in (1.0, -1.0):
        lo, hi = np.zeros(len(at)), nudge.copy()
        for _ in range(12):
            mid = 0.5 * (lo + hi)
            hit = shapely.intersects(material, placed(at, sign * mid))
            lo, hi = np.where(hit, lo, mid), np.where(hit, mid, hi)
        free += lo
    return areas, depth, float(np.min(np.maximum(ahead, back))), free


def _prove(pair: InternalPairData, pinion: np.ndarray, ring_material, *, module: float, tol: float, play: float):
    """Overlap area and depth of the whole pinion and the whole ring as assembled at pinion angles
    over the cycle (one position per third of a pinion tooth, at least 96); at every fourth, the
    least overlap with the ring turned either way by the budget's nudge, and the free play (the
    ring turned each way until the two first touch, bisection).  Whole outlines, not windows round
    the pitch point: inside a noncircular ring a tooth pair several pitches away can be the one
    that touches first (the oval example's least play is set 20 mm from the pitch point).  All in
    the ring's frame, the ring prepared once: the pinion turned by −φ1 about O and the ring by
    −φ2 + t about (−E, 0) put the pinion at R(φ2 − t)·(R(−φ1)·x + (E, 0)) in the ring's frame."""
    b = budget(tol)
    z1 = round(perimeter(pair.pinion) / (math.pi * module))
    cycle = pair.cycle
    positions = max(96, 3 * z1 * round(cycle / (2 * math.pi)))
    phi1 = np.linspace(0.0, cycle, positions, endpoint=False)
    phi2 = pair.angle_map(phi1)
    e = pair.center_distance
    radius = pair.pinion.r(phi1) + e  # the contact's distance from the ring's pivot
    shapely.prepare(ring_material)

    def pinions(at, turn) -> np.ndarray:
        out = []
        for k, t in zip(at, turn):
            a, c = -phi1[k], phi2[k] - t
            xy = pinion @ np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]]) + (e, 0.0)
            out.append(shapely.Polygon(xy @ np.array([[math.cos(c), math.sin(c)], [-math.sin(c), math.cos(c)]])))
        return np.array(out, dtype=object)

    at = np.arange(positions)[::4]
    nudge = b.nudge_arc(module=module, play=play) / radius[at]
    areas, depth, nudged, free = whole_proof(ring_material, pinions, positions, at, nudge, module)
    worst = int(np.argmax(areas))
    return MeshProof(
        positions=positions,
        max_overlap=float(areas[worst]),
        allowed_overlap=b.teeth_overlap(module),
        nudged_min_overlap=nudged,
        max_depth=float(np.max(depth)),
        worst_phi=float(phi1[worst]),
        least_play=float(np.min(free * radius[at])),
    )


def _findings(p: NcInternalParams, pair: InternalPairData, proof: MeshProof, tol: float) -> list[Finding]:
    out = []
    if pair.curvature_margin <= 0:
        out.append(
            finding(
                "interference",
                f"the pinion's pitch curve bends less than the ring's at a contact (κ1 − κ2 = "
                f"{pair.curvature_margin:.4g} 1/mm): it cannot roll inside; give the pinion less eccentricity "
                "or the ring more lobes",
                "ring.lobes",
            )
        )
    if proof.max_depth > budget(tol).allowed_depth or proof.max_overlap > proof.allowed_overlap:
        out.append(
            finding(
                "interference",
                f"{p.pinion.name} and {p.ring.name} overlap by {proof.max_overlap:.4g} mm², "
                f"{proof.max_depth * 1e3:.3g} µm deep, at pinion angle {math.degrees(proof.worst_phi):.1f}°",
                "teeth",
            )
        )
    return out


def design(p: NcInternalParams) -> Draft:
    """The pinion, the ring, their centre distance, teeth, parts, motion and the mesh's proof."""
    tol = p.output.tolerance
    fine = budget(tol).fine
    curve = pinion_curve(p)
    if not convexity(curve).convex:
        raise DesignError(f"pinion: the pitch curve {curve.name} is not convex; a pinion inside a ring must be")
    pair = internal_pair(curve, ring_lobes=p.ring.lobes, key="ring.lobes")
    z1, z2 = p.teeth.count, p.ring_teeth
    module = perimeter(curve) / (math.pi * z1)
    alpha = p.pressure_angle
    pinion_rack = _rack(module, alpha, p.backlash, internal=False)
    ring_rack = _rack(module, alpha, p.backlash, internal=True)
    resize = "fewer teeth.count"
    pinion_teeth = cut_teeth(arc_frame(curve), pinion_rack, z1, pinion_rack.pitch / 2, tolerance=fine, resize=resize)
    ring_frame = arc_frame(pair.ring)
    if not math.isclose(ring_frame.perimeter, z2 * ring_rack.pitch, rel_tol=1e-9):  # pragma: no cover - closure
        raise DesignError(f"ring.lobes = {p.ring.lobes}: the ring's pitch curve does not carry {z2} teeth")
    hole_gear = cut_teeth(ring_frame, ring_rack, z2, ring_rack.pitch / 2, tolerance=fine, resize=resize)
    hole = hole_gear.outline.outer[::-1].copy()
    r2_max = radius_range(pair.ring)[1]
    rim = circle_ring(r2_max + (1.25 + p.ring.wall) * module, fine)
    pinion_outline = pinion_teeth.outline.outer
    ring_material = shapely.Polygon(rim, [hole])
    proof = _prove(pair, pinion_outline, ring_material, module=module, tol=tol, play=p.backlash)
    parts = (
        PartSpec(p.pinion.name, pinion_outline, bore=p.bore, wall=module, marks=(polyline(curve, fine),)),
        PartSpec(p.ring.name, rim, hole=hole, marks=(polyline(pair.ring, fine),)),
    )
    e = pair.center_distance
    placements = (Placement(p.pinion.name, 0.0, (0.0, 0.0)), Placement(p.ring.name, 0.0, (-e, 0.0)))
    contacts = (Contact(0, 1, module=module, radius=float(curve.r(np.array([0.0]))[0] + e), nudge=False),)
    frames = int(min(180, max(24, math.ceil(pair.cycle / (2 * math.pi / z1 / 3)))))
    phi1 = np.linspace(0.0, pair.cycle, frames, endpoint=False)
    motion = Motion((p.pinion.name, p.ring.name), np.column_stack([-phi1, -pair.angle_map(phi1)]))
    dense = np.linspace(0.0, pair.cycle, 4097)
    ratio = pair.angle_map.slope(dense)
    data = {
        "pair": {
            "center_distance": e,
            "lobes": list(pair.lobes),
            "closure_error": pair.closure_error,
            "contact_residual": pair.contact_residual,
            "slip_residual": pair.slip_residual,
            "curvature_margin": pair.curvature_margin,
            "ratio_min": float(ratio.min()),
            "ratio_max": float(ratio.max()),
            "cycle": pair.cycle,
        },
        "teeth": {
            "module": module,
            "pinion_teeth": z1,
            "ring_teeth": z2,
            "pressure_angle_deg": p.teeth.pressure_angle_deg,
            "backlash": p.backlash,
        },
        "mesh": {
            "positions": proof.positions,
            "max_overlap": proof.max_overlap,
            "allowed_overlap": proof.allowed_overlap,
            "nudged_min_overlap": proof.nudged_min_overlap,
            "max_depth": proof.max_depth,
            "allowed_depth": budget(tol).allowed_depth,
            "worst_phi": proof.worst_phi,
            "least_play": proof.least_play,
        },
    }
    summary = (
        f"{p.pinion.name} ({pair.lobes[0]} lobes, {z1} teeth) in {p.ring.name} ({pair.lobes[1]} lobes, {z2} teeth): "
        f"E = {e:.6g} mm, module {module:.5g} mm, ratio ω2/ω1 {ratio.min():.4g}…{ratio.max():.4g}, "
        f"closure {pair.closure_error:.1e} rad"
    )
    return Draft(
        params=p,
        mechanism="nc-internal",
        summary=summary,
        findings=tuple(_findings(p, pair, proof, tol)),
        parts=parts,
        placements=placements,
        contacts=contacts,
        data=data,
        units=UNITS,
        detail=pair,
        motion=motion,
        proofs=(proof,),
        where="teeth",
    )
