"""Contact ratio and working pressure angle along a noncircular pair's pitch curves.

At each driver angle φ1 the pair meshes about the pitch point like the two spur gears that
osculate its pitch curves there (radii of curvature ρ1, ρ2; a concave stretch is an internal
gear): the line of action passes through the pitch point at the rack's pressure angle α to the
common tangent, and each gear's tip curve, h = (h_a + x)·m above its pitch curve, ends it.
Along the line, gear k's tip cuts off (signed curvature κ = 1/ρ, no cancellation as κ → 0)

    c(κ, h) = h·(2 + h·κ) / (√((1 + h·κ)² − cos²α) + sin α)

(h/sin α for a rack, √(r_a² − r_b²) − r·sin α for a circle), so the contact ratio is
ε(φ1) = (c1 + c2)/(π·m·cos α): on circles the textbook ε_α.  The tooth force on the driven gear
makes α − μ with the pitch point's velocity, μ = atan(r1'/r1) the tilt of the common tangent
off the perpendicular to the line of centres (driving flank, φ1 increasing; the coast flank has
α + μ): on circles α itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..pitch.curve import curvature
from ..pitch.pair import PairData
from .rack import Rack

__all__ = ["ContactData", "WorkingPressure", "contact_along", "contact_ratio", "tip_cut", "working_pressure"]


@dataclass(frozen=True)
class ContactData:
    phi1: np.ndarray
    """(n,) driver angles φ1 over one cycle, rad."""
    ratio: np.ndarray
    """(n,) contact ratio (tooth pairs in contact, on average over a base pitch)."""
    pressure_angle: np.ndarray
    """(n,) working pressure angle of the driving flank, rad."""
    coast_pressure_angle: np.ndarray
    """(n,) the same for the other flank (driver turning back), rad."""

    def as_dict(self) -> dict:
        """report.json's pair.teeth.contact: smallest and largest and where (φ1, degrees)."""
        out = {"positions": len(self.phi1)}
        for key, values, scale in (
            ("ratio", self.ratio, 1.0),
            ("pressure_angle", self.pressure_angle, 180 / math.pi),
            ("coast_pressure_angle", self.coast_pressure_angle, 180 / math.pi),
        ):
            unit = "" if scale == 1.0 else "_deg"
            lo, hi = int(np.argmin(values)), int(np.argmax(values))
            out[f"{key}_min{unit}"] = float(values[lo] * scale)
            out[f"{key}_min_at_phi1_deg"] = float(math.degrees(self.phi1[lo]))
            out[f"{key}_max{unit}"] = float(values[hi] * scale)
            out[f"{key}_max_at_phi1_deg"] = float(math.degrees(self.phi1[hi]))
        return out

    def sentence(self) -> str:
        d = self.as_dict()
        return (
            f"contact ratio {d['ratio_min']:.3f} (at φ1 = {d['ratio_min_at_phi1_deg']:.1f}°)…"
            f"{d['ratio_max']:.3f} (at {d['ratio_max_at_phi1_deg']:.1f}°); working pressure angle "
            f"{d['pressure_angle_min_deg']:.2f}° (at {d['pressure_angle_min_at_phi1_deg']:.1f}°)…"
            f"{d['pressure_angle_max_deg']:.2f}° (at {d['pressure_angle_max_at_phi1_deg']:.1f}°)"
        )


def tip_cut(kappa: np.ndarray, h: float, alpha: float) -> np.ndarray:
    """Length of the line of action from the pitch point to a tip curve h above a pitch curve of
    signed curvature ``kappa`` (1/mm; negative where concave), mm; 0 where the tip curve stays
    inside the base circle."""
    k = np.asarray(kappa, dtype=float)
    root = np.sqrt(np.maximum((1 + h * k) ** 2 - math.cos(alpha) ** 2, 0.0))
    return np.maximum(h * (2 + h * k) / (root + math.sin(alpha)), 0.0)


def contact_ratio(k1, k2, tips: tuple[float, float], alpha: float, module: float) -> np.ndarray:
    """The contact ratio of two toothings meshing about a pitch point where their pitch curves
    have signed curvatures ``k1``, ``k2`` (1/mm; negative: concave, a ring), their tips ``tips``
    mm above them."""
    k1, k2 = np.asarray(k1, dtype=float), np.asarray(k2, dtype=float)
    c1, c2 = tip_cut(k1, tips[0], alpha), tip_cut(k2, tips[1], alpha)
    # a tip cannot drive beyond where the line of action touches the mate's base circle
    # (that would be undercut flank): cap each cut at ρ_mate·sin α on a convex mate
    with np.errstate(divide="ignore"):
        c1 = np.where(k2 > 0, np.minimum(c1, math.sin(alpha) / k2), c1)
        c2 = np.where(k1 > 0, np.minimum(c2, math.sin(alpha) / k1), c2)
    return (c1 + c2) / (math.pi * module * math.cos(alpha))


