"""Reading STEP files back with OpenCASCADE for the tests (import after
``pytest.importorskip("OCP")``): the shape, its sub-shapes of a kind, its faces counted by
surface type."""

from __future__ import annotations

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Plane
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

SURFACES = {
    GeomAbs_Plane: "plane",
    GeomAbs_Cylinder: "cylinder",
    GeomAbs_Cone: "cone",
    GeomAbs_BSplineSurface: "bspline",
}
"""OpenCASCADE's surface types by the names the report's ``faces`` uses."""


def read_step(path):
    """The one shape of a STEP file, as OpenCASCADE's STEP reader transfers it."""
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone, path
    reader.TransferRoots()
    return reader.OneShape()


def every(shape, kind) -> list:
    """Every sub-shape of ``shape`` of the topological ``kind`` (TopAbs_…)."""
    found, explorer = [], TopExp_Explorer(shape, kind)
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    return found


def face_counts(shape) -> dict[str, int]:
    """The shape's faces counted by surface type ("plane", "cylinder", …, "other")."""
    counts: dict[str, int] = {}
    for face in every(shape, TopAbs_FACE):
        kind = SURFACES.get(BRepAdaptor_Surface(TopoDS.Face(face)).GetType(), "other")
        counts[kind] = counts.get(kind, 0) + 1
    return counts
