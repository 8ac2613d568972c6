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

__all__ = ["ContactData", "contact_along", "contact_ratio", "tip_cut"]


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
