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
    boxes = np.array([ring_bounds(item) for item in items])
    return (float(boxes[:, 0].min()), float(boxes[:, 1].min()), float(boxes[:, 2].max()), float(boxes[:, 3].max()))
