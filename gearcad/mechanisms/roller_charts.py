"""What the roller body's charts are drawn from, computed with the design (the exporters draw
and compute nothing of the model): the amplitude limits, the velocity and acceleration field of
the contour as cut, the limits against the roller radius and the paper's Figs. 1–2."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..bodies import claims as C
from ..bodies import limits as LM
from ..bodies import rollers as RB
from .chart_data import (
    AmplitudeLimitsChart,
    Blocks,
    Charts,
    FieldFrame,
    LimitsVsRChart,
    ShapeFamilyChart,
    VelocityFieldChart,
)

__all__ = ["FIELD_ANGLES", "charts", "velocity_field"]

FIELD_ANGLES = (0.0, 30.0, 60.0, 90.0)
"""The body's turn angles (degrees) at which the field is drawn."""
FIGURES = ((1, 3, (0.1, 0.15, 0.2)), (2, 6, (0.03, 0.05, 0.1)))
"""The paper's Figs. 1 and 2: figure, m and the amplitudes drawn (units of R)."""


def velocity_field(osc: RB.Oscillation, *, w: float, roller_radius: float) -> list[FieldFrame]:
    """At each of :data:`FIELD_ANGLES`: the contour of roller radius ``roller_radius`` (units
    of R) where it is then (``outline``, (n, 2)), and 49 of its points (``points``) with their
    ``velocity`` and ``acceleration`` (units of R, per s and per s²)."""
    tau = np.linspace(0, 2 * math.pi, 49, endpoint=False)
    dense = RB.contour(osc, np.linspace(0, 2 * math.pi, 2000), r=roller_radius)[::10]
    pts = RB.contour(osc, tau, r=roller_radius)
    field = []
    for degrees in FIELD_ANGLES:
        t = math.radians(degrees) / w
        # every point at the same instant: the motion is elementwise in the point and the time
        outline = RB.point_motion(osc, dense[:, 0], dense[:, 1], w=w, t=np.full(len(dense), t))[0]
        position, velocity, acceleration = RB.point_motion(osc, pts[:, 0], pts[:, 1], w=w, t=np.full(len(pts), t))
        field.append(
            FieldFrame(degrees=degrees, outline=outline, points=position, velocity=velocity, acceleration=acceleration)
        )
    return field


@lru_cache(maxsize=8)
def _family(direction: str, m: int, amplitudes: tuple[float, ...]) -> tuple[dict, ...]:
    """The paper's figure for a direction: the same for every profile, so made once a process."""
    family = LM.shape_family(direction, m, amplitudes, LM.PAPER_RADII)
    for entry in family:
        entry["points"].flags.writeable = False
    return tuple(family)


def charts(osc: RB.Oscillation, p, roller_radius: float, data: Blocks) -> Charts:
    """Chart file → its data, for a roller-body profile ``p`` whose parts are cut with rollers
    of ``roller_radius`` (units of R; the requested one adjusted to whole teeth)."""
    if not p.output.charts:
        return {}
    out: Charts = {}
    if "limits" in data:
        out["amplitude_limits.png"] = AmplitudeLimitsChart(
            limits=data["limits"],
            direction=p.direction,
            roller_radius=p.roller_radius,
            eq4=(C.EQ4["coefficient"], C.EQ4["exponent"]),
        )
    field = velocity_field(osc, w=p.rpm * 2 * math.pi / 60, roller_radius=roller_radius)
    out["velocity_field.png"] = VelocityFieldChart(
        direction=p.direction, m=p.m, amplitude=p.amplitude, rpm=p.rpm, roller_radius=roller_radius, field=field
    )
    if "limits_vs_r" in data:
        out["limits_vs_r.png"] = LimitsVsRChart(table=data["limits_vs_r"], paper_by_eye=C.PAPER_BY_EYE)
        for fig, m, amplitudes in FIGURES:
            family = _family(p.direction, m, amplitudes)
            out[f"shape_family_m{m}.png"] = ShapeFamilyChart(family=family, title=f"Fig. {fig}: {p.direction}, m = {m}")
    return out
