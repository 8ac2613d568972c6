"""DXF files for laser cutters, CAD and CAM: closed outlines on named layers, units mm.

Three encodings of the same geometry (``[output] dxf``):

* ``polyline`` — one closed LWPOLYLINE per ring, arcs as bulges (laser software, CAD);
* ``lines-arcs`` — the same segments as LINE and ARC entities sharing end points (OpenSCAD
  and importers that ignore bulges);
* ``polyline-flat`` — one closed LWPOLYLINE per ring without bulges, chords within the
  tolerance (the simplest importers).
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import units

from ..geometry.arcfit import ArcRing
from .drawing import Drawing

__all__ = ["FLAVOURS", "write_dxf"]

FLAVOURS = ("polyline", "lines-arcs", "polyline-flat")
_LAYER_COLOURS = {"CUT": 1, "MARK": 5}


@contextmanager
def _reproducible():
    """ezdxf's fixed dates, ids and markers: the same drawing always gives the same bytes."""
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before


def _arc_entity(msp, a, b, bulge, layer):
    """An ARC from a to b with the given bulge (ARCs always run counter-clockwise)."""
    sweep = 4 * math.atan(bulge)
    chord = b - a
    length = float(np.hypot(*chord))
    radius = length / (2 * abs(math.sin(sweep / 2)))
    normal = np.array([-chord[1], chord[0]]) / length
    centre = (a + b) / 2 + normal * radius * math.cos(sweep / 2) * math.copysign(1.0, sweep)
    start, end = (a, b) if sweep > 0 else (b, a)
    msp.add_arc(
        centre.tolist(),
        radius,
        math.degrees(math.atan2(start[1] - centre[1], start[0] - centre[0])),
        math.degrees(math.atan2(end[1] - centre[1], end[0] - centre[0])),
        dxfattribs={"layer": layer},
    )


def write_dxf(path: Path, drawing: Drawing, *, flavour: str = "polyline") -> int:
    """Write the drawing; return the number of vertices (segment end points) written.

    R2010, $INSUNITS = mm, no creation time or random id: the same drawing gives the same bytes.
    """
    if flavour not in FLAVOURS:
        raise ValueError(f"unknown DXF flavour {flavour!r}")
    with _reproducible():
        doc = ezdxf.new("R2010", setup=False)
        doc.units = units.MM
        doc.header["$MEASUREMENT"] = 1
        for name in sorted({*drawing.closed, *drawing.strokes}):
            layer = doc.layers.add(name, color=_LAYER_COLOURS.get(name, 7))
            if name in drawing.descriptions:
                layer.description = drawing.descriptions[name]
        msp = doc.modelspace()
        count = 0
        for layer, rings in drawing.closed.items():
            for ring in rings:
                count += _ring(msp, ring, layer, flavour)
        for layer, strokes in drawing.strokes.items():
            for stroke in strokes:
                if flavour == "lines-arcs":
                    for a, b in zip(stroke[:-1], stroke[1:]):
                        msp.add_line(a.tolist(), b.tolist(), dxfattribs={"layer": layer})
                else:
                    msp.add_lwpolyline(np.asarray(stroke).tolist(), format="xy", dxfattribs={"layer": layer})
                count += len(stroke)
        doc.saveas(path)
    return count


def _ring(msp, ring, layer: str, flavour: str) -> int:
    if isinstance(ring, ArcRing):
        v, bulges = ring.vertices, ring.bulges
    else:
        v, bulges = np.asarray(ring, dtype=float), np.zeros(len(ring))
    if flavour == "lines-arcs":
        n = len(v)
        for k in range(n):
            a, b = v[k], v[(k + 1) % n]
            if bulges[k] == 0:
                msp.add_line(a.tolist(), b.tolist(), dxfattribs={"layer": layer})
            else:
                _arc_entity(msp, a, b, bulges[k], layer)
        return n
    if flavour == "polyline-flat" and np.any(bulges):
        raise ValueError("the flat encoding takes plain rings sampled within the tolerance")
    points = np.column_stack([v, np.zeros(len(v)), np.zeros(len(v)), bulges])
    msp.add_lwpolyline(points.tolist(), format="xyseb", close=True, dxfattribs={"layer": layer})
    return len(v)
