"""Parts: a toothed (or pitch) outline with its bore, keyway or D-flat, as one Outline."""

from __future__ import annotations

import math

import numpy as np
import shapely
import shapely.geometry

from .errors import DesignError
from .outline import Outline, arc_steps
from .profiles import BoreParams

__all__ = ["BoreParams", "bore_ring", "circle_ring", "with_bore"]


def circle_ring(radius: float, tolerance: float) -> np.ndarray:
    """Counter-clockwise vertices on a circle whose chords stray at most ``tolerance`` from it."""
    steps = max(16, arc_steps(radius, tolerance))
    t = np.linspace(0.0, 2 * math.pi, steps, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def bore_ring(bore: BoreParams, tolerance: float) -> np.ndarray | None:
    """The bore as a clockwise hole ring (None without a bore)."""
    if bore.diameter <= 0:
        return None
    r = bore.diameter / 2
    hole = shapely.Polygon(circle_ring(r, tolerance))
    if bore.keyway_width > 0 and bore.keyway_depth > 0:
        half = bore.keyway_width / 2
        hole = hole.union(shapely.box(0.0, -half, r + bore.keyway_depth, half))
    if bore.flat > 0:
        hole = hole.intersection(shapely.box(-2 * r, -2 * r, bore.flat, 2 * r))
    ring = shapely.geometry.polygon.orient(hole, -1.0).exterior.coords
    return np.asarray(ring)[:-1]


def with_bore(outer: np.ndarray, bore: BoreParams, tolerance: float, *, part: str, module: float | None) -> Outline:
    """The part's outline: ``outer`` and, if any, the bore hole — which must leave a wall."""
    hole = bore_ring(bore, tolerance)
    if hole is None:
        return Outline((outer,))
    reach = float(np.max(np.hypot(hole[:, 0], hole[:, 1])))
    root = float(np.min(np.hypot(outer[:, 0], outer[:, 1])))
    wall = module if module else 0.0
    if reach + wall >= root:
        raise DesignError(
            f"bore.diameter = {bore.diameter:g}: the bore reaches {reach:.3f} mm from the pivot of {part}, "
            f"whose outline comes within {root:.3f} mm of it; leave at least {wall:.3f} mm of material"
        )
    return Outline((outer, hole))
