"""Gear trains on a carrier, by the method of stopping (seed 001).

Gear 1 turns about the fixed axis at ω1, ε1; the carrier (crank) turns about the same axis at
ω, ε and carries the other gears' centres.  In the carrier's frame every gear turns about a
fixed centre at Ω_k = ω_k + ω (the seed projects the carrier's rotation as −ω), and meshing
gears share the velocity of their contact point: Ω_k·r_k = −Ω_{k+1}·r_{k+1} for an external
mesh, +Ω_{k+1}·r_{k+1} for an internal one.  Accelerations follow the same chain.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["TrainData", "solve_train", "solve_by_velocities", "three_gear_external", "three_gear_internal"]


@dataclass(frozen=True)
class TrainData:
    radii: tuple[float, ...]
    meshes: tuple[str, ...]
    """"external" or "internal", one per consecutive pair."""
    omega: np.ndarray
    """Absolute angular velocity of each gear, rad/s (gear 1 first)."""
    epsilon: np.ndarray
    """Absolute angular acceleration of each gear, rad/s²."""
    relative: np.ndarray
    """Ω_k = ω_k + ω: each gear's speed seen from the carrier."""


def solve_train(radii, meshes, *, omega1: float, epsilon1: float, carrier: float, carrier_eps: float) -> TrainData:
    """Every gear's ω and ε by the method of stopping."""
    radii = tuple(float(r) for r in radii)
    if len(meshes) != len(radii) - 1:
        raise ValueError(f"{len(radii)} gears need {len(radii) - 1} meshes, got {len(meshes)}")
    rel_w = [omega1 + carrier]
    rel_e = [epsilon1 + carrier_eps]
    for k, mesh in enumerate(meshes):
        sign = -1.0 if mesh == "external" else 1.0
        rel_w.append(sign * rel_w[-1] * radii[k] / radii[k + 1])
        rel_e.append(sign * rel_e[-1] * radii[k] / radii[k + 1])
    rel_w, rel_e = np.array(rel_w), np.array(rel_e)
    return TrainData(radii, tuple(meshes), rel_w - carrier, rel_e - carrier_eps, rel_w)


def solve_by_velocities(radii, meshes, *, omega1: float, carrier: float, angle: float = 0.3) -> np.ndarray:
    """Independent check: absolute velocities in the fixed frame, no stopping.

    Gear centres sit on the carrier line at the given angle; each contact point's velocity
    computed as a point of gear k (its centre moving with the carrier) must equal it as a
    point of gear k+1, which fixes ω_{k+1}.  Positive ω is counter-clockwise; the carrier's ω
    is taken clockwise-positive as in the seed (its z-projection is −ω).
    """
    u = np.array([np.cos(angle), np.sin(angle)])
    n = np.array([-u[1], u[0]])
    wz_carrier = -carrier
    centres = [0.0]
    for k, mesh in enumerate(meshes):
        step = radii[k] + radii[k + 1] if mesh == "external" else radii[k] - radii[k + 1]
        centres.append(centres[-1] + step)
    omegas = [omega1]
    for k in range(len(meshes)):
        c_k, c_next = centres[k] * u, centres[k + 1] * u
        contact = c_k + radii[k] * u  # on the carrier line, r_k out from gear k's centre
        # velocity of a point p of gear j: carrier moves its centre, gear spins about it
        v_centre_k = wz_carrier * np.array([-c_k[1], c_k[0]])
        v = v_centre_k + omegas[k] * np.array([-(contact - c_k)[1], (contact - c_k)[0]])
        v_centre_next = wz_carrier * np.array([-c_next[1], c_next[0]])
        arm = contact - c_next
        # v = v_centre_next + ω·(−arm_y, arm_x): solve along the tangent direction n
        perp = np.array([-arm[1], arm[0]])
        omegas.append(float((v - v_centre_next) @ n / (perp @ n)))
    return np.array(omegas)


def three_gear_external(r1, r3, *, omega1, carrier):
    """The seed's closed form for three external gears: ω3 = ω1·r1/r3 + ω·(r1 − r3)/r3."""
    return omega1 * r1 / r3 + carrier * (r1 - r3) / r3


def three_gear_internal(r1, r3, *, omega1, carrier):
    """The seed's closed form with gear 3 inside gear 2: ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3."""
    return -(omega1 * r1 + carrier * r1 + carrier * r3) / r3
