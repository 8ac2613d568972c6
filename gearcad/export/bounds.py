"""Exact bounding boxes of drawings: arcs reach past their end vertices (SVG viewBox, DXF $EXTMIN)."""

from __future__ import annotations

from ..geometry.bounds import ring_bounds, rings_bounds
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
    box = rings_bounds(items)  # arcs reach past their vertices; all items in one pass
    return (float(box[0]), float(box[1]), float(box[2]), float(box[3]))