def contact_along(pair: PairData, racks: tuple[Rack, Rack], positions: int = 720) -> ContactData:
    """Contact ratio and working pressure angles at ``positions`` driver angles over a cycle."""
    phi1 = np.linspace(0.0, pair.cycle, positions, endpoint=False)
    theta2 = np.pi - pair.angle_map(phi1)  # gear 2's own angle of the pitch point
    rack = racks[0]
    alpha, m = rack.params.pressure_angle, rack.params.module
    k1 = curvature(pair.gear1, phi1 % (2 * np.pi))
    k2 = curvature(pair.gear2, theta2 % (2 * np.pi))
    ratio = contact_ratio(k1, k2, (rack.v_tip, racks[1].v_tip), alpha, m)
    r1 = pair.gear1.r(phi1 % (2 * np.pi))
    mu = np.arctan2(pair.gear1.dr(phi1 % (2 * np.pi)), r1)
    return ContactData(phi1=phi1, ratio=ratio, pressure_angle=alpha - mu, coast_pressure_angle=alpha + mu)


@dataclass(frozen=True)
class WorkingPressure:
    """The largest working pressure angle of a pair over its cycle, either flank: α + |μ|."""

    largest: float
    """rad, refined to 1e-9 rad of φ1 about the largest of a dense sample."""
    phi1: float
    """gear 1's angle where it is largest, rad."""
    above: tuple[tuple[float, float], ...]
    """The stretches of φ1 (rad, start and end, each refined by bisection) where it exceeds the
    limit asked for; () when it never does."""


def _largest_tilt(pair: PairData, positions: int) -> tuple[np.ndarray, np.ndarray]:
    phi1 = np.linspace(0.0, 2 * np.pi, positions, endpoint=False)
    return phi1, np.abs(np.arctan2(pair.gear1.dr(phi1), pair.gear1.r(phi1)))


def working_pressure(pair: PairData, alpha: float, limit: float, positions: int = 4096) -> WorkingPressure:
    """The working pressure angle α + |μ|, tan μ = r1'/r1 (the tilt of the pitch curves' common
    tangent off the perpendicular to the line of centres, the same on both gears), at its
    largest over gear 1's turn and where it exceeds ``limit`` (rad).  Sampled at ``positions``
    angles, then the largest refined by golden section about the largest sample and each
    crossing of the limit by bisection between the samples that straddle it (|μ| is smooth
    between its zeros; a kink at μ = 0 is a minimum, never the largest)."""
    phi1, tilt = _largest_tilt(pair, positions)
    step = phi1[1] - phi1[0]

    def f(p: float) -> float:
        at = np.array([p % (2 * np.pi)])
        return float(np.abs(np.arctan2(pair.gear1.dr(at), pair.gear1.r(at)))[0])

    k = int(np.argmax(tilt))
    lo, hi = phi1[k] - step, phi1[k] + step
    g = (math.sqrt(5) - 1) / 2
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = f(a), f(b)
    while hi - lo > 1e-9:
        if fa >= fb:
            hi, b, fb = b, a, fa
            a = hi - g * (hi - lo)
            fa = f(a)
        else:
            lo, a, fa = a, b, fb
            b = lo + g * (hi - lo)
            fb = f(b)
    best, where = (fa, a) if fa >= fb else (fb, b)
    best, where = max((best, where), (float(tilt[k]), float(phi1[k])))
    over = alpha + tilt > limit
    stretches: list[tuple[float, float]] = []
    if over.any() and not over.all():

        def crossing(i: int) -> float:  # between samples i and i + 1, one over and one not
            x0, x1 = phi1[i], phi1[i] + step
            up = alpha + f(x0) > limit
            while x1 - x0 > 1e-9:
                mid = (x0 + x1) / 2
                x0, x1 = (mid, x1) if (alpha + f(mid) > limit) == up else (x0, mid)
            return (x0 + x1) / 2

        starts = sorted(crossing(i) for i in np.flatnonzero(~over & np.roll(over, -1)))
        ends = [crossing(i) for i in np.flatnonzero(over & ~np.roll(over, -1))]
        for start in starts:  # each stretch ends at the first end after its start, all round
            end = min(ends, key=lambda e: (e - start) % (2 * np.pi))
            stretches.append((start % (2 * np.pi), end % (2 * np.pi)))
    elif over.all():
        stretches = [(0.0, 2 * np.pi)]
    return WorkingPressure(alpha + best, where % (2 * np.pi), tuple(stretches))
