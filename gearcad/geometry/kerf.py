"""The cutter's path around a part, and what the cutter leaves of it.

A laser's beam (a router's tool) of width ``w`` follows a path offset ``w/2`` into the waste.
The path's sharp turns are cut as a beam cuts them: around a convex corner of the part the path
is an arc of radius ``w/2`` (the corner stays sharp), into a concave corner of the part (a
hole's corner: a D-flat or a keyway; a sharp tooth root) the two offset edges meet in a mitre
and the beam rounds the corner with its own radius.  What the beam cannot reach is left
standing: at a nominal point ``q`` the material left is ``dist(q, path) − w/2``.  A corner of
90° or more (a keyway's; a D-flat's are 146° for Ø6 at 2.5 mm) keeps at most (√2 − 1)·w/2 at its
apex; more than that is a tooth space or hole the beam fills (or, with a negative offset, a
tooth or wall it cuts away), reported with where it is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from .outline import Outline, arc_steps
from .rings import offset_outline
from .verify import distances

__all__ = ["CORNER", "KerfFault", "kerf_path", "kerf_fault"]

CORNER = math.sqrt(2) - 1
"""Material a beam of radius r leaves at the apex of a 90° inside corner, over r: the most a
rounded corner may keep; a sharper corner or a narrower space is filled, not rounded."""


@dataclass(frozen=True)
class KerfFault:
    """Where a cutter of the given offset spoils a part: ``what`` ("tooth space", "hole",
    "tooth", "wall"), ``left`` mm of nominal material left standing (or cut away), at polar
    angle ``angle_deg`` and radius ``radius`` (mm) about the pivot."""

    what: str
    left: float
    angle_deg: float
    radius: float

    def describe(self, part: str, cutter: str = "beam") -> str:
        verb = "fills" if self.what in ("tooth space", "hole") else "cuts away"
        return (
            f"{part}: the {cutter} {verb} a {self.what} at {self.angle_deg:.1f}° and {self.radius:.2f} mm "
            "from the pivot "
            f"({self.left:.3f} mm of it {'left uncut' if verb == 'fills' else 'lost'})"
        )


def kerf_path(fine: Outline, offset: float, tolerance: float) -> Outline | None:
    """The cutter's path: ``fine`` offset by ``offset`` mm into the waste (negative: into the
    part), or None where that changes the part's topology (a hole closes, the part falls apart)."""
    try:
        return offset_outline(fine, offset, tolerance, what="kerf")
    except DesignError:
        return None


def kerf_fault(fine: Outline, path: Outline | None, offset: float, tolerance: float) -> tuple[KerfFault, ...]:
    """What the cutter spoils, worst place of each ring; empty when it only rounds corners (at
    most :data:`CORNER` · ``|offset|`` of material left, plus twice ``tolerance`` for the
    sampling of both rings).  ``path`` None (the offset changed the topology) always spoils something."""
    reach = abs(offset)
    rings = path.rings if path is not None else _raw_rings(fine, offset, tolerance)
    faults = []
    for index, ring in enumerate(fine.rings):
        d = distances(ring, rings)
        k = int(np.argmax(d))
        left, point = float(d[k]) - reach, ring[k]
        if left <= CORNER * reach + 2 * tolerance:
            continue
        if offset > 0:
            what = "tooth space" if index == 0 else "hole"
        else:
            what = "tooth" if index == 0 else "wall"
        angle = math.degrees(math.atan2(point[1], point[0])) % 360
        faults.append(KerfFault(what, left, angle, float(np.hypot(*point))))
    if path is None and not faults:  # the topology changed within the allowance: say so anyway
        faults.append(KerfFault("hole" if offset > 0 else "tooth", reach, 0.0, 0.0))
    return tuple(faults)


def _raw_rings(fine: Outline, offset: float, tolerance: float) -> list[np.ndarray]:
    """Every ring of the offset whose topology changed (to find where it did)."""
    steps = max(2, arc_steps(abs(offset), tolerance, np.pi / 2))
    shape = shapely.Polygon(fine.rings[0], fine.rings[1:]).buffer(offset, quad_segs=steps)
    polygons = getattr(shape, "geoms", [shape])
    return [np.asarray(r.coords)[:-1] for p in polygons for r in (p.exterior, *p.interiors)] or [fine.rings[0][:1]]
