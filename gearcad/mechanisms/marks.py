"""The engraved dots that show where a toothed pair's gears meet in the assembly's phase."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..geometry.arcfit import ArcRing
from .parts import Part

__all__ = ["assembly_marks"]


def _dot(centre: np.ndarray, radius: float) -> ArcRing:
    """A small engraved diamond, counter-clockwise: four straight edges, exact in every DXF
    encoding and never split (arcs as small as this would be, for bulge-ignoring readers)."""
    x, y = centre
    return ArcRing(np.array([[x + radius, y], [x, y + radius], [x - radius, y], [x, y - radius]]), np.zeros(4))


def assembly_marks(design, parts: tuple[Part, ...]) -> tuple[Part, ...]:
    """The parts with an engraved dot (a diamond, MARK layer) on each gear of a toothed pair (the
    gear pair's ``marks`` hook; ``design`` its draft or design) where the two
    meet in the assembly's phase: on the line of centres at driver angle 0, two modules inside
    the pitch curve.  Turn the gears so the dots face each other and they mesh as designed."""
    teeth = getattr(design.detail, "teeth", None)
    if teeth is None:
        return parts
    pair, m = design.detail.pitch.pair, teeth.plan.module
    r1 = float(pair.gear1.r(0.0))
    toward = pair.center_distance - r1
    phi2 = float(pair.angle_map(np.array([0.0]))[0])
    spots = (
        np.array([r1 - 2 * m, 0.0]),
        (toward - 2 * m) * np.array([-math.cos(phi2), math.sin(phi2)]),
    )
    out = list(parts)
    for i, spot in enumerate(spots):
        part = out[i]
        hole = part.pivot_diameter / 2
        if np.hypot(*spot) - 0.25 * m > hole + 0.5 * m:  # clear of the bore
            out[i] = replace(part, mark=part.mark + (_dot(spot, 0.25 * m),))
    return tuple(out)
