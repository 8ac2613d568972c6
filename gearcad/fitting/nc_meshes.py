"""The noncircular internal pair's mesh and a carrier-less planetary set's meshes (sun–planet,
planet–ring) as the band measures them (issue 38): each a :class:`~.band_mesh.MeshGeometry` at any
driver angle, and the :class:`~.moving.MovingMesh` its proof measures (:mod:`.band_nc` bands them;
the frames are described there)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..pitch.curve import curvature, polar_curvature
from ..teeth.contact import ContactData, contact_ratio
from ..teeth.frame import arc_frame
from .band_mesh import MeshGeometry
from .band_trains import _repeats
from .moving import MovingMesh

__all__ = ["INSIDE_PER_TOOTH", "NcMesh", "internal_meshes", "moving", "nc_meshes", "planetary_meshes"]

TWO_PI = 2 * math.pi
INSIDE_PER_TOOTH = 4
"""Positions a driver tooth the slope estimate and the fit search's quick look start from (the
proof starts from :class:`~.moving.MovingMesh`'s own): the tooth pair that
closes the play may stand far from the pitch point for part of a tooth's passage (a dip of the
play about a pitch wide, nc_internal.toml: 0.150 mm against 0.20 mm either side); two a tooth
(:data:`~.certify.PER_TOOTH`) can straddle it, unseen by the slopes either side."""


@dataclass(frozen=True)
class NcMesh:
    """One mesh: its name, its geometry at any driver angle, the driver angles to start from,
    its cycle (rad), whether it is internal, its contact along the first positions, and gear 1's
    teeth past the contact a cycle; ``repeats``: the mesh a cycle on is this one turned (each
    outline its own vertices turned by its lobe: the proof wraps there, :func:`moving`)."""

    name: str
    at: object
    """phi (n,) -> :class:`~.band_mesh.MeshGeometry` at those driver angles."""
    first: np.ndarray
    cycle: float
    internal: bool
    contact: ContactData
    module: float
    """The teeth's module (mm; the geometry's may be larger, :func:`_window`)."""
    passes: int
    repeats: bool


def moving(mesh: NcMesh) -> MovingMesh:
    """The mesh as the proof measures it: gear 2's placement in gear 1's frame at any driver angle,
    its pitch radius at the contact taken at its least over each interval (``arm`` None)."""
    return MovingMesh(mesh=mesh.at(mesh.first), place=mesh.at, cycle=mesh.cycle, passes=mesh.passes, arm=None)


def _turned(xy: np.ndarray, angle) -> np.ndarray:
    """Points (n, 2) each turned by its ``angle`` (n,) about O."""
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]])


def _inward(tangent: np.ndarray) -> np.ndarray:
    """The unit normals (n, 2) a quarter turn left of the tangents at the angles ``tangent``: into
    a counter-clockwise curve."""
    return np.column_stack([-np.sin(tangent), np.cos(tangent)])


def _shape(spec) -> shapely.Polygon:
    return shapely.Polygon(spec.outer, None if spec.hole is None else [spec.hole])


def _tilt(normal_angle: np.ndarray, contact: np.ndarray, pivot: np.ndarray) -> np.ndarray:
    """The angle (rad, within ±π/2) between the pitch curves' common normal at the contact and the
    line from the contact to the driven part's pivot: the working pressure angle is α ∓ it."""
    d = np.arctan2(pivot[:, 1] - contact[:, 1], pivot[:, 0] - contact[:, 0])
    return (d - normal_angle + math.pi / 2) % math.pi - math.pi / 2


def _tooth(frame, phi: np.ndarray, pitch: float, teeth: int) -> np.ndarray:
    """The tooth (counted from polar angle 0) whose pitch arc holds the point at ``phi``."""
    return np.floor(frame.arc(np.mod(phi, TWO_PI)) / pitch).astype(int) % teeth


