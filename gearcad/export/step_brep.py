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
from .flank_fit import FlankFit, band_volume, fit_heights, fit_rings, greville, split_spans

__all__ = ["StepSolid", "straight_solid", "twisted_solid", "kinked", "runs_of", "ring_area", "flank_section", "volume"]

_MERGE = 1e-9
"""Two arcs are one circle, two lines one line, where centres, radii and offsets agree this
closely (mm): only runs that are the same curve by construction (a circle's quarter arcs)."""


@dataclass(frozen=True)
class StepSolid:
    """A part's B-rep (an OCP ``TopoDS_Shape``) and its name; ``volume`` (mm³) where it is known
    already (in closed form, or a twisted part's by OpenCASCADE's fixed Gauss rule: its adaptive
    one takes seconds on hundreds of B-spline faces)."""

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


def _tangents(seg: tuple) -> tuple[np.ndarray, np.ndarray]:
    """A run's unit tangents at its start and at its end."""
    if seg[0] == "line":
        d = (seg[2] - seg[1]) / float(np.hypot(*(seg[2] - seg[1])))
        return d, d
    out = []
    for p in (seg[1], seg[2]):
        r = p - seg[3]
        out.append(np.sign(seg[5]) * np.array([-r[1], r[0]]) / float(np.hypot(*r)))
    return out[0], out[1]


KINK = (1e-9, np.radians(20))
"""A joint between two runs that turns by more than nothing and less than a corner (20°, as
``geometry/inset.py`` counts corners), rad: an arc fit's joints (its arcs end on the outline's
vertices, tangent to neither neighbour)."""


def kinked(ring: ArcRing) -> bool:
    """Whether ``ring`` has a joint that turns by a little (:data:`KINK`): OpenCASCADE's chamfer
    fails on such a ring (the cones and planes either side of a joint meet nearly tangent), after
    seconds; a circle, a bore's keyway, a square take it."""
    runs = _segments(ring)
    if len(runs) < 2:
        return False
    ends = [_tangents(s) for s in runs]
    for (_, t_in), (t_out, _) in zip(ends[-1:] + ends[:-1], ends):
        turn = abs(float(np.arctan2(t_in[0] * t_out[1] - t_in[1] * t_out[0], float(np.dot(t_in, t_out)))))
        if KINK[0] < turn < KINK[1]:
            return True
    return False


def runs_of(ring: ArcRing) -> list[tuple]:
    """The ring's runs as its solid's side faces are made of them (see ``_segments``)."""
    return _segments(ring)


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
    return StepSolid(name, shape, thickness * sum(ring_area(r) for r in rings))


def ring_area(ring: ArcRing) -> float:
    """The signed area inside a ring of lines and arcs (mm²): its chords' shoelace area and each
    arc's circular segment r²(θ − sin θ)/2, θ the signed sweep."""
    area = 0.0
    for seg in _segments(ring):
        a, b = seg[1], seg[2]
        area += 0.5 * float(a[0] * b[1] - a[1] * b[0])
        if seg[0] == "arc":
            area += 0.5 * seg[4] ** 2 * (seg[5] - np.sin(seg[5]))
    return area


def _surfaces(fit: FlankFit, rows: np.ndarray, vknots: np.ndarray, vmults: np.ndarray, vdegree: int) -> list:
    """The flank band as faces' surfaces, each of at most :data:`_SPANS` knot spans round the
    section (OpenCASCADE's default volume takes one fixed Gauss rule of at most 61 points across
    a face: enough for 8 cubic spans): u = z, of degree ``vdegree`` (``rows`` (r, m, 2) the
    control rings up the band), v cubic round the section (``fit``'s knots, in mm); poles
    rounded to :data:`_GRID` mm.  Returns (surface, first v, last v) for each."""
    from OCP.collections import Array2_gp_Pnt
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    poles = fit.poles_of(rows)
    heights = np.round(greville(vknots, vmults, vdegree), 12).tolist()
    uk, um = _knots(vknots, vmults)
    out = []
    for a, b, inner, part in fit.parts():
        flat = np.concatenate([np.full(4, fit.t[a]), np.sort(inner), np.full(4, fit.t[b])])
        for knots, block in split_spans(flat, poles[:, part], _SPANS):
            block = np.round(block / _GRID) * _GRID
            r, q = block.shape[:2]
            grid = Array2_gp_Pnt(1, r, 1, q)
            for i in range(r):
                for j, (x, y) in enumerate(block[i].tolist()):
                    grid.SetValue(i + 1, j + 1, gp_Pnt(round(x, 9), round(y, 9), heights[i]))
            distinct, mults = np.unique(knots, return_counts=True)
            vk, vm = _knots(distinct, mults)
            out.append((Geom_BSplineSurface(grid, uk, vk, um, vm, vdegree, 3), float(knots[0]), float(knots[-1])))
    return out


_SPANS = 8
"""Knot spans round the section per B-spline face."""
_GRID = 1e-6
"""The flank's poles are rounded to this, mm (a shorter file; far inside any tolerance)."""


"""Pieces of a section (between its corners: a tooth's tip land, the flanks and root beside it)
per B-spline face."""


