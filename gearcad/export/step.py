"""STEP files: every part as one exact named solid in mm, and the assembly of them.

A straight part without a chamfer is written as text (``export/step_prism.py``: its arc-fitted
cut rings extruded, planes and cylinders); the other solids are built in ``export/step_brep.py``
(a chamfered straight part's cones, a twisted part fitted through the 3MF's sections) and written
by OpenCASCADE (OCP), imported only for them.  ``assembly.step`` is made of the parts' files
(``export/step_text.py``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from ..mechanisms import Design
from .step_brep import (
    StepSolid,
    flank_section,
    kinked,
    ring_area,
    runs_of,
    straight_solid,
    twisted_solid,
    volume,
)
from .step_prism import prism_text
from .step_stacked import mirrored_ring, stacked_solid
from .step_text import assemble, compact

__all__ = [
    "write_step_files",
    "write_part_step",
    "write_step",
    "face_counts",
    "volume",
    "STEP_TIMESTAMP",
]

STEP_TIMESTAMP = "2000-01-01T00:00:00"
"""The FILE_NAME time stamp of every STEP file: fixed (ISO 8601, as the standard asks), so that
files are byte-identical from build to build (as ezdxf's fixed dates in the DXF)."""


def face_counts(shape) -> dict[str, int]:
    """The shape's faces by surface type: {"plane": …, "cylinder": …, "cone": …, "bspline": …}."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    names = {
        GeomAbs_Plane: "plane",
        GeomAbs_Cylinder: "cylinder",
        GeomAbs_Cone: "cone",
        GeomAbs_BSplineSurface: "bspline",
    }
    counts: dict[str, int] = {}
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        kind = names.get(BRepAdaptor_Surface(TopoDS.Face(explorer.Current())).GetType(), "other")
        counts[kind] = counts.get(kind, 0) + 1
        explorer.Next()
    return counts


def _document():
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("gearcad"))
    return doc, XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())


def _named(label, name: str) -> None:
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name

    TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))


def _write(path: Path, doc) -> None:
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.Message import Message, Message_Gravity
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller

    STEPControl_Controller.Init_s()  # its defaults first, then ours
    for printer in Message.DefaultMessenger_s().Printers():  # its transfer statistics, on stdout
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)  # no 2-D curves on faces: a third of the size
    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise RuntimeError(f"STEP: OpenCASCADE could not write {path.name}")
    _fixed_header(writer.ChangeWriter().Model(), path.stem)
    if writer.Write(str(path)) != IFSelect_RetDone:  # it says no more: a full disk, a folder it may not write
        why = "OpenCASCADE could not write it: a full disk, or a folder it may not write"
        raise OSError(0, why, str(path))
    path.write_text(compact(path.read_text(encoding="latin-1")), encoding="latin-1", newline="\n")


def _fixed_header(model, name: str) -> None:
    """The FILE_NAME entity without the clock (OpenCASCADE stamps the time of writing): the
    same design gives the same bytes, as every other file gearcad writes."""
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.TCollection import TCollection_HAsciiString

    header = APIHeaderSection_MakeHeader(model)
    header.SetName(TCollection_HAsciiString(name))
    header.SetTimeStamp(TCollection_HAsciiString(STEP_TIMESTAMP))
    header.SetAuthorValue(1, TCollection_HAsciiString("gearcad"))
    header.SetOrganizationValue(1, TCollection_HAsciiString(""))
    header.SetOriginatingSystem(TCollection_HAsciiString("gearcad"))


def write_step(path: Path, solid: StepSolid) -> dict:
    """One part as one named solid in mm; returns its faces by type and its volume (mm³)."""
    doc, tool = _document()
    _named(tool.AddShape(solid.shape, False), solid.name)
    _write(path, doc)
    measured = volume(solid.shape) if solid.volume is None else solid.volume
    return {"faces": face_counts(solid.shape), "volume": measured}


def _solid(design: Design, part, rings) -> tuple[StepSolid, dict]:
    """The part's solid and what its files entry adds (the twisted parts' section deviation)."""
    out = design.params.output
    twisted = design.sections.get(part.name)
    if twisted is None:
        return straight_solid(rings, out.thickness, name=part.name, chamfer=out.chamfer), {}
    breaks = (out.thickness / 2,) if twisted.hand.startswith("herringbone") else ()
    solid = twisted_solid(
        twisted.heights,
        twisted.rings,
        rings[1:],
        name=part.name,
        tolerance=out.tolerance,
        chamfer=out.chamfer,
        breaks=breaks,
    )
    # halfway up the widest interval the flank is read off its B-spline faces and measured
    # against the section finely cut there (the twist between sections is largest there)
    mid = flank_section(solid.shape, twisted.mid_height)
    deviation = shapely.hausdorff_distance(shapely.LinearRing(mid), shapely.LinearRing(twisted.mid_ring))
    return solid, {
        "sections": len(twisted.heights),
        "section_deviation": twisted.deviation,
        "mid_height": twisted.mid_height,
        "mid_deviation": float(deviation),
    }


def write_part_step(design: Design, name: str, folder: Path) -> tuple[StepSolid | None, dict]:
    """The part ``name``'s ``<name>.step`` into ``folder``: its solid and its files entry.  A
    straight part without a chamfer is written as text (``export/step_prism.py``: no OpenCASCADE
    loaded, its solid None), any other through OpenCASCADE."""
    part = design.part(name)
    rings = design.made_rings(name)  # the part itself: no kerf
    out = design.params.output
    path = folder / f"{name}.step"
    if name in design.bands:  # two stacked bands, the upper the lower turned over: joined unchamfered
        upper = [mirrored_ring(r, design.bands[name]) for r in rings]
        solid = stacked_solid(rings, upper, out.thickness, name=name)
        counts = write_step(path, solid)
        entry = {"bytes": path.stat().st_size, "kind": "step", "part": name, **counts, "bands": 2}
        return solid, {**entry, "chamfer": 0.0} if out.chamfer else entry
    if name not in design.sections and (out.chamfer == 0 or any(kinked(r) for r in rings)):
        path.write_text(prism_text(name, rings, out.thickness, STEP_TIMESTAMP), encoding="latin-1", newline="\n")
        runs = [run[0] for ring in rings for run in runs_of(ring)]
        faces = {"cylinder": runs.count("arc"), "plane": runs.count("line") + 2}
        entry = {
            "bytes": path.stat().st_size,
            "kind": "step",
            "part": name,
            "faces": {k: v for k, v in faces.items() if v},
            "volume": out.thickness * sum(ring_area(r) for r in rings),
        }
        # OpenCASCADE cannot chamfer an arc fit's slightly kinked joints (a noncircular gear's
        # teeth): such a part is its exact unchamfered solid, which its files entry says
        return None, {**entry, "chamfer": 0.0} if out.chamfer else entry
    solid, extra = _solid(design, part, rings)
    counts = write_step(path, solid)
    return solid, {"bytes": path.stat().st_size, "kind": "step", "part": name, **counts, **extra}


def _same(design: Design, part) -> bytes | None:
    """What a straight part's solid is made of (its kerf-less rings, the thickness, the chamfer)
    as bytes: two parts alike (a self-conjugate pair's gears) make the same solid; None for a
    twisted part."""
    if part.name in design.sections:
        return None
    out = design.params.output
    band = [design.bands[part.name]] if part.name in design.bands else []
    rings = design.made_rings(part.name)
    data = [np.asarray(r.vertices, dtype=float).tobytes() + np.asarray(r.bulges, dtype=float).tobytes() for r in rings]
    return b"|".join([*data, np.array([out.thickness, out.chamfer, *band]).tobytes()])


def write_step_files(design: Design, folder: Path, made: object = None) -> dict[str, dict]:
    """Every part's ``<name>.step`` and ``assembly.step`` (parts placed as in assembly.3mf) into
    ``folder``; returns their files entries (faces by type, volume in mm³).  A part alike an
    earlier one (the same solid) is that one's file with its own name: the bytes OpenCASCADE
    would write, without transferring the solid again.  The assembly is made of the parts' files
    as written (``step_text.assemble``): no solid is transferred twice."""
    files: dict[str, dict] = {}
    texts: dict[str, str] = {}
    written: dict[bytes, str] = {}
    for part in design.parts():
        key, path = _same(design, part), folder / f"{part.name}.step"
        first = written.get(key) if key is not None else None
        if first is not None:
            text = (folder / f"{first}.step").read_bytes()
            old, new = f"'{first}'".encode(), f"'{part.name}'".encode()
            if text.count(old) == 3 and new not in text:  # FILE_NAME's and PRODUCT's names only
                path.write_bytes(text.replace(old, new))
                entry = files[f"{first}.step"]
                files[path.name] = {**entry, "part": part.name, "bytes": path.stat().st_size}
                texts[part.name] = path.read_text(encoding="latin-1")
                continue
        _, files[path.name] = write_part_step(design, part.name, folder)
        texts[part.name] = path.read_text(encoding="latin-1")
        if key is not None:
            written.setdefault(key, part.name)
    path = folder / "assembly.step"
    placements = [(p.part, float(p.angle), float(p.offset[0]), float(p.offset[1])) for p in design.placements]
    path.write_text(assemble(texts, placements), encoding="latin-1", newline="\n")
    count = len(placements)
    files[path.name] = {"bytes": path.stat().st_size, "kind": "step", "part": "assembly", "components": count}
    return files
