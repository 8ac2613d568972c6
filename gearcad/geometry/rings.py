"""Rings every part uses: circles sampled from a tolerance, bore holes, offsets by a distance."""

from __future__ import annotations

import math

import numpy as np
import shapely
import shapely.geometry

from ..errors import DesignError
from .outline import Outline, arc_steps

__all__ = ["circle_ring", "bore_ring", "offset_outline"]


def circle_ring(radius: float, tolerance: float) -> np.ndarray:
    """Counter-clockwise vertices on a circle whose chords stray at most ``tolerance`` from it."""
    steps = max(16, arc_steps(radius, tolerance))
    t = np.linspace(0.0, 2 * math.pi, steps, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def bore_ring(
    diameter: float, tolerance: float, *, keyway_width: float = 0.0, keyway_depth: float = 0.0, flat: float = 0.0
) -> np.ndarray | None:
    """The bore as a clockwise hole ring (None for diameter 0): a keyway cut beyond the bore's
    edge at +x, or a D-flat at distance ``flat`` from the centre on the +x side."""
    if diameter <= 0:
        return None
    r = diameter / 2
    hole = shapely.Polygon(circle_ring(r, tolerance))
    if keyway_width > 0 and keyway_depth > 0:
        half = keyway_width / 2
        hole = hole.union(shapely.box(0.0, -half, r + keyway_depth, half))
    if flat > 0:
        hole = hole.intersection(shapely.box(-2 * r, -2 * r, flat, 2 * r))
    ring = shapely.geometry.polygon.orient(hole, -1.0).exterior.coords
    return np.asarray(ring)[:-1]


def offset_outline(outline: Outline, distance: float, tolerance: float, *, what: str) -> Outline:
    """The outline grown (``distance`` > 0) or shrunk (< 0) by a distance, round joins sampled so
    that they stray at most ``tolerance``; raises :class:`DesignError` naming ``what`` when the
    offset changes the part's topology (teeth merge, spaces close, the part falls apart)."""
    if distance == 0:
        return outline
    steps = max(2, arc_steps(abs(distance), tolerance, np.pi / 2))  # shapely counts segments per quarter
    shape = outline.polygon().buffer(distance, join_style="round", quad_segs=steps)
    if shape.geom_type != "Polygon" or shape.is_empty or len(shape.interiors) != len(outline.rings) - 1:
        raise DesignError(f"{what}: the offset outline falls apart or its holes close")
    shape = shapely.geometry.polygon.orient(shape, 1.0)
    rings = [np.asarray(shape.exterior.coords)[:-1]] + [np.asarray(r.coords)[:-1] for r in shape.interiors]
    return Outline(tuple(rings))
