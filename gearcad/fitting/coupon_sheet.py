"""Where a coupon's labels go: a box that fits inside a piece (:func:`fit_box`), and a tab below
a sector's hub where its arm is too short for its label (:func:`with_tab`)."""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely import affinity

__all__ = ["LABEL_CLEAR_MM", "LABEL_CHAR_MM", "fit_box", "with_tab"]

LABEL_CLEAR_MM = 0.8
"""An engraved label is kept this far inside its piece and off the hub."""
LABEL_CHAR_MM = 1.2
"""A label's letters (1.5 mm tall) are taken as at most this wide per 1 mm of height, spaces and
signs included, when deciding whether a sector's arm holds its label or it gets a tab."""


def fit_box(region, width: float, height: float) -> tuple[float, float, float] | None:
    """Where a ``width`` × ``height`` box (mm) lies inside ``region``: its centre and its angle
    (0: along x; 90: along y), the first row found of the region shrunk by half the height whose
    longest run takes the width, checked by containment; None where none does."""
    pieces = list(getattr(region, "geoms", [region]))
    region = max(pieces, key=lambda g: g.area) if pieces else region
    if region.is_empty:
        return None
    for angle in (0.0, 90.0):
        turned = affinity.rotate(region, -angle, origin=(0, 0))
        room = turned.buffer(-height / 2)
        if room.is_empty:
            continue
        x0, y0, x1, y1 = room.bounds
        rows = np.linspace(y0, y1, 24)[1:-1]
        lines = shapely.intersection(shapely.linestrings([[[x0 - 1, y], [x1 + 1, y]] for y in rows]), room)
        best = None
        for y, line in zip(rows, lines):
            for seg in getattr(line, "geoms", [line]):
                if seg.is_empty or seg.geom_type != "LineString" or seg.length < width:
                    continue
                mid = (seg.coords[0][0] + seg.coords[-1][0]) / 2
                box = shapely.box(mid - width / 2, y - height / 2, mid + width / 2, y + height / 2)
                if turned.contains(box) and (best is None or seg.length > best[0]):
                    best = (seg.length, mid, y)
        if best is not None:
            x, y = best[1:]
            c, s_ = math.cos(math.radians(angle)), math.sin(math.radians(angle))
            return x * c - y * s_, x * s_ + y * c, angle
    return None


def with_tab(sector: shapely.Polygon, hub: float, hole: float, label: str) -> shapely.Polygon:
    """``sector`` as it is where its arm holds ``label`` (1.5 mm letters), else with a tab below its
    hub, away from its teeth, long enough for it."""
    width = LABEL_CHAR_MM * 1.5 * len(label)
    arm = sector.buffer(-LABEL_CLEAR_MM).difference(shapely.Point(0, 0).buffer(hub + LABEL_CLEAR_MM))
    if fit_box(arm, width, 1.6) is not None:
        return sector
    side = max(2 * hub, 1.6 + 2 * LABEL_CLEAR_MM + 1.0)
    end = hub + 2 * LABEL_CLEAR_MM + width + 0.5
    tab = shapely.box(-side / 2, -end, side / 2, -(hole / 2 + 0.5))
    return shapely.geometry.polygon.orient(shapely.union(sector, tab), 1.0)
