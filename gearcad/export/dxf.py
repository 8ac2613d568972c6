"""DXF files for laser cutters and CAD: closed LWPOLYLINEs on named layers, units mm."""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import units

__all__ = ["Layer", "write_dxf", "cross"]

Layer = str

_LAYER_COLOURS = {"CUT": 1, "MARK": 5, "PITCH": 3}


def cross(center, size: float) -> list[np.ndarray]:
    """Two short open strokes marking a pivot: list of (2, 2) float, mm."""
    x, y = center
    return [np.array([[x - size, y], [x + size, y]]), np.array([[x, y - size], [x, y + size]])]


def write_dxf(path: Path, closed: dict[Layer, list[np.ndarray]], open_: dict[Layer, list[np.ndarray]] = None) -> int:
    """Write closed rings and open strokes by layer; return the number of vertices written.

    The file is R2010, $INSUNITS = mm, and its header carries no creation time or random id, so
    the same geometry always gives the same bytes.
    """
    with _reproducible():
        return _write(path, closed, open_ or {})


def _write(path, closed, open_) -> int:
    doc = ezdxf.new("R2010", setup=False)
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    for name in sorted({*closed, *open_}):
        doc.layers.add(name, color=_LAYER_COLOURS.get(name, 7))
    msp = doc.modelspace()
    count = 0
    for layer, rings in closed.items():
        for ring in rings:
            msp.add_lwpolyline(
                np.asarray(ring, dtype=float).tolist(), format="xy", close=True, dxfattribs={"layer": layer}
            )
            count += len(ring)
    for layer, strokes in open_.items():
        for stroke in strokes:
            msp.add_lwpolyline(
                np.asarray(stroke, dtype=float).tolist(), format="xy", close=False, dxfattribs={"layer": layer}
            )
            count += len(stroke)
    doc.saveas(path)
    return count


@contextmanager
def _reproducible():
    """ezdxf's fixed dates, ids and markers: the same drawing always gives the same bytes."""
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before
