"""The engraving's POLYLINE entities, their VERTEX entities written as text.

ezdxf makes an entity object for every VERTEX of a POLYLINE and exports each attribute by
attribute: a third of a second for a sheet's 1 700 engraved vertices, two thirds of all the
DXF writing, where the cut path's LWPOLYLINE (one entity, every vertex in it) takes a tenth
of that a vertex.  Here ezdxf makes each POLYLINE with its SEQEND and no vertices, the vertices'
handles are taken from the document's handle seed in the order ezdxf would give them (after
the SEQEND's), and their tags are written as ezdxf writes a 2-D VERTEX (R2000 and later:
``AcDbEntity``, the layer, ``AcDbVertex``, ``AcDb2dVertex``, the location, a bulge unless it is
0, flags 0) and put before their SEQEND in the text ezdxf wrote: the same file, byte for byte,
as ezdxf's own ``add_polyline2d`` with the points (tests/test_exports.py compares the two).
"""

from __future__ import annotations

import io
import re
from collections.abc import Sequence
from pathlib import Path

__all__ = ["Marks"]

_SEQEND = re.compile(r"  0\nSEQEND\n  5\n([0-9A-F]+)\n")


class Marks:
    """The engraved polylines of one document: :meth:`add` each, then :meth:`save` the document."""

    def __init__(self, doc):
        self._doc = doc
        self._vertices: dict[str, str] = {}
        """The VERTEX tags of each POLYLINE, by the handle of its SEQEND."""

    def add(self, msp, rows: Sequence[Sequence[float]], layer: str, *, close: bool = False) -> None:
        """A 2-D POLYLINE on ``layer`` through ``rows`` of (x, y) or (x, y, bulge) floats,
        closed when ``close`` is."""
        polyline = msp.add_polyline2d([], close=close, dxfattribs={"layer": layer})
        head = "  0\nVERTEX\n  5\n"
        tail = f"\n330\n{polyline.dxf.owner}\n100\nAcDbEntity\n  8\n{layer}\n100\nAcDbVertex\n100\nAcDb2dVertex\n"
        next_handle = self._doc.entitydb.next_handle
        text = []
        for row in rows:
            x, y = float(row[0]), float(row[1])
            bulge = float(row[2]) if len(row) > 2 else 0.0
            arc = f" 42\n{bulge}\n" if bulge else ""
            text.append(f"{head}{next_handle()}{tail} 10\n{x}\n 20\n{y}\n 30\n0.0\n{arc} 70\n0\n")
        self._vertices[polyline.seqend.dxf.handle] = "".join(text)

    def save(self, path: Path) -> None:
        """Write the document to ``path`` as ``doc.saveas`` does (its encoding and error
        handler), each polyline's vertices before its SEQEND."""
        stream = io.StringIO()
        self._doc.write(stream)
        vertices = self._vertices
        text = _SEQEND.sub(lambda m: vertices.get(m.group(1), "") + m.group(0), stream.getvalue())
        with open(path, "w", encoding=self._doc.output_encoding, errors="dxfreplace") as fp:
            fp.write(text)
