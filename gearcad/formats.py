"""The output formats: one entry per format, read by the profiles (which names a profile may
ask for in ``output.formats``) and by the writing loop (which writer makes which files).

A format's writer is named, not imported (``"module:function"`` under :mod:`gearcad.export`), so
that its file library is loaded only when a profile asks for it.  Adding a format is its writer
module plus one entry below.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["Format", "TABLE", "WHOLES", "FORMATS", "DEFAULT_FORMATS", "DXF_FLAVOURS", "by_name"]


@dataclass(frozen=True)
class Format:
    """One output format.

    Every writer has one signature, ``writer(design, folder, made) -> {file name: entry}``: it
    writes all the format's files of the design into ``folder`` and returns their entries in the
    report (counts: vertices, triangles, …).  ``takes`` is what it reads from ``made``
    (``export.pieces.Made``, made once for every format): ``"drawing"`` (the cut and mark paths
    of the parts as placed, ``export.drawing.Drawing``), ``"solid"`` (the parts as solids,
    ``export.mesh.SolidItem``), or ``"design"`` (nothing: it makes its solids itself from the
    design — STEP: exact B-rep from the arc-fitted rings).  Every part is written to
    ``<part>.<extension>``; ``wholes`` are the files over all parts it also writes ("assembly":
    as assembled, "sheet": laid flat on output.sheet, "plate": on output.bed, one file per bed:
    ``plate``, ``plate-2``, …).
    """

    name: str
    extension: str
    takes: str
    writer: str
    wholes: tuple[str, ...] = ()
    flavours: tuple[str, ...] = ()
    """The ways it may be written (``output.dxf`` for DXF), the default first."""
    default: bool = True
    """Written when a profile names no formats."""
    exact: bool = False
    """Its writer needs each part's rings as cut without the kerf (``Design.made``: an exact solid)."""

    def whole_of(self, stem: str) -> str | None:
        """The whole a file of this format named ``stem`` holds (a plate's files: ``plate``,
        ``plate-2``, …), or None for a part's own file."""
        return next((w for w in self.wholes if stem == w or re.fullmatch(rf"{w}-[0-9]+", stem)), None)


WHOLES: dict[str, str] = {
    "assembly": "assembly: parts in place (checks the fit; not for cutting or printing)",
    "sheet": "cutting sheet: every part laid out",
    "plate": "print plate: parts laid out on the bed",
}
"""What each whole a format may write is, in the page's words."""


TABLE: tuple[Format, ...] = (
    Format(
        "dxf", "dxf", "drawing", "files:write_dxf", ("assembly", "sheet"), ("polyline", "lines-arcs", "polyline-flat")
    ),
    Format("svg", "svg", "drawing", "files:write_svg", ("assembly", "sheet")),
    Format("stl", "stl", "solid", "files:write_stl"),
    Format("3mf", "3mf", "solid", "files:write_3mf", ("assembly", "plate")),
    # asked for, not by default: OpenCASCADE takes about a second to load
    Format("step", "step", "design", "step:write_step_files", ("assembly",), default=False, exact=True),
)

FORMATS: tuple[str, ...] = tuple(f.name for f in TABLE)
"""The formats ``output.formats`` may name."""
DEFAULT_FORMATS: tuple[str, ...] = tuple(f.name for f in TABLE if f.default)
"""What a profile gets without asking."""
DXF_FLAVOURS: tuple[str, ...] = next(f.flavours for f in TABLE if f.name == "dxf")


def by_name(name: str) -> Format:
    return next(f for f in TABLE if f.name == name)