def _window(r1, r2, centre2, angle2, contact, module: float, *, points: int = 360) -> float:
    """The module scale that makes a mesh's window (three modules about the pitch point,
    :mod:`.band_mesh`) hold every stretch of gear 1 where a tooth of it may touch the ring: inside a
    ring the pitch curves part slowly, and a tooth pair far from the pitch point can close the play
    (nc_internal.toml: 20 mm away, ten modules).  At each position (``centre2``, ``angle2``,
    ``contact``: the ring's pivot and turn and the pitch point in gear 1's frame) gear 1's pitch
    curve ``r1`` is sampled and each point's radial gap to the ring's ``r2`` measured; where it is
    under :data:`NEAR` modules (the two toothings' heights, the edges and a shift, over the cos of
    any tilt) the point may be in contact, and the window reaches it and a tooth beyond.  The play's
    bounds scale with the window too, so the reach sought and the shrink tried grow, never the
    verdict."""
    chi = np.linspace(0.0, TWO_PI, points, endpoint=False)
    rho = r1(chi)
    p = np.stack([rho * np.cos(chi), rho * np.sin(chi)], -1)  # (points, 2)
    w = p[None, :, :] - centre2[:, None, :]
    gamma = np.arctan2(w[..., 1], w[..., 0]) - angle2[:, None]
    gap = r2(np.mod(gamma, TWO_PI)) - np.hypot(w[..., 0], w[..., 1])
    far = np.hypot(*(p[None, :, :] - contact[:, None, :]).transpose(2, 0, 1))
    reach = float(np.max(np.where(gap < NEAR * module, far, 0.0))) + 2 * module
    return max(1.0, reach / (3 * module))


NEAR = 4.0
"""Modules of radial gap between gear 1's and the ring's pitch curves under which a tooth pair may
touch (:func:`_window`): both toothings' heights (2), and the edges and shifts of a process with
room to spare."""


def internal_meshes(draft) -> list[NcMesh]:
    """The pinion–ring mesh of a noncircular internal pair."""
    pair, teeth = draft.detail, draft.data["teeth"]
    m, z1, alpha = teeth["module"], teeth["pinion_teeth"], draft.params.pressure_angle
    e, curve = pair.center_distance, pair.pinion
    shapes = (_shape(draft.parts[0]), _shape(draft.parts[1]))
    frame = arc_frame(curve)
    wide = 1.0

    def at(phi) -> MeshGeometry:
        phi = np.asarray(phi, dtype=float)
        u = np.column_stack([np.cos(phi), np.sin(phi)])
        r1 = curve.r(np.mod(phi, TWO_PI))
        return MeshGeometry(
            shapes=shapes,
            phi1=phi,
            centre2=-e * u,
            angle2=phi - pair.angle_map(phi),
            contact=r1[:, None] * u,
            tighter=-u,
            module=wide * m,
            pressure_angle=alpha,
            teeth=_tooth(frame, phi, math.pi * m, z1),
        )

    dense = at(np.linspace(0.0, pair.cycle, 96 * max(1, round(pair.cycle / TWO_PI)), endpoint=False))
    wide = _window(curve.r, pair.ring.r, dense.centre2, dense.angle2, dense.contact, m)  # at() reads it from here on
    n1, n2 = pair.lobes
    repeats = _repeats(shapes[0].exterior, n1) and _repeats(shapes[1].interiors[0], n2)
    cycle = TWO_PI / n1 if repeats else pair.cycle
    passes = round(z1 * cycle / TWO_PI)
    s = np.arange(INSIDE_PER_TOOTH * passes) * frame.perimeter / (INSIDE_PER_TOOTH * z1)
    first = frame.angle(s % frame.perimeter) + TWO_PI * np.floor(s / frame.perimeter)
    phi2 = pair.angle_map(first)
    k1 = curvature(curve, np.mod(first, TWO_PI))
    k2 = -curvature(pair.ring, np.mod(phi2, TWO_PI))  # the ring is concave at the contact
    ratio = contact_ratio(k1, k2, (m, m), alpha, m)
    mu = np.arctan2(curve.dr(np.mod(first, TWO_PI)), curve.r(np.mod(first, TWO_PI)))
    contact = ContactData(first, ratio, alpha - mu, alpha + mu)
    name = f"{draft.parts[0].name}/{draft.parts[1].name}"
    return [NcMesh(name, at, first, cycle, True, contact, m, passes, True)]


