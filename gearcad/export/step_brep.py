"""The B-rep of a part for STEP (OpenCASCADE through OCP): exact extrusions and ruled lofts.

A straight part is its cut rings — lines and circular arcs within the tolerance of the exact
outline (``geometry/arcfit.py``), the same paths the DXF writes — extruded: one plane per line
and one cylinder per arc (consecutive arcs of one circle, and collinear lines, are one face).
A chamfer is cut at 45° by OpenCASCADE's chamfer on every top and bottom edge: a plane beside a
line, a cone beside an arc.  A twisted part (helical, herringbone) is lofted through the
transverse sections the 3MF uses, joined by ruled B-spline faces with vertex j of each section
on the same material line (``teeth/correspond.py``), its bores extruded straight through.

OCP is imported inside the functions only (``export/step.py`` is its one caller): it takes
about a second to load.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..geometry.arcfit import ArcRing
from ..geometry.inset import inset_ring

__all__ = ["StepSolid", "straight_solid", "twisted_solid", "ruled_section", "volume"]

_MERGE = 1e-9
"""Two arcs are one circle, two lines one line, where centres, radii and offsets agree this
closely (mm): only runs that are the same curve by construction (a circle's quarter arcs)."""


@dataclass(frozen=True)
class StepSolid:
    """A part's B-rep (an OCP ``TopoDS_Shape``) and its name; ``volume`` (mm³) where it is known
    in closed form (a twisted part's: OpenCASCADE integrates its ruled faces in seconds)."""

    name: str
    shape: object
    volume: float | None = None


def _segments(ring: ArcRing) -> list[tuple]:
    """The ring as runs: ("line", a, b) or ("arc", a, b, centre, radius, sweep), consecutive arcs
    of one circle and collinear lines merged (sweep in rad, positive counter-clockwise)."""
    v = np.asarray(ring.vertices, dtype=float)
    bulges = np.asarray(ring.bulges, dtype=float)
    out: list[tuple] = []
    for k in range(len(v)):
        a, b, bulge = v[k], v[(k + 1) % len(v)], float(bulges[k])
        if bulge == 0:
            seg = ("line", a, b)
        else:
            chord = b - a
            length = float(np.hypot(*chord))
            sweep = 4 * np.arctan(bulge)
            radius = length / (2 * abs(np.sin(sweep / 2)))
            left = np.array([-chord[1], chord[0]]) / length
            centre = (a + b) / 2 + left * radius * np.cos(sweep / 2) * np.sign(sweep)
            seg = ("arc", a, b, centre, radius, sweep)
        if out and _same_curve(out[-1], seg):
            out[-1] = _joined(out[-1], seg)
        else:
            out.append(seg)
    if len(out) > 1 and _same_curve(out[-1], out[0]):
        out[-1] = _joined(out[-1], out.pop(0))
    return out


def _joined(s: tuple, t: tuple) -> tuple:
    if s[0] == "line":
        return ("line", s[1], t[2])
    return ("arc", s[1], t[2], s[3], s[4], s[5] + t[5])


def _same_curve(s: tuple, t: tuple) -> bool:
    if s[0] != t[0]:
        return False
    if s[0] == "arc":
        return s[5] * t[5] > 0 and abs(s[4] - t[4]) <= _MERGE and float(np.hypot(*(s[3] - t[3]))) <= _MERGE
    d1, d2 = s[2] - s[1], t[2] - t[1]
    cross = d1[0] * (t[2] - s[1])[1] - d1[1] * (t[2] - s[1])[0]
    return float(np.dot(d1, d2)) > 0 and abs(cross) / float(np.hypot(*d1)) <= _MERGE


def _wire(ring: ArcRing, z: float = 0.0):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.GC import GC_MakeArcOfCircle
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt

    def point(p):
        return gp_Pnt(float(p[0]), float(p[1]), z)

    maker = BRepBuilderAPI_MakeWire()
    for seg in _segments(ring):
        if seg[0] == "line":
            edge = BRepBuilderAPI_MakeEdge(point(seg[1]), point(seg[2])).Edge()
        elif abs(abs(seg[5]) - 2 * np.pi) <= 1e-9:  # the whole circle, one edge
            _, a, _, centre, radius, sweep = seg
            axis = gp_Dir(0, 0, 1 if sweep > 0 else -1)
            edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(point(centre), axis), float(radius))).Edge()
        else:  # through its ends and its middle: the direction follows
            _, a, b, centre, radius, sweep = seg
            c, s = np.cos(sweep / 2), np.sin(sweep / 2)
            r = a - centre
            mid = centre + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]])
            edge = BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(point(a), point(mid), point(b)).Value()).Edge()
        maker.Add(edge)
    if not maker.IsDone():
        raise RuntimeError("STEP: a cut ring does not close into a wire")
    return maker.Wire()


