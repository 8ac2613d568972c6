"""Exact bounding boxes of drawings: arcs reach past their end vertices (SVG viewBox, DXF $EXTMIN)."""

from __future__ import annotations

import numpy as np

from ..geometry.bounds import ring_bounds
from .drawing import Drawing

__all__ = ["ring_bounds", "drawing_bounds"]


def drawing_bounds(drawing: Drawing) -> tuple[float, float, float, float]:
    """``(xmin, ymin, xmax, ymax)`` of every closed ring and stroke of a drawing, mm.

    Raises
    ------
    ValueError
        If the drawing holds no geometry.
    """
    items = [r for rings in drawing.closed.values() for r in rings]
    items += [s for strokes in drawing.strokes.values() for s in strokes]
    if not items:
        raise ValueError("the drawing is empty: no closed rings and no strokes to bound")
    # arcs reach past their vertices (ring_bounds); plain rings and strokes end at theirs: one
    # array for all of them (a sheet's lettering is hundreds of strokes)
    boxes = [ring_bounds(item) for item in items if getattr(item, "bulges", None) is not None]
    plain = [np.asarray(item, dtype=float) for item in items if getattr(item, "bulges", None) is None]
    if plain:
        points = np.concatenate(plain)
        boxes.append(np.concatenate([points.min(axis=0), points.max(axis=0)]) + 0.0)  # + 0.0: no -0.0
    box = np.array(boxes)
    return (float(box[:, 0].min()), float(box[:, 1].min()), float(box[:, 2].max()), float(box[:, 3].max()))