def planetary_meshes(draft) -> list[NcMesh]:
    """The first planet's meshes with the sun and with the ring, over one sun lobe."""
    from ..trains import nc_planetary as NP
    from ..trains import nc_set as NS

    ps, teeth, p = draft.detail, draft.data["teeth"], draft.params
    m, z, alpha = teeth["module"], teeth["sun"], p.pressure_angle
    sun, planet = ps.sun, ps.planet
    shapes = [_shape(part) for part in draft.parts]
    frames = [arc_frame(NS.as_pitch_curve(c, "curve")) for c in (sun, planet)]
    ring_curve = NS.ring_pitch_curve(ps)
    pitch = math.pi * m
    lobe = ps.lobe
    wide = 1.0

    last: dict = {}

    def state(theta):
        theta = np.asarray(theta, dtype=float)
        key = theta.tobytes()
        if key not in last:  # (both meshes' bounds ask for the same thousands of angles: once)
            pose = NP.poses(sun, planet, theta)
            p2 = pose.rho[:, None] * np.column_stack([np.cos(theta), np.sin(theta)])
            last.clear()
            last[key] = theta, pose, p2, ps.ring_turn(theta)
        return last[key]

    def sun_planet(theta) -> MeshGeometry:
        theta, pose, _, _ = state(theta)
        return MeshGeometry(
            shapes=(shapes[0], shapes[1]),
            phi1=theta,
            centre2=pose.centre,
            angle2=pose.beta,
            contact=sun.point(theta),
            tighter=_inward(sun.tangent_angle(theta)),
            module=m,
            pressure_angle=alpha,
            teeth=_tooth(frames[0], theta, pitch, z),
        )

    def planet_ring(theta) -> MeshGeometry:
        theta, pose, p2, phi_r = state(theta)
        back = -pose.beta
        return MeshGeometry(
            shapes=(shapes[1], shapes[2]),
            phi1=theta,
            centre2=_turned(-pose.centre, back),
            angle2=phi_r - pose.beta,
            contact=_turned(p2 - pose.centre, back),
            tighter=_inward(planet.tangent_angle(pose.chi)),
            module=wide * m,
            pressure_angle=alpha,
            teeth=_tooth(frames[1], pose.chi, pitch, z),
        )

    dense = planet_ring(np.linspace(0.0, lobe, 90, endpoint=False))
    wide = _window(planet.r, ring_curve.r, dense.centre2, dense.angle2, dense.contact, m)  # planet_ring() reads it
    count = INSIDE_PER_TOOTH * z // sun.lobes
    first = np.arange(count) * lobe / count
    theta, pose, p2, phi_r = state(first)
    s_point = sun.point(theta)
    normal_sun = sun.tangent_angle(theta) - math.pi / 2
    k_sun, k_planet = sun.curvature(theta), planet.curvature(pose.psi)
    mu1 = _tilt(normal_sun, s_point, pose.centre)
    gamma = ps.ring_angle(theta)
    rho, drho, d2rho = (f(np.mod(gamma, TWO_PI)) for f in (ring_curve.r, ring_curve.dr, ring_curve.d2r))
    k_ring, k_far = -polar_curvature(rho, drho, d2rho), planet.curvature(pose.chi)
    normal_far = planet.tangent_angle(pose.chi) + pose.beta - math.pi / 2
    mu2 = _tilt(normal_far, p2, pose.centre)
    contacts = (
        ContactData(first, contact_ratio(k_sun, k_planet, (m, m), alpha, m), alpha - mu1, alpha + mu1),
        ContactData(first, contact_ratio(k_far, k_ring, (m, m), alpha, m), alpha - mu2, alpha + mu2),
    )
    names = (f"{p.set.sun}/{p.set.planet}", f"{p.set.planet}/{p.set.ring}")
    n = sun.lobes
    repeats = [_repeats(shapes[k].exterior, n) for k in (0, 1)] + [_repeats(shapes[2].interiors[0], ps.ring_lobes)]
    return [
        NcMesh(names[0], sun_planet, first, lobe, False, contacts[0], m, z // n, repeats[0] and repeats[1]),
        NcMesh(names[1], planet_ring, first, lobe, True, contacts[1], m, z // n, repeats[1] and repeats[2]),
    ]


def nc_meshes(draft) -> list[NcMesh]:
    """The meshes of a noncircular internal pair or planetary set (by what its detail holds)."""
    return planetary_meshes(draft) if hasattr(draft.detail, "ring_turn") else internal_meshes(draft)
