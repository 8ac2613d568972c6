"""The carrier-less noncircular planetary as parts (issue 38): a lobed sun, N identical planets, a
lobed ring, closed exactly, every mesh proved over the whole cycle.

The kinematics are :mod:`gearcad.trains.nc_planetary`'s (the sun's e solved so that the ring
closes with its lobes).  One rack cuts all three: sun and planets as gears, the ring as a gear-
shaped hole (addendum and dedendum swapped, reversed), conjugate by Camus's theorem at both
contacts.  Teeth are phased at the assembled position (the sun's lobe on the first planet's
valley): a sun tooth at the contact, a planet space there, and the ring's space where the planet
leaves a tooth at its far contact.  The set repeats after one sun lobe (turned by 2π/n, every
toothing invariant under it), so the meshes are proved over one sun lobe, sun held: the first
planet against the sun and against the ring (every planet is its copy turned by 2π/N).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from ..findings import finding
from ..geometry.rings import circle_ring
from ..pitch.curve import radius_range
from ..pitch.discretize import polyline
from ..profiles.nc_planetary import NcPlanetaryParams
from ..teeth.frame import arc_frame
from ..teeth.gear import cut_teeth
from ..tolerances import budget
from ..trains import nc_planetary as NP
from ..trains import nc_set as NS
from .base import Motion
from .finish import Contact, Draft, PartSpec
from .nc_internal import _rack, whole_proof
from .parts import Placement

__all__ = ["SetProof", "design"]

UNITS = {"length": "mm", "angle": "rad"}
TWO_PI = 2 * math.pi


@dataclass(frozen=True)
class SetProof:
    """One mesh proved at ``positions`` sun angles over a sun lobe (a :class:`~.finish.Proof`)."""

    mesh: str
    positions: int
    max_overlap: float
    allowed_overlap: float
    nudged_min_overlap: float
    max_depth: float
    least_play: float

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def _rot(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s], [-s, c]])  # xy @ _rot(a) turns row vectors by a


def _prove(name, fixed, moving_xy, place, arm, *, positions, module, tol, play) -> SetProof:
    """``fixed`` (a prepared polygon, its own frame) against ``moving_xy`` placed by
    ``place(ks, turns)`` (→ (m, n, 2) in the fixed part's frame) at positions ``ks``, turned
    ``turns`` extra; ``arm[k]``: the contact's distance from the turning part's pivot (nudge and
    play as arc there)."""
    b = budget(tol)
    every = np.arange(positions)

    def placed(at, turn):  # every position's polygon made by one call
        return shapely.polygons(place(np.asarray(at), np.asarray(turn, dtype=float)))

    at = every[::2]
    nudge = b.nudge_arc(module=module, play=play) / arm[at]
    areas, depth, nudged, free = whole_proof(fixed, placed, positions, at, nudge, module)
    return SetProof(
        name,
        positions,
        float(areas.max()),
        b.teeth_overlap(module),
        nudged,
        float(depth.max()),
        float(np.min(free * arm[at])),
    )


def _cycle_lobes(ps, most: int = 60) -> int:
    """Sun lobes (sun held, θ) after which the set with its ring held looks as it started: the sun
    turned by whole lobes and the planets' carrier by whole planet spacings (1 if none within
    ``most``)."""
    turn = float(ps.ring_turn(ps.lobe))  # the ring's turn per sun lobe, sun held
    orbit = ps.lobe - turn  # the planets' carrier's, ring held
    for k in range(1, most + 1):
        a, b = k * orbit / (TWO_PI / ps.planets), k * turn / ps.lobe
        if abs(a - round(a)) < 1e-6 and abs(b - round(b)) < 1e-6:
            return k
    return 1


def _motion(ps, placements) -> Motion:
    """One cycle with the ring held: the sun turned by −φ_r(θ), each planet on its orbit (its
    pivot moves: ``Motion.pivots``), 24 frames a sun lobe (at most 240)."""
    lobes = _cycle_lobes(ps)
    frames = min(240, 24 * lobes)
    theta = np.arange(frames) * lobes * ps.lobe / frames
    sun, centres, turns = ps.ring_held_frames(theta)
    placed = np.array([pl.angle for pl in placements[1:-1]])
    angles = np.column_stack([sun, turns - placed, np.zeros(frames)])
    origin = np.zeros((frames, 1, 2))
    return Motion(tuple(pl.part for pl in placements), angles, np.concatenate([origin, centres, origin], axis=1))


def design(p: NcPlanetaryParams) -> Draft:
    """Sun, planets and ring: the exact closure, teeth, parts, the proofs and the planets' gap."""
    s, tol = p.set, p.output.tolerance
    fine = budget(tol).fine
    n, big_n, ring_lobes = s.lobes, s.planets, p.ring_lobes
    planet = NP.Lobed(s.radius, n, s.e)
    sun, closure = NP.close_ring(planet, ring_lobes, key="set.e")
    ps = NS.planetary_set(sun, planet, big_n, ring_lobes)
    check = NP.by_sun_angle(sun, planet, steps=400)  # RK4: ~1e-10 rad (200 steps: ~1e-9)
    gap_bound, gap_least, gap_at = NS.planet_gap(ps)
    z = p.teeth.count
    z_ring = z * ring_lobes // n
    sun_curve, planet_curve = NS.as_pitch_curve(sun, s.sun), NS.as_pitch_curve(planet, s.planet)
    ring_curve = NS.ring_pitch_curve(ps, s.ring)
    frames = [arc_frame(c) for c in (sun_curve, planet_curve, ring_curve)]
    module = frames[1].perimeter / (math.pi * z)
    gap_teeth = gap_bound - 2 * module  # each planet's tips stand an addendum (1 m) off its pitch curve
    if gap_teeth <= 0:
        raise DesignError(
            f"set.planets = {big_n}: neighbouring planets' tips would touch (pitch curves {gap_bound:.4g} mm apart "
            f"at least, tips {2 * module:.4g} mm of it): use fewer planets or more teeth.count"
        )
    alpha, backlash = p.pressure_angle, p.backlash
    gear_rack, ring_rack = _rack(module, alpha, backlash, internal=False), _rack(module, alpha, backlash, internal=True)
    pitch = gear_rack.pitch
    pose = NP.poses(sun, planet, np.array([0.0]))
    psi0, chi0 = float(pose.psi[0]), float(pose.chi[0])
    # a sun tooth at its arc ``quarter`` (0: the contact), a planet space where it meets it (the
    # planet's arc runs back), the ring's hole (its teeth the ring's spaces) offset as the planet's
    # features are at its far contact.  Stacked bands: the teeth a quarter pitch off the set's
    # symmetry line, so that the upper band (the lower one mirrored about it) has them half a
    # pitch off the lower band's
    bands = s.retention == "bands"
    quarter = pitch / 4 if bands else 0.0
    planet_phase = (float(frames[1].arc(np.array([psi0]))[0]) - quarter) % pitch
    offset = ((float(frames[1].arc(np.array([chi0 % TWO_PI]))[0]) - planet_phase) / pitch) % 1.0
    resize = "fewer teeth.count"
    cut = [
        cut_teeth(frames[0], gear_rack, z, pitch / 2 + quarter, tolerance=fine, resize=resize),
        cut_teeth(frames[1], gear_rack, z, planet_phase, tolerance=fine, resize=resize),
        cut_teeth(frames[2], ring_rack, z_ring, (-offset * pitch) % pitch, tolerance=fine, resize=resize),
    ]
    sun_xy, planet_xy = cut[0].outline.outer, cut[1].outline.outer
    hole = cut[2].outline.outer[::-1].copy()
    rim = circle_ring(radius_range(ring_curve)[1] + (1.25 + s.wall) * module, fine)
    positions = max(48, 3 * z // n * 4)
    theta = np.arange(positions) * ps.lobe / positions
    poses = NP.poses(sun, planet, theta)
    phi_r = ps.ring_turn(theta)

    def turned(xy, angle):  # (n, 2) or (m, n, 2) points turned by angles (m,) about O: (m, n, 2)
        c, s_ = np.cos(angle)[:, None], np.sin(angle)[:, None]
        x, y = xy[..., 0], xy[..., 1]
        return np.stack([x * c - y * s_, x * s_ + y * c], axis=-1)

    def planet_in_sun(ks, turns):  # the first planet at θ_k, turned ``turn`` more about its centre
        return turned(planet_xy, poses.beta[ks] + turns) + poses.centre[ks][:, None, :]

    def planet_in_ring(ks, turns):  # …seen from the ring turned φ_r(θ_k) − turn about O
        return turned(planet_in_sun(ks, np.zeros(len(ks))), -(phi_r[ks] - turns))

    sun_poly = shapely.Polygon(sun_xy)
    ring_poly = shapely.Polygon(rim, [hole])
    shapely.prepare(sun_poly)
    shapely.prepare(ring_poly)
    kw = {"positions": positions, "module": module, "tol": tol, "play": backlash}
    arm_sun = planet.r(poses.psi)  # the sun–planet contact from the planet's centre
    proofs = (
        _prove(f"{s.sun}/{s.planet}", sun_poly, planet_xy, planet_in_sun, arm_sun, **kw),
        _prove(f"{s.planet}/{s.ring}", ring_poly, planet_xy, planet_in_ring, poses.rho, **kw),
    )
    findings = []
    for proof in proofs:
        if proof.max_depth > budget(tol).allowed_depth or proof.max_overlap > proof.allowed_overlap:
            findings.append(
                finding(
                    "interference",
                    f"{proof.mesh}: overlap {proof.max_overlap:.4g} mm², {proof.max_depth * 1e3:.3g} µm deep",
                    "teeth",
                )
            )
    parts = (
        PartSpec(s.sun, sun_xy, bore=p.bore, wall=module, marks=(polyline(sun_curve, fine),)),
        PartSpec(s.planet, planet_xy, marks=(polyline(planet_curve, fine),)),
        PartSpec(s.ring, rim, hole=hole, marks=(polyline(ring_curve, fine),)),
    )
    beta0, centre0 = float(pose.beta[0]), pose.centre[0]
    planets = [
        Placement(s.planet, beta0 + TWO_PI * k / big_n, tuple(float(v) for v in centre0 @ _rot(TWO_PI * k / big_n)))
        for k in range(big_n)
    ]
    placements = (Placement(s.sun), *planets, Placement(s.ring))
    contacts = tuple(Contact(0, 1 + k, module=module, nudge=False) for k in range(big_n)) + tuple(
        Contact(1 + k, 1 + big_n, module=module, nudge=False) for k in range(big_n)
    )
    motion = _motion(ps, placements)
    # as assembled (θ = 0) the pitch curves are symmetric about the line O C₀ (the x axis) and, by
    # the set's N-fold symmetry, about each line O Cₖ: the mirror image of the lower bands' proven
    # motion, run backwards, is the upper bands' (each part's own line: 0 for sun and ring, −β₀
    # in the planet's frame, the same for every planet)
    mirror = {s.sun: 0.0, s.planet: -beta0, s.ring: 0.0} if bands else {}
    held = (
        (
            "retention: two stacked bands, the upper the lower turned over (its teeth half a pitch off: a planet "
            "cannot slide out); the plate holds the set assembled, printed in place",
        )
        if bands
        else ()
    )
    data = {
        "set": {
            "lobes": n,
            "planets": big_n,
            "ring_lobes": ring_lobes,
            "planet_e": s.e,
            "planet_radius": s.radius,
            "sun_e": sun.e,
            "sun_radius": sun.radius,
            "closure_residual": closure,
            "closure_by_sun_angle": abs(ring_lobes * abs(check.sweep) - TWO_PI),
            "natural_ring_lobes_identical": NP.by_arc_length(planet, planet, extremes=False).natural_lobes,
            "orbit_min": ps.data.orbit_min,
            "orbit_max": ps.data.orbit_max,
            "ring_turn_per_sun_lobe": ps.data.ring_turn,
            "planet_gap_pitch_bound": gap_bound,
            "planet_gap_pitch_least": gap_least,
            "planet_gap_at": gap_at,
            "planet_gap_tips_bound": gap_teeth,
        },
        "teeth": {"module": module, "sun": z, "planet": z, "ring": z_ring, "backlash": backlash},
        "retention": {"kind": s.retention, "band_lines": mirror},
        "meshes": [proof.as_dict() for proof in proofs],
    }
    summary = (
        f"{s.sun} ({n} lobes, e {sun.e:.5f}, {z} teeth), {big_n} × {s.planet} (e {s.e:g}, {z}), {s.ring} "
        f"({ring_lobes} lobes, {z_ring}): closure {closure:.1e} rad, module {module:.4g} mm, planets ≥ "
        f"{gap_teeth:.3g} mm apart at the tips"
    )
    return Draft(
        params=p,
        mechanism="nc-planetary",
        summary=summary,
        findings=tuple(findings),
        parts=parts,
        placements=placements,
        contacts=contacts,
        data=data,
        units=UNITS,
        detail=ps,
        motion=motion,
        proofs=proofs,
        where="teeth",
        bands=mirror,
        details=held,
    )
