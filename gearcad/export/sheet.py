"""The cutting sheet as a drawing: every part laid out flat (``design.sheet``, made with the
design), each engraved with its name so that parts that look alike (the two gears of a pair of
centre ellipses) are told apart once cut."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import shapely
from shapely.ops import polylabel

from ..mechanisms import Design
from .drawing import Drawing, assembly_drawing

__all__ = ["NAME_HEIGHT_MM", "sheet_drawing", "name_strokes"]

NAME_HEIGHT_MM = (1.5, 5.0)
"""Engraved names are 1.5–5 mm high: as large as the part's free middle takes, else left out."""
_CLEAR_MM = 2.0  # kept free around the pivot's hole and cross and inside the outline (tooth roots)


def name_strokes(name: str, region: shapely.Polygon) -> list[np.ndarray]:
    """``name`` in outline letters ((k, 2) float closed strokes, mm), centred on the point of
    ``region`` farthest from its edges and sized to fit there; [] where no legible size fits."""
    from matplotlib.textpath import TextPath  # only when a sheet is written

    pieces = list(getattr(region, "geoms", [region]))
    region = max(pieces, key=lambda g: g.area) if pieces else region
    if region.is_empty or region.geom_type != "Polygon":
        return []
    centre = polylabel(region, tolerance=0.05)
    room = min(float(ring.distance(centre)) for ring in (region.exterior, *region.interiors))
    glyphs = TextPath((0.0, 0.0), name, size=1.0)
    extents = glyphs.get_extents()
    x0, y0, x1, y1 = extents.x0, extents.y0, extents.x1, extents.y1
    half_diagonal = float(np.hypot(x1 - x0, y1 - y0)) / 2
    height = min(NAME_HEIGHT_MM[1], 0.9 * room / half_diagonal) if half_diagonal > 0 else 0.0
    if height < NAME_HEIGHT_MM[0]:
        return []
    shift = np.array([centre.x, centre.y]) - height * np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    return [np.vstack([p, p[:1]]) * height + shift for p in glyphs.to_polygons(closed_only=False) if len(p) >= 3]


def sheet_drawing(design: Design) -> Drawing:
    """The parts' cut rings (kerf applied) and marks, placed as ``design.sheet`` lays them out,
    and each part's name engraved (mark layer) in its free middle."""
    drawing = assembly_drawing(replace(design, placements=design.sheet), cut=True)
    parts = {p.name: p for p in design.parts()}
    mark = design.params.output.mark_layer
    names = []
    for placement in design.sheet:
        part = parts[placement.part]
        body = shapely.Polygon(part.outline.polygon(placement.angle, placement.offset).exterior).buffer(-_CLEAR_MM)
        keep_off = max(part.pivot_mark, part.pivot_diameter / 2) + _CLEAR_MM
        names += name_strokes(part.name, body.difference(shapely.Point(placement.offset).buffer(keep_off)))
    return replace(drawing, strokes={**drawing.strokes, mark: [*drawing.strokes.get(mark, []), *names]})
