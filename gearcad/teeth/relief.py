"""Relief where the rack's envelope is not conjugate to the mate: trim gear 1 by the mate's sweep.

On a concave stretch of a pitch curve the rack leaves the local envelope, and where the mate's
flank was shaped by the rack's tip (below ~0.75 m) the two racks' contacts no longer coincide:
gear 1's tip keeps material that the mate's tooth passes through (the walker's wheel at its
seams, 16 µm).  Cutting gear 1 with the mate itself, as a shaper cutter would, over the driver
angles where the proof found the pair too deep removes exactly that material and nothing else:
a tip relief found by the conjugate motion, not chosen by hand.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..geometry.outline import Outline
from ..geometry.verify import nearest
from ..pitch.pair import PairData
from .frame import ArcFrame
from .gear import ToothedGear
from .mesh import MeshData, placing

__all__ = ["Relief", "relieve", "MAX_RELIEF_MODULES"]

MAX_RELIEF_MODULES = 0.02
"""The deepest bite the trim takes off, in modules: the size of a tip relief (a few hundredths
of a module; the walker's seams need 0.011 m).  A deeper bite is not a tip left by a
non-conjugate rack but a pair that interferes (undercut, a rack path crossing itself, teeth too
coarse for the curvature): it is refused as interference, not trimmed into a different gear."""

STEP = np.radians(0.05)
"""Driver-angle step of the mate's sweep: the mate's tooth moves ~r·step ≈ 6 µm at the contact
between two cuts, so the scallops it leaves stand well under a nanometre."""


@dataclass(frozen=True)
class Relief:
    """What the mate's sweep took off gear 1."""

    depth_before: float
    """The rack-cut pair's largest penetration depth, found by the proof before the trim, mm."""
    gear1_angle: float
    """Gear 1's angle at that depth, rad."""
    teeth: int
    """Teeth of gear 1 touched by the trim."""
    area: float
    """Material removed, mm²."""
    positions: int
    """Mate positions that cut."""


def relieve(
    pair: PairData,
    fine: ToothedGear,
    gears: tuple[ToothedGear, ToothedGear],
    frames: tuple[ArcFrame, ArcFrame],
    mesh: MeshData,
    *,
    deep: np.ndarray,
) -> tuple[ToothedGear, Relief]:
    """Gear 1's fine cut ``fine`` less the mate (``gears[1]``) placed at every driver angle within
    one proof step of the angles ``deep`` (rad) where the proof found the pair too deep."""
    step = pair.cycle / mesh.positions
    spans = np.concatenate([np.arange(a - step, a + step, STEP) for a in np.unique(deep)])
    phi1 = np.unique(np.round(spans / STEP)) * STEP
    _, placed = placing(pair, gears, frames, phi1)(0.0)
    body = shapely.Polygon(fine.outline.outer)
    shapely.prepare(body)
    trimmed = body.difference(shapely.union_all(placed[shapely.intersects(body, placed)]))
    if trimmed.geom_type == "MultiPolygon":  # a crumb cut loose from a tip: gone with the trim
        trimmed = max(trimmed.geoms, key=lambda g: g.area)
    ring = np.asarray(shapely.geometry.polygon.orient(trimmed, 1.0).exterior.coords)[:-1]
    cut = body.difference(trimmed)
    x, y = np.asarray(shapely.get_coordinates(shapely.centroid(shapely.get_parts(cut)))).T
    s = frames[0].arc(np.arctan2(y, x) % (2 * np.pi))
    touched = np.unique(np.round((s - fine.phase) / fine.rack.pitch - 0.5).astype(int) % fine.teeth)
    relieved = replace(fine, outline=Outline((ring,)), space_root=nearest(fine.outline.outer[fine.space_root], ring)[0])
    return relieved, Relief(float(mesh.max_depth), mesh.depth_at[0], len(touched), float(cut.area), len(phi1))
