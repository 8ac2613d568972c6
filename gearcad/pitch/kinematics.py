"""Angular velocity and acceleration of the follower when the driver turns steadily.

Computed from the two pitch curves at their contact point (not from any paper's closed form):
the follower/driver speed ratio is r_driver/r_follower, and its derivative by the chain rule.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .curve import TWO_PI
from .pair import PairData

__all__ = ["KinematicsData", "kinematics"]


@dataclass(frozen=True)
class KinematicsData:
    """Follower motion over one turn of the driver, sampled at ``driver_angle``.

    Speeds are magnitudes (the follower of an external pair turns the other way).
    """

    driver: int
    """1 or 2: which gear turns at constant speed."""
    driver_speed: float
    """rad/s."""
    driver_angle: np.ndarray
    """(n,) float, rad."""
    follower_angle: np.ndarray
    """(n,) float, rad."""
    ratio: np.ndarray
    """(n,) follower speed / driver speed."""
    speed: np.ndarray
    """(n,) follower angular velocity, rad/s."""
    acceleration: np.ndarray
    """(n,) follower angular acceleration, rad/s²."""


def _contact(pair: PairData, driver: int, psi: np.ndarray):
    """Driver/follower radii at the contact and their rates of change per rad of driver."""
    amap, g1, g2 = pair.angle_map, pair.gear1, pair.gear2
    if driver == 1:
        phi1 = psi
        theta = np.pi - amap(phi1)
        r_d, dr_d = g1.r(phi1), g1.dr(phi1)
        r_f = g2.r(theta)
        k = r_d / r_f
        dr_f = -g2.dr(theta) * k  # θ = π − φ2 decreases at rate k
        follower = amap(phi1)
    else:
        theta = np.pi - psi
        phi1 = amap.inverse(psi)
        r_d, dr_d = g2.r(theta), -g2.dr(theta)
        r_f = g1.r(phi1)
        k = r_d / r_f
        dr_f = g1.dr(phi1) * k
        follower = phi1
    return r_d, dr_d, r_f, dr_f, follower


def kinematics(pair: PairData, *, driver: int = 1, speed: float = 1.0, angle=None) -> KinematicsData:
    """Follower speed and acceleration at constant driver ``speed`` (rad/s).

    Parameters
    ----------
    angle : (n,) float, optional
        Driver angles (rad); one turn in 0.5° steps when omitted.
    """
    if driver not in (1, 2):
        raise ValueError(f"driver must be 1 or 2, got {driver!r}")
    psi = np.linspace(0.0, TWO_PI, 721) if angle is None else np.asarray(angle, dtype=float)
    r_d, dr_d, r_f, dr_f, follower = _contact(pair, driver, psi)
    ratio = r_d / r_f
    dratio = (dr_d * r_f - r_d * dr_f) / (r_f * r_f)
    return KinematicsData(
        driver=driver,
        driver_speed=speed,
        driver_angle=psi,
        follower_angle=follower,
        ratio=ratio,
        speed=speed * ratio,
        acceleration=speed * speed * dratio,
    )
