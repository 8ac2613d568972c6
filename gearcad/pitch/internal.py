"""The internal conjugate: a noncircular pinion rolling inside a noncircular ring, fixed centres.

The pinion (gear 1) turns about the origin, the ring (gear 2) about (−E, 0).  The contact is on
the line of centres on the same side of both centres, at (r1, 0): the pinion turned clockwise by
φ1 brings its body point at polar angle φ1 there, the ring turned clockwise by φ2 its body point
at polar angle φ2.  Rolling without slip means

    r2(φ2) = r1(φ1) + E,    dφ2/dφ1 = r1/(r1 + E)

(both turn the same way, the ring slower).  The ring closes with n2 lobes round a pinion of n1
when φ2(2π) = 2π·n1/n2 (n2 > n1): the turn ∫ r1/(r1 + E) dφ1 falls monotonically from 2π
(E → 0) to 0 (E → ∞), so E is bracketed and found by Brent's method.  For the pinion to stay
inside the ring near the contact its pitch curve must bend more: κ1 > κ2 at every contact.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import gcd

import numpy as np

from ..errors import DesignError
from ..roots import brentq
from ..tolerances import DEFAULT, Tolerances
from . import chebyshev
from .curve import TWO_PI, PitchCurve, polar_curvature, radius_range, segments
from .pair import AngleMap, turn_on_nodes

__all__ = ["InternalPairData", "internal_angle_map", "solve_internal_distance", "ring_curve", "internal_pair"]


def internal_angle_map(curve: PitchCurve, center_distance: float, *, tol: Tolerances = DEFAULT) -> AngleMap:
    """The ring's angle as a function of the pinion's for centre distance ``E``."""
    e = center_distance

    def rate(p):
        r = curve.r(p)
        return r / (r + e)

    fitted = chebyshev.fit(rate, segments(curve), rel_tol=tol.fit_rel)
    forward = fitted.integral()
    turn = float(forward(np.array([TWO_PI]))[0])
    return AngleMap(forward, fitted, rate, turn)


def solve_internal_distance(curve: PitchCurve, target_turn: float, *, tol: Tolerances = DEFAULT) -> float:
    """Centre distance E at which the ring turns ``target_turn`` (0 < target < 2π) per pinion turn.

    ∫ r/(r + E) dφ is minus the external pair's ∫ r/(E′ − r) dφ at E′ = −E, so the external
    Clenshaw–Curtis rule serves; the root is refined until the spectrally fitted map confirms
    closure."""
    if not 0 < target_turn < TWO_PI:
        raise DesignError(f"the ring's turn per pinion turn must lie in (0, 2π), got {target_turn:.6g}")
    r_max = radius_range(curve)[1]
    n = 64
    while True:
        external = turn_on_nodes(curve, n)  # ∫ r/(E − r) dφ

        def turn(e: float, external=external) -> float:
            return -external(-e)  # ∫ r/(−E − r) dφ = −∫ r/(r + E) dφ

        lo, hi = 1e-12 * r_max, r_max
        while turn(hi) - target_turn > 0:
            hi *= 2
        e = brentq(lambda x: turn(x) - target_turn, lo, hi, xtol=1e-15 * hi, rtol=1e-15)
        closure = abs(internal_angle_map(curve, e, tol=tol).turn - target_turn)
        if closure <= tol.closure_rad or n >= 1 << 14:
            return e
        n *= 4


def ring_curve(pinion: PitchCurve, center_distance: float, amap: AngleMap, *, lobes: int, name: str = "") -> PitchCurve:
    """The ring's pitch curve r2(θ) = r1(φ1) + E with φ1 = φ2⁻¹(θ), derivatives by the chain rule:
    dφ1/dθ = (r1 + E)/r1."""
    e = center_distance

    def r(theta):
        return pinion.r(amap.inverse(np.asarray(theta, dtype=float))) + e

    def dr(theta):
        p = amap.inverse(np.asarray(theta, dtype=float))
        r1 = pinion.r(p)
        return pinion.dr(p) * (r1 + e) / r1

    def d2r(theta):
        p = amap.inverse(np.asarray(theta, dtype=float))
        r1, r1p, r1pp = pinion.r(p), pinion.dr(p), pinion.d2r(p)
        return (r1pp * (r1 + e) / r1 - e * r1p * r1p / (r1 * r1)) * (r1 + e) / r1

    seams = np.array([float(b) for b in pinion.breaks])
    repeats = int(np.ceil(TWO_PI / amap.turn)) + 2
    breaks = sorted(
        {float(m + q * amap.turn) % TWO_PI for m in (amap(seams) if len(seams) else []) for q in range(repeats)}
    )
    return PitchCurve(name=name or f"ring of {pinion.name}", r=r, dr=dr, d2r=d2r, lobes=lobes, breaks=tuple(breaks))


@dataclass(frozen=True)
class InternalPairData:
    """A pinion and the ring it rolls in, with the measured residuals."""

    pinion: PitchCurve
    ring: PitchCurve
    center_distance: float
    lobes: tuple[int, int]
    angle_map: AngleMap
    closure_error: float
    """|φ2(2π) − 2π·n1/n2|, rad."""
    contact_residual: float
    """max |r2 − r1 − E| over a cycle, mm."""
    slip_residual: float
    """max |r1 − r2·dφ2/dφ1| over a cycle, mm per rad of pinion."""
    curvature_margin: float
    """min over the cycle of κ1 − κ2 at the contact, 1/mm: > 0 keeps the pinion inside."""

    @property
    def cycle(self) -> float:
        """Pinion angle after which the pair returns to its start, rad."""
        n1, n2 = self.lobes
        return TWO_PI * n2 / gcd(n1, n2)


def internal_pair(
    pinion: PitchCurve,
    *,
    ring_lobes: int,
    center_distance: float | None = None,
    key: str = "ring.lobes",
    tol: Tolerances = DEFAULT,
) -> InternalPairData:
    """The ring of ``ring_lobes`` lobes in which ``pinion`` rolls; E solved from closure unless given."""
    n1, n2 = pinion.lobes, ring_lobes
    if n2 <= n1:
        raise DesignError(
            f"{key} = {n2}: a ring round a pinion of {n1} lobes needs more lobes than it, {n1 + 1} or more"
        )
    target = TWO_PI * n1 / n2
    if center_distance is None:
        center_distance = solve_internal_distance(pinion, target, tol=tol)
    amap = internal_angle_map(pinion, center_distance, tol=tol)
    ring = ring_curve(pinion, center_distance, amap, lobes=n2)
    phi1 = np.linspace(0.0, TWO_PI * n2 / gcd(n1, n2), 4097)
    phi2 = amap(phi1)
    r1 = pinion.r(phi1)
    r2 = ring.r(phi2)
    contact = float(np.max(np.abs(r2 - r1 - center_distance)))
    slip = float(np.max(np.abs(r1 - r2 * amap.slope(phi1))))
    k1 = polar_curvature(r1, pinion.dr(phi1), pinion.d2r(phi1))
    k2 = polar_curvature(r2, ring.dr(phi2), ring.d2r(phi2))
    return InternalPairData(
        pinion=pinion,
        ring=ring,
        center_distance=float(center_distance),
        lobes=(n1, n2),
        angle_map=amap,
        closure_error=abs(amap.turn - target),
        contact_residual=contact,
        slip_residual=slip,
        curvature_margin=float(np.min(k1 - k2)),
    )