def _knots(values: np.ndarray, mults: np.ndarray):
    from OCP.collections import Array1_double, Array1_int

    knot, mult = Array1_double(1, len(values)), Array1_int(1, len(values))
    for n, (value, count) in enumerate(zip(values.tolist(), mults.tolist())):
        knot.SetValue(n + 1, float(value))
        mult.SetValue(n + 1, int(count))
    return knot, mult


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
    tolerance: float,
    chamfer: float = 0.0,
    breaks: Sequence[float] = (),
) -> StepSolid:
    """The solid through the sections ``rings[k]`` ((n, m, 2), counter-clockwise, vertex j of
    every section the same tooth point) at ``heights[k]``, the chamfer's sections inset as the
    3MF's loft insets them: one B-spline face per band between the chamfer's heights and the
    ``breaks`` (a herringbone's mid-height), cubic round the section with knots common to all
    (within a quarter of ``tolerance`` of every section across it; the chamfer's inset end
    sections within half) and cubic up the band through its end sections (within a quarter);
    straight ``holes`` (clockwise cut rings) through it, their ends chamfered."""
    from OCP.BRepBuilderAPI import (
        BRepBuilderAPI_MakeEdge,
        BRepBuilderAPI_MakeFace,
        BRepBuilderAPI_MakeSolid,
        BRepBuilderAPI_MakeWire,
        BRepBuilderAPI_Sewing,
    )
    from OCP.BRepLib import BRepLib
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec
    from OCP.TopAbs import TopAbs_REVERSED
    from OCP.TopoDS import TopoDS

    z = np.asarray(heights, dtype=float)
    rings = np.asarray(rings, dtype=float)
    bottom, top = float(z[0]), float(z[-1])
    levels = list(breaks)
    targets = np.full(len(z), tolerance / 4)
    if chamfer > 0:
        depth = np.maximum(0.0, np.maximum(chamfer - (z - bottom), chamfer - (top - z)))
        rings = np.stack([inset_ring(r, d) if d > 0 else r for r, d in zip(rings, depth)])
        levels += [bottom + chamfer, top - chamfer]
        targets[depth > 0] = tolerance / 2
    fit = fit_rings(rings, targets)
    sewing = BRepBuilderAPI_Sewing(1e-6)
    ends = {}
    flank = 0.0
    for band in _bands(z, levels):
        rows, vknots, vmults, vdegree = fit_heights(rings[band], z[band], tolerance / 4)
        flank += band_volume(fit, rows, vknots, vmults, vdegree)
        surfaces = _surfaces(fit, rows, vknots, vmults, vdegree)
        for surface, u0, u1 in surfaces:
            sewing.Add(BRepBuilderAPI_MakeFace(surface, z[band][0], z[band][-1], u0, u1, 1e-7).Face())
        if band.start == 0:
            ends[0] = surfaces
        ends[len(z) - 1] = surfaces
    for level in (0, len(z) - 1):
        wire = BRepBuilderAPI_MakeWire()
        for surface, _, _ in ends[level]:
            wire.Add(BRepBuilderAPI_MakeEdge(surface.UIso(float(z[level]))).Edge())
        face = BRepBuilderAPI_MakeFace(wire.Wire(), True)
        for hole in holes:
            face.Add(_wire(hole, float(z[level])))
        sewing.Add(face.Face())
    for hole in holes:
        sewing.Add(BRepPrimAPI_MakePrism(_wire(hole, bottom), gp_Vec(0.0, 0.0, top - bottom)).Shape())
    sewing.Perform()
    shell = TopoDS.Shell(sewing.SewedShape())
    solid = BRepBuilderAPI_MakeSolid(shell).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    if solid.Orientation() == TopAbs_REVERSED:  # the faces inward: the shell turned, the solid forward
        solid = BRepBuilderAPI_MakeSolid(TopoDS.Shell(shell.Reversed())).Solid()
    shape = solid
    if chamfer > 0 and holes:
        shape = _chamfered(shape, chamfer, (bottom, top), lines_and_arcs=True)
    return StepSolid(name, shape, flank - _voids(holes, top - bottom, chamfer))


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


def _wire_of(edge):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeWire

    return BRepBuilderAPI_MakeWire(edge).Wire()


def volume(shape, *, relative_error: float | None = 1e-7) -> float:
    """The shape's volume, mm³, integrated over its faces by OpenCASCADE to ``relative_error``
    (adaptive), or with ``None`` by its fixed Gauss rule (what FreeCAD's ``Shape.Volume`` gives:
    on a twisted part's faces of ≤ 8 spans within 1e-4 of the adaptive one, in a tenth of the time)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    if relative_error is None:
        BRepGProp.VolumeProperties_s(shape, props)
    else:
        BRepGProp.VolumeProperties_s(shape, props, relative_error)
    return float(props.Mass())


def flank_section(shape, z: float, per_span: int = 8) -> np.ndarray:
    """The twisted flank's section at height ``z`` read off its B-spline faces: (p, 2) mm, every
    face spanning ``z`` (in the order of u round the section) evaluated ``per_span`` times in
    every knot span."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    found = []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        surface = BRep_Tool.Surface_s(TopoDS.Face(explorer.Current()))
        explorer.Next()
        if not hasattr(surface, "NbUPoles"):  # a plane, cylinder or cone: not the flank
            continue
        z0, z1, v0, _ = surface.Bounds()  # u = z, v round the section
        if z0 < z < z1:
            knots = np.array([surface.VKnot(i) for i in range(1, surface.NbVKnots() + 1)])
            u = (knots[:-1, None] + np.diff(knots)[:, None] * (np.arange(per_span) / per_span)).ravel()
            found.append((v0, [(q.X(), q.Y()) for q in (surface.Value(z, float(v)) for v in u)]))
    if not found:
        raise ValueError(f"no flank face spans z = {z:g} mm")
    return np.array([p for _, points in sorted(found, key=lambda f: f[0]) for p in points])
