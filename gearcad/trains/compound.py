"""Compound gears on a carrier (seed 001, second scheme): gear 2 as a ring with two toothings.

Gear 1 turns about the fixed centre O at ω1, ε1; the carrier turns at ω, ε (clockwise: the seed
projects it as −ω on z) and carries the other centres.  Gear 2 meshes gear 1 with external
teeth of pitch radius r2_outer, and gear 3 turns inside it on internal teeth of pitch radius
r2_inner.  By the method of stopping (carrier frame, every centre fixed, Ω_k = ω_k + ω):

    Ω1·r1 = −Ω2·r2_outer (external),    Ω2·r2_inner = Ω3·r3 (internal: same sign),

so ω3 = −(ω1 + ω)·r1·r2_inner/(r2_outer·r3) − ω, and ε3 the same with ε1, ε.  With
r2_inner = r2_outer the seed's formula ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3 returns.

Any chain of meshes, each naming the pitch radius used on either side, is solved by
:func:`solve_chain`; :func:`chain_by_velocities` is the independent check in the fixed frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "Mesh",
    "CompoundRing",
    "ChainData",
    "solve_chain",
    "chain_centres",
    "chain_by_velocities",
    "seed_internal_formula",
]


@dataclass(frozen=True)
class Mesh:
    """One mesh of a chain: ``kind`` "external", or "internal" (the next gear turns inside this
    one's internal teeth); ``r_from`` the pitch radius of this gear's toothing in the mesh,
    ``r_to`` the next gear's; ``angle`` where the next centre sits, rad from the carrier line."""

    kind: str
    r_from: float
    r_to: float
    angle: float = 0.0

    def __post_init__(self):
        if self.kind not in ("external", "internal"):
            raise ValueError(f"mesh kind must be 'external' or 'internal', got {self.kind!r}")
        if self.r_from <= 0 or self.r_to <= 0:
            raise ValueError(f"pitch radii must be positive, got {self.r_from:g} and {self.r_to:g}")
        if self.kind == "internal" and self.r_to >= self.r_from:
            raise ValueError(
                f"an internal mesh needs the inner gear smaller than the ring: r_to = {self.r_to:g} "
                f"must be < r_from = {self.r_from:g}"
            )


@dataclass(frozen=True)
class CompoundRing:
    """The seed's second scheme with gear 2 as a real compound ring (pitch radii, mm)."""

    r1: float
    r2_outer: float
    """Gear 2's external toothing, meshing gear 1."""
    r2_inner: float
    """Gear 2's internal toothing, meshing gear 3."""
    r3: float
    inner_angle: float = 0.0
    """Where gear 3's centre sits inside gear 2, rad from the carrier line."""

    @property
    def meshes(self) -> tuple[Mesh, Mesh]:
        return (
            Mesh("external", self.r1, self.r2_outer),
            Mesh("internal", self.r2_inner, self.r3, self.inner_angle),
        )

    def wall(self, module_outer: float, module_inner: float, *, dedendum: float = 1.25) -> float:
        """Radial material left in the ring between the external teeth's root circle and the
        internal teeth's root circle (mm); must be positive (a few modules) for a real part."""
        return (self.r2_outer - dedendum * module_outer) - (self.r2_inner + dedendum * module_inner)

    def omega3_closed_form(self, *, omega1: float, carrier: float) -> float:
        """ω3 = −(ω1 + ω)·r1·r2_inner/(r2_outer·r3) − ω."""
        return -(omega1 + carrier) * self.r1 * self.r2_inner / (self.r2_outer * self.r3) - carrier


@dataclass(frozen=True)
class ChainData:
    omega: np.ndarray
    """Absolute angular velocity of each gear (z-projection, counter-clockwise +), rad/s."""
    epsilon: np.ndarray
    """Absolute angular acceleration of each gear, rad/s²."""
    relative: np.ndarray
    """Ω_k = ω_k + ω, each gear's speed seen from the carrier."""


def solve_chain(meshes, *, omega1: float, epsilon1: float, carrier: float, carrier_eps: float) -> ChainData:
    """Every gear's ω and ε by the method of stopping: Ω_{k+1} = ∓Ω_k·r_from/r_to."""
    rel_w, rel_e = [omega1 + carrier], [epsilon1 + carrier_eps]
    for mesh in meshes:
        sign = -1.0 if mesh.kind == "external" else 1.0
        rel_w.append(sign * rel_w[-1] * mesh.r_from / mesh.r_to)
        rel_e.append(sign * rel_e[-1] * mesh.r_from / mesh.r_to)
    rel_w, rel_e = np.array(rel_w), np.array(rel_e)
    return ChainData(rel_w - carrier, rel_e - carrier_eps, rel_w)


def chain_centres(meshes, *, carrier_angle: float = 0.0) -> np.ndarray:
    """Gear centres (n + 1, 2) in mm, gear 1 at the origin, the carrier line at
    ``carrier_angle``; each next centre at the mesh's centre distance and angle."""
    centres = [np.zeros(2)]
    for mesh in meshes:
        direction = carrier_angle + mesh.angle
        step = mesh.r_from + mesh.r_to if mesh.kind == "external" else mesh.r_from - mesh.r_to
        centres.append(centres[-1] + step * np.array([math.cos(direction), math.sin(direction)]))
    return np.array(centres)


def _cross_z(w: float, v: np.ndarray) -> np.ndarray:
    """(0, 0, w) × (v, 0)."""
    return w * np.array([-v[1], v[0]])


def chain_by_velocities(meshes, *, omega1: float, carrier: float, carrier_angle: float = 0.3) -> np.ndarray:
    """Independent check in the fixed frame, no stopping: each contact point's velocity as a
    point of gear k (its centre carried round at −ω) must equal it as a point of gear k + 1
    along the common tangent, which fixes ω_{k+1}.  Returns every gear's ω (rad/s)."""
    centres = chain_centres(meshes, carrier_angle=carrier_angle)
    wz_carrier = -carrier
    omegas = [omega1]
    for k, mesh in enumerate(meshes):
        c_k, c_next = centres[k], centres[k + 1]
        direction = (c_next - c_k) / np.hypot(*(c_next - c_k))
        contact = c_k + mesh.r_from * direction  # external: between the centres; internal: beyond c_next
        v_centre_k = np.zeros(2) if k == 0 else _cross_z(wz_carrier, c_k)
        v = v_centre_k + _cross_z(omegas[k], contact - c_k)
        v_centre_next = _cross_z(wz_carrier, c_next)
        tangent = np.array([-direction[1], direction[0]])
        # v = v_centre_next + ω·ẑ × (contact − c_next): solve along the tangent
        omegas.append(float((v - v_centre_next) @ tangent / (_cross_z(1.0, contact - c_next) @ tangent)))
    return np.array(omegas)


def seed_internal_formula(r1: float, r3: float, *, omega1: float, carrier: float) -> float:
    """The seed's result for its second scheme (one radius r2 for both toothings):
    ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3 — independent of r2."""
    return -(omega1 * r1 + carrier * r1 + carrier * r3) / r3
