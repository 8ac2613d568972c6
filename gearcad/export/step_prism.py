"""A straight part's STEP file written as text, without OpenCASCADE: its cut rings (lines and
circular arcs, ``geometry/arcfit.py``) extruded from z = 0 to the thickness.

The B-rep is the one OpenCASCADE's prism makes of the same rings, entity for entity as its STEP
writer writes it (AP214, mm, uncertainty 1e-7 mm): per run of a ring (a line, or consecutive arcs
of one circle, as ``export/step_brep.py`` merges them) a side face (a plane, or a cylinder), its
bottom and top edges (lines, circles) and a vertical line edge at its start; a bottom and a top
plane bounded by every ring.  Loading OpenCASCADE takes a second or two of CPU: a design of
straight parts only needs none (issue 37 item 10).  Equal points, directions, vectors and
placements are written once, as ``export/step_text.py`` shares them in OpenCASCADE's files.
Coordinates are rounded to 1e-9 mm (12 significant digits, as OpenCASCADE writes them).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..geometry.arcfit import ArcRing
from .step_brep import runs_of
from .step_text import product_head

__all__ = ["prism_text"]


def _num(x: float) -> str:
    """A STEP real of ``x`` rounded to 1e-9: a decimal point always, no negative zero."""
    text = format(round(float(x), 9) + 0.0, ".12G")
    mantissa, e, exponent = text.partition("E")
    if "." not in mantissa:
        mantissa += "."
    if mantissa in ("0.", "-0."):
        return "0."
    return mantissa + (f"E{int(exponent)}" if e else "")


class _Entities:
    """Entities numbered in the order made; geometry (``shared``) made once for equal text."""

    def __init__(self, first: int) -> None:
        self.lines: list[str] = []
        self.next = first
        self.seen: dict[str, int] = {}

    def add(self, body: str) -> int:
        n = self.next
        self.next += 1
        self.lines.append(f"#{n}={body};")
        return n

    def shared(self, body: str) -> int:
        n = self.seen.get(body)
        if n is None:
            n = self.seen[body] = self.add(body)
        return n

    def point(self, x: float, y: float, z: float) -> int:
        return self.shared(f"CARTESIAN_POINT('',({_num(x)},{_num(y)},{_num(z)}))")

    def direction(self, x: float, y: float, z: float) -> int:
        return self.shared(f"DIRECTION('',({_num(x)},{_num(y)},{_num(z)}))")

    def placement(self, origin: int, axis: int, ref: int) -> int:
        return self.shared(f"AXIS2_PLACEMENT_3D('',#{origin},#{axis},#{ref})")

    def bound(self, edges: Sequence[tuple[int, bool]]) -> int:
        """A face bound: a loop of the ``edges`` (edge, used along its curve's sense or not)."""
        used = [self.add(f"ORIENTED_EDGE('',*,*,#{n},{'.T.' if along else '.F.'})") for n, along in edges]
        loop = self.add(f"EDGE_LOOP('',({','.join(f'#{n}' for n in used)}))")
        return self.add(f"FACE_BOUND('',#{loop},.T.)")


def prism_text(name: str, rings: Sequence[ArcRing], thickness: float, timestamp: str) -> str:
    """The STEP file of ``rings`` (the outer counter-clockwise first, holes clockwise; mm)
    extruded by ``thickness``, one product named ``name``."""
    e = _Entities(14)  # 1–13: the product and the solid's own entities, below
    up, down, x_axis = e.direction(0, 0, 1), e.direction(0, 0, -1), e.direction(1, 0, 0)
    origin = e.point(0, 0, 0)
    e.seen[f"AXIS2_PLACEMENT_3D('',#{origin},#{up},#{x_axis})"] = 11  # the solid's own placement
    levels = (0.0, float(thickness))
    vertical = e.shared(f"VECTOR('',#{up},1.)")
    faces: list[int] = []
    bottoms, tops = [], []  # per ring: its runs' bottom and top edges
    for ring in rings:
        runs = runs_of(ring)
        starts = [run[1] for run in runs]
        below = [e.add(f"VERTEX_POINT('',#{e.point(p[0], p[1], 0.0)})") for p in starts]
        above = [e.add(f"VERTEX_POINT('',#{e.point(p[0], p[1], levels[1])})") for p in starts]
        rising = []
        for p, b, t in zip(starts, below, above):
            line = e.shared(f"LINE('',#{e.point(p[0], p[1], 0.0)},#{vertical})")
            rising.append(e.add(f"EDGE_CURVE('',#{b},#{t},#{line},.T.)"))
        ring_bottom, ring_top = [], []
        for k, run in enumerate(runs):
            after = (k + 1) % len(runs)
            edges = []
            for z, ends in zip(levels, (below, above)):
                if run[0] == "line":
                    a, b = run[1], run[2]
                    length = float(np.hypot(*(b - a)))
                    way = e.direction((b - a)[0] / length, (b - a)[1] / length, 0.0)
                    along = e.shared(f"VECTOR('',#{way},1.)")
                    curve = e.shared(f"LINE('',#{e.point(a[0], a[1], z)},#{along})")
                    sense = ".T."
                else:
                    centre, radius, sweep = run[3], run[4], run[5]
                    axes = e.placement(e.point(centre[0], centre[1], z), up, x_axis)
                    curve = e.shared(f"CIRCLE('',#{axes},{_num(radius)})")
                    sense = ".T." if sweep > 0 else ".F."
                edges.append(e.add(f"EDGE_CURVE('',#{ends[k]},#{ends[after]},#{curve},{sense})"))
            bottom, top = edges
            ring_bottom.append(bottom)
            ring_top.append(top)
            if run[0] == "line":
                a, b = run[1], run[2]
                length = float(np.hypot(*(b - a)))
                d = (b - a) / length
                out = e.direction(d[1], -d[0], 0.0)  # right of the way: out of the material
                plane = e.placement(e.point(a[0], a[1], 0.0), out, e.direction(d[0], d[1], 0.0))
                surface, same = e.shared(f"PLANE('',#{plane})"), ".T."
            else:
                centre, radius, sweep = run[3], run[4], run[5]
                axes = e.placement(e.point(centre[0], centre[1], 0.0), up, x_axis)
                # the cylinder's normal points away from its axis: out of the material where the
                # run turns left (the material on its left, the centre too), into it otherwise
                surface = e.shared(f"CYLINDRICAL_SURFACE('',#{axes},{_num(radius)})")
                same = ".T." if sweep > 0 else ".F."
            bound = e.bound([(bottom, True), (rising[after], True), (top, False), (rising[k], False)])
            faces.append(e.add(f"ADVANCED_FACE('',(#{bound}),#{surface},{same})"))
        bottoms.append(ring_bottom)
        tops.append(ring_top)
    for z, edges_of, normal, sense in ((0.0, bottoms, down, ".F."), (levels[1], tops, up, ".T.")):
        bounds = []
        for edges in edges_of:
            order = edges[::-1] if sense == ".F." else edges  # the bottom seen from below
            bounds.append(e.bound([(n, sense == ".T.") for n in order]))
        plane = e.shared(f"PLANE('',#{e.placement(e.point(0.0, 0.0, z), normal, x_axis)})")
        faces.append(e.add(f"ADVANCED_FACE('',({','.join(f'#{n}' for n in bounds)}),#{plane},.T.)"))
    context = e.next
    tail = [
        f"#{context}=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{context + 4})) "
        f"GLOBAL_UNIT_ASSIGNED_CONTEXT((#{context + 1},#{context + 2},#{context + 3})) "
        "REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY') );",
        f"#{context + 1}=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
        f"#{context + 2}=( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
        f"#{context + 3}=( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() );",
        f"#{context + 4}=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{context + 1},"
        "'distance_accuracy_value','confusion accuracy');",
        f"#{context + 5}=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#7));",
    ]
    head = [
        *product_head(name),
        f"#10=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#11,#12),#{context});",
        f"#11=AXIS2_PLACEMENT_3D('',#{origin},#{up},#{x_axis});",
        "#12=MANIFOLD_SOLID_BREP('',#13);",
        f"#13=CLOSED_SHELL('',({','.join(f'#{n}' for n in faces)}));",
    ]
    header = (
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('gearcad part'),'2;1');\n"
        f"FILE_NAME('{name}','{timestamp}',('gearcad'),(''),'gearcad','gearcad','Unknown');\n"
        "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
    )
    return header + "\n".join(head + e.lines + tail) + "\nENDSEC;\nEND-ISO-10303-21;\n"
