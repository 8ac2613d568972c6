"""Reference method for tests and benchmarks only: the gear as the blank minus a union of
rack copies at many sampled positions (what a rack cutter physically does).  Slow, and its
accuracy is limited by the number of positions; gearcad's outlines come from the closed-form
envelope in :mod:`gearcad.teeth.gear`."""

from __future__ import annotations

import numpy as np
import shapely

from .frame import ArcFrame
from .rack import Rack, rack_polygon

__all__ = ["rack_cut"]


def rack_cut(
    frame: ArcFrame, rack: Rack, teeth: int, phase: float, *, steps_per_pitch: int = 24, samples: int = 400
) -> shapely.Polygon:
    """Blank (the tip curve) minus the rack placed at ``steps_per_pitch`` positions per pitch.

    The rack drawn has 5 teeth centred on the pitch point, enough to cover the mesh zone.
    """
    p = rack.pitch
    s_blank = np.linspace(0.0, frame.perimeter, samples * teeth // 10 + 64, endpoint=False)
    c, _, n = frame.frame(s_blank)
    blank = shapely.Polygon(c + rack.v_tip * n)
    local = rack_polygon(rack, 5, samples=16)
    local[:, 0] -= 2 * p  # teeth at −2p … 2p
    cutters = []
    for s in phase + np.arange(teeth * steps_per_pitch) * p / steps_per_pitch:
        # the rack tooth at u = 0 sits on the space centred at `phase + k·p`; position the
        # rack so that its coordinate u = s touches C(s)
        shift = (s - phase) - np.round((s - phase) / p) * p  # rack coordinate of C(s), near 0
        u = local[:, 0] + (s - shift)
        c, t, n = frame.frame(np.array([s]))
        pts = c + (u - s)[:, None] * t + local[:, 1][:, None] * n
        cutters.append(shapely.Polygon(pts))
    return shapely.difference(blank, shapely.union_all(cutters))
