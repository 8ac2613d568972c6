"""The generating rack: its profile in rolling-line coordinates.

Coordinates (u, v): u along the rack's rolling line (the line that rolls without slip on the
pitch curve), v across it, positive away from the gear.  A rack tooth centred at u = 0 cuts a
tooth space of the gear.  With profile shift x the rack sits x·m further out, so its reference
line is at v = x·m; backlash thins the gear's teeth by widening the rack's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError

__all__ = ["RackParams", "Rack", "rack_polygon"]


@dataclass(frozen=True)
class RackParams:
    module: float
    """mm."""
    pressure_angle: float = math.radians(20)
    """rad."""
    addendum: float = 1.0
    """Gear addendum coefficient (tip height over the pitch curve / m)."""
    dedendum: float = 1.25
    """Gear dedendum coefficient (root depth under the pitch curve / m) = rack tooth height."""
    tip_radius: float = 0.38
    """Rack tip fillet radius / m (cuts the trochoidal root fillet)."""
    profile_shift: float = 0.0
    """x: the rack moved out by x·m."""
    thinning: float = 0.0
    """How much thinner than nominal each gear tooth is on the pitch curve, mm (half the
    pair's backlash)."""


@dataclass(frozen=True)
class Rack:
    """Derived rack geometry (mm, rad)."""

    params: RackParams
    pitch: float
    half_width: float
    """w0: half the rack tooth thickness on the rolling line."""
    tan_a: float
    cot_a: float
    v_tip: float
    """Gear tip (blank) height above the pitch curve."""
    v_root: float
    """Depth of the rack tip line, i.e. the gear's root (negative)."""
    v_low: float
    """Where the straight flank meets the tip fillet (negative)."""
    fillet_u: float
    """u of the fillet centre (right side, ≥ 0)."""
    fillet_v: float
    radius: float
    """Fillet radius, mm."""

    @classmethod
    def from_params(cls, p: RackParams) -> Rack:
        m, a = p.module, p.pressure_angle
        pitch = math.pi * m
        w0 = pitch / 4 - p.profile_shift * m * math.tan(a) + p.thinning / 2
        v_root = (p.profile_shift - p.dedendum) * m
        rho = p.tip_radius * m
        v_c = v_root + rho
        u_c = w0 + v_c * math.tan(a) - rho / math.cos(a)
        if u_c < -1e-12:
            # the rack tooth's half width at its tip line: the room the fillet has
            room = w0 + v_root * math.tan(a)
            if room <= 0:  # pointed before its tip line: no fillet fits, the tooth is too deep
                most = p.profile_shift + (w0 - rho * (1 - math.sin(a)) / math.cos(a)) / (m * math.tan(a))
                raise DesignError(
                    f"teeth.dedendum = {p.dedendum:g}: the rack tooth comes to a point before that depth at "
                    f"{math.degrees(a):g}°; at most {max(most, 0):.3f} fits with teeth.tip_radius = {p.tip_radius:g} "
                    "(or a smaller teeth.pressure_angle_deg)"
                )
            limit = room * math.cos(a) / (1 - math.sin(a)) / m
            raise DesignError(
                f"teeth.tip_radius = {p.tip_radius:g}: the rack tip is too narrow for this fillet; "
                f"at most {limit:.3f} fits"
            )
        return cls(
            params=p,
            pitch=pitch,
            half_width=w0,
            tan_a=math.tan(a),
            cot_a=1 / math.tan(a),
            v_tip=(p.profile_shift + p.addendum) * m,
            v_root=v_root,
            v_low=v_c - rho * math.sin(a),
            fillet_u=max(u_c, 0.0),
            fillet_v=v_c,
            radius=rho,
        )

    @property
    def fillet_start(self) -> float:
        """β where the fillet meets the straight flank: the flank's outward normal, −α."""
        return -self.params.pressure_angle


def rack_polygon(rack: Rack, teeth: int, *, samples: int = 12) -> np.ndarray:
    """One rack as a closed (n, 2) polygon in (u, v), teeth centred at u = k·p, k = 0…teeth−1:
    flanks up to the rack's root land a quarter module above the gear's tip, a body above
    that.  For drawings and the boolean reference method."""
    m = rack.params.module
    land = rack.v_tip + 0.25 * m
    beta = np.linspace(-math.pi / 2, rack.fillet_start, samples)
    pts = []
    for k in range(teeth):
        c = k * rack.pitch
        pts.append((c - rack.half_width - land * rack.tan_a, land))
        pts += list(
            zip(c - rack.fillet_u - rack.radius * np.cos(beta[::-1]), rack.fillet_v + rack.radius * np.sin(beta[::-1]))
        )
        pts += list(zip(c + rack.fillet_u + rack.radius * np.cos(beta), rack.fillet_v + rack.radius * np.sin(beta)))
        pts.append((c + rack.half_width + land * rack.tan_a, land))
    pts += [
        (pts[-1][0] + rack.pitch / 2, land),
        (pts[-1][0] + rack.pitch / 2, land + 2 * m),
        (pts[0][0] - rack.pitch / 2, land + 2 * m),
        (pts[0][0] - rack.pitch / 2, land),
    ]
    return np.array(pts)