def _face(rings: Sequence[ArcRing], z: float = 0.0):
    """The planar face at height ``z`` bounded by the outer ring and its holes."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace

    maker = BRepBuilderAPI_MakeFace(_wire(rings[0], z), True)
    for hole in rings[1:]:
        maker.Add(_wire(hole, z))
    return maker.Face()


def _chamfered(shape, chamfer: float, z_levels: Sequence[float], *, lines_and_arcs: bool = False):
    """``shape`` with every edge lying in a plane z = level cut at 45° by ``chamfer`` mm (only
    its lines and arcs with ``lines_and_arcs``: a loft's outer edges are inset already)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepFilletAPI import BRepFilletAPI_MakeChamfer
    from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Line
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    maker = BRepFilletAPI_MakeChamfer(shape)
    explorer = TopExp_Explorer(shape, TopAbs_EDGE)
    while explorer.More():
        edge = TopoDS.Edge(explorer.Current())
        curve = BRepAdaptor_Curve(edge)
        ends = (curve.Value(curve.FirstParameter()).Z(), curve.Value(curve.LastParameter()).Z())
        level = any(abs(ends[0] - z) < 1e-9 and abs(ends[1] - z) < 1e-9 for z in z_levels)
        if level and (not lines_and_arcs or curve.GetType() in (GeomAbs_Line, GeomAbs_Circle)):
            maker.Add(chamfer, edge)
        explorer.Next()
    maker.Build()
    if not maker.IsDone():
        raise RuntimeError("STEP: OpenCASCADE could not chamfer the part")
    return maker.Shape()


def straight_solid(rings: Sequence[ArcRing], thickness: float, *, name: str, chamfer: float = 0.0) -> StepSolid:
    """The part's cut rings (outer counter-clockwise, holes clockwise; lines and arcs, mm)
    extruded from z = 0 to ``thickness``, the top and bottom edges chamfered by ``chamfer``."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec

    shape = BRepPrimAPI_MakePrism(_face(rings), gp_Vec(0.0, 0.0, float(thickness))).Shape()
    if chamfer > 0:  # the volume of OpenCASCADE's corners: integrated
        return StepSolid(name, _chamfered(shape, chamfer, (0.0, thickness)))
    return StepSolid(name, shape, thickness * sum(_area(r) for r in rings))


def _area(ring: ArcRing) -> float:
    """The signed area inside a ring of lines and arcs (mm²): its chords' shoelace area and each
    arc's circular segment r²(θ − sin θ)/2, θ the signed sweep."""
    area = 0.0
    for seg in _segments(ring):
        a, b = seg[1], seg[2]
        area += 0.5 * float(a[0] * b[1] - a[1] * b[0])
        if seg[0] == "arc":
            area += 0.5 * seg[4] ** 2 * (seg[5] - np.sin(seg[5]))
    return area


def _grid_surface(rings: np.ndarray, z: np.ndarray):
    """The ruled surface through sections ``rings`` ((k, m, 2)) at heights ``z`` ((k,)): degree 1
    both ways, u = j at vertex j (closed: u = m is vertex 0 again), v = z; vertex j of one
    section joined straight to vertex j of the next, as the 3MF's loft joins them."""
    from OCP.collections import Array1_double, Array1_int, Array2_gp_Pnt
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    k, m = rings.shape[:2]
    poles = Array2_gp_Pnt(1, m + 1, 1, k)
    for i in range(k):
        level = float(z[i])
        for j, (x, y) in enumerate(np.vstack([rings[i], rings[i, :1]]).tolist()):
            poles.SetValue(j + 1, i + 1, gp_Pnt(x, y, level))

    def knots(values):
        knot, mult = Array1_double(1, len(values)), Array1_int(1, len(values))
        for n, value in enumerate(values):
            knot.SetValue(n + 1, float(value))
            mult.SetValue(n + 1, 2 if n in (0, len(values) - 1) else 1)
        return knot, mult

    uk, um = knots(range(m + 1))
    vk, vm = knots(z)
    return Geom_BSplineSurface(poles, uk, vk, um, vm, 1, 1)


def _bands(z: np.ndarray, breaks: Sequence[float]) -> list[slice]:
    """The section ranges between consecutive breaks (each at least two sections)."""
    cuts = sorted({0, len(z) - 1, *(int(np.argmin(np.abs(z - b))) for b in breaks)})
    return [slice(a, b + 1) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]


def twisted_solid(
    heights: np.ndarray,
    rings: np.ndarray,
    holes: Sequence[ArcRing],
    *,
    name: str,
    chamfer: float = 0.0,
    breaks: Sequence[float] = (),
) -> StepSolid:
    """The solid through the sections ``rings[k]`` ((n, m, 2), counter-clockwise, vertex j of
    every section the same tooth point) at ``heights[k]``, ruled from section to section as the
    3MF's loft is (the chamfer's sections inset alike): one B-spline face per band between the
    chamfer's heights and the ``breaks`` (a herringbone's mid-height); straight ``holes``
    (clockwise cut rings) through it, their ends chamfered."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
    from OCP.BRepLib import BRepLib
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec
    from OCP.TopoDS import TopoDS

    z = np.asarray(heights, dtype=float)
    rings = np.asarray(rings, dtype=float)
    bottom, top = float(z[0]), float(z[-1])
    levels = list(breaks)
    if chamfer > 0:
        depth = np.maximum(0.0, np.maximum(chamfer - (z - bottom), chamfer - (top - z)))
        rings = np.stack([inset_ring(r, d) if d > 0 else r for r, d in zip(rings, depth)])
        levels += [bottom + chamfer, top - chamfer]
    sewing = BRepBuilderAPI_Sewing(1e-6)
    for band in _bands(z, levels):
        surface = _grid_surface(rings[band], z[band])
        sewing.Add(BRepBuilderAPI_MakeFace(surface, 0.0, float(rings.shape[1]), z[band][0], z[band][-1], 1e-7).Face())
    for level in (0, len(z) - 1):
        edge = _ring_edge(rings[level], float(z[level]))
        face = BRepBuilderAPI_MakeFace(_wire_of(edge), True)
        for hole in holes:
            face.Add(_wire(hole, float(z[level])))
        sewing.Add(face.Face())
    for hole in holes:
        sewing.Add(BRepPrimAPI_MakePrism(_wire(hole, bottom), gp_Vec(0.0, 0.0, top - bottom)).Shape())
    sewing.Perform()
    solid = BRepBuilderAPI_MakeSolid(TopoDS.Shell(sewing.SewedShape())).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    shape = solid
    if chamfer > 0 and holes:
        shape = _chamfered(shape, chamfer, (bottom, top), lines_and_arcs=True)
    return StepSolid(name, shape, _ruled_volume(rings, z) - _voids(holes, top - bottom, chamfer))


def _ruled_volume(rings: np.ndarray, z: np.ndarray) -> float:
    """The volume inside the ruled sections (mm³), exact: between two sections every vertex
    moves linearly with z, so the section's area is quadratic in z and Simpson's rule is exact."""
    x, y = rings[..., 0], rings[..., 1]

    def areas(x, y):
        return 0.5 * np.sum(x * np.roll(y, -1, axis=-1) - y * np.roll(x, -1, axis=-1), axis=-1)

    mid_x, mid_y = (x[1:] + x[:-1]) / 2, (y[1:] + y[:-1]) / 2
    ends = areas(x, y)
    return float(np.sum(np.diff(z) / 6 * (ends[:-1] + 4 * areas(mid_x, mid_y) + ends[1:])))


def _voids(holes: Sequence[ArcRing], thickness: float, chamfer: float) -> float:
    """The volume the straight ``holes`` take out, their chamfers included (mm³): a disc around
    them with and without them (planes, cylinders and cones, which OpenCASCADE integrates exactly)."""
    if not holes:
        return 0.0
    reach = 2 * max(float(np.max(np.hypot(*np.asarray(h.vertices, dtype=float).T))) for h in holes) + 1
    disc = ArcRing(reach * np.array([[1.0, 0], [0, 1], [-1, 0], [0, -1]]), np.full(4, np.tan(np.pi / 8)))
    whole = straight_solid([disc], thickness, name="disc", chamfer=chamfer).shape
    holed = straight_solid([disc, *holes], thickness, name="disc", chamfer=chamfer).shape
    return volume(whole) - volume(holed)


def _ring_edge(ring: np.ndarray, z: float):
    """A closed ring (m, 2) as one degree-1 B-spline edge, u = j at vertex j (the sections'
    surfaces' edge at that height)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt

    m = len(ring)
    poles = Array1_gp_Pnt(1, m + 1)
    for j, (x, y) in enumerate(np.vstack([ring, ring[:1]]).tolist()):
        poles.SetValue(j + 1, gp_Pnt(x, y, z))
    knots, mults = Array1_double(1, m + 1), Array1_int(1, m + 1)
    for j in range(m + 1):
        knots.SetValue(j + 1, float(j))
        mults.SetValue(j + 1, 2 if j in (0, m) else 1)
    return BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(poles, knots, mults, 1)).Edge()


def _wire_of(edge):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeWire

    return BRepBuilderAPI_MakeWire(edge).Wire()


def volume(shape, *, relative_error: float = 1e-7) -> float:
    """The shape's volume, mm³, integrated over its faces by OpenCASCADE to ``relative_error``
    (adaptive: a ruled face of thousands of spans defeats a fixed Gauss rule, and takes seconds)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, relative_error)
    return float(props.Mass())


def ruled_section(shape, z: float) -> np.ndarray:
    """The twisted flank's section at height ``z`` read off its B-spline faces: (m, 2) mm, the
    surface evaluated at u = j (vertex j of the sections), v = z.  The faces are degree 1 in u,
    so the polyline through these points is the section itself (bilinear between two sections:
    halfway up, the midpoints of the vertical edges — not the 3MF's diagonals)."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        surface = BRep_Tool.Surface_s(TopoDS.Face(explorer.Current()))
        explorer.Next()
        if not hasattr(surface, "NbUPoles"):  # a plane, cylinder or cone: not the flank
            continue
        u0, u1, v0, v1 = surface.Bounds()
        if v0 < z < v1:
            return np.array([(q.X(), q.Y()) for q in (surface.Value(float(u), z) for u in range(int(u0), int(u1)))])
    raise ValueError(f"no ruled face spans z = {z:g} mm")
