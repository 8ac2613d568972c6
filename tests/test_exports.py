"""Files for making things, read back by independent readers (ezdxf, trimesh, Pillow)."""

import functools
import json
from pathlib import Path

import ezdxf
import ezdxf.path
import numpy as np
import pytest
import shapely
import trimesh
from PIL import Image

from gearcad.cli import main
from gearcad.errors import DesignError
from gearcad.export.dxf import CHORD_AREA, limit_sweep, ring_area_with_arcs
from gearcad.export.mesh import extrude
from gearcad.geometry.arcfit import ArcRing
from gearcad.geometry.outline import Outline

from .conftest import drawn

SMALL = """
name = "small"
[gear1]
name = "a"
curve = "ellipse"
pivot = "focus"
a = 20.0
b = 16.0
[gear2]
name = "b"
lobes = 1
[teeth]
count = 25
[output]
tolerance = {tol}
charts = false
animation = {animation}
thickness = 4.0
chamfer = {chamfer}
kerf = {kerf}
dxf = "{dxf}"
formats = {formats}
[bore]
diameter = {bore}
{bore_extra}
"""


def build(
    tmp_path,
    *,
    tol=0.001,
    chamfer=0.0,
    kerf=0.0,
    dxf="polyline",
    bore=3.0,
    bore_extra="",
    animation="false",
    name="out",
    formats='["dxf", "stl", "3mf"]',
):
    """The small pair built with these settings into ``tmp_path``: (its folder, its report).
    Built once per settings for the module (the tests only read what it wrote), in this process
    (the design as drawn, :func:`~.conftest.drawn` — the files are what is tested here, and with
    no process the fit's band changes none of them — and the writing loop: no pool, no forks),
    writing only ``formats``."""
    from gearcad.export.write import write_design
    from gearcad.profiles import load_profile

    key = (tol, chamfer, kerf, dxf, bore, bore_extra, animation, formats)
    if key in _BUILT and _BUILT[key][0].is_dir():
        return _BUILT[key]
    path = tmp_path / f"{name}.toml"
    path.write_text(
        SMALL.format(
            tol=tol,
            chamfer=chamfer,
            kerf=kerf,
            dxf=dxf,
            bore=bore,
            bore_extra=bore_extra,
            animation=animation,
            formats=formats,
        )
    )
    folder = tmp_path / name / "small"
    folder.mkdir(parents=True)
    design = drawn(load_profile(path))
    assert design.ok, design.failures()  # what ``gearcad build`` asks before it writes (exit 3 if not)
    write_design(design, folder)
    _BUILT[key] = folder, json.loads((folder / "report.json").read_text())
    return _BUILT[key]


_BUILT: dict[tuple, tuple[Path, dict]] = {}


def flattened(entity, distance=1e-5) -> np.ndarray:
    return np.array([(v.x, v.y) for v in ezdxf.path.make_path(entity).flattening(distance)])[:-1]


def cut_polygon(source) -> shapely.Polygon:
    """The CUT layer's rings of a DXF file (its path, or the document already read) as a polygon."""
    doc = ezdxf.readfile(source) if isinstance(source, Path) else source
    rings = [flattened(e) for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT"]
    rings.sort(key=lambda r: -shapely.Polygon(r).area)
    return shapely.Polygon(rings[0], rings[1:])


def test_dxf_reads_back_as_the_outline_within_tolerance(tmp_path):
    folder, report = build(tmp_path)
    for gear in report["gears"]:
        doc = ezdxf.readfile(folder / f"{gear['name']}.dxf")
        polygon = cut_polygon(doc)  # as read, before the audit could repair anything
        assert not doc.audit().has_errors and doc.units == 4
        assert {layer.dxf.name for layer in doc.layers} >= {"CUT", "MARK"}
        cut = [e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT"]
        assert len(cut) == 2 and all(e.closed for e in cut)  # outline and bore
        assert any(b != 0 for e in cut for *_, b in e.get_points("xyb"))  # arcs as bulges
        # the same outline: flattened arcs against a fine reference cut of the same teeth
        reference = shapely.Polygon(*_reference_rings(report, gear))
        # reference chords stray ≤ 1e-4 mm from the exact teeth: allow for that
        assert _distance(polygon.exterior, reference.exterior) <= 0.001 + 1e-4
        assert polygon.area == pytest.approx(gear["part"]["area"], abs=0.001 * gear["perimeter"])


def _distance(a: shapely.LinearRing, b: shapely.LinearRing) -> float:
    """Largest distance from either ring's vertices to the other ring (a one-sided Hausdorff
    distance each way, to the continuous ring)."""

    def one_way(ring_from, ring_to):  # nearest segment by GEOS's R-tree: exact, not all pairs
        c = np.asarray(ring_to.coords)
        tree = shapely.STRtree(shapely.linestrings(np.stack([c[:-1], c[1:]], axis=1)))
        _, d = tree.query_nearest(shapely.points(np.asarray(ring_from.coords)), return_distance=True, all_matches=False)
        return d.max()

    return float(max(one_way(a, b), one_way(b, a)))


def _reference_rings(report, gear):
    """gearcad's own cut of the part at a tenth of the tolerance (chords within 1e-4 mm)."""
    part = _reference_parts()[0 if gear["name"] == "a" else 1]
    return part.outline.rings[0], part.outline.rings[1:]


@functools.cache
def _reference_parts():
    """The parts as drawn (:func:`~tests.conftest.drawn`: the fit and its proof at 1e-4 mm took 6
    of the 7 CPU-s and change no vertex of the outline)."""
    from gearcad.profiles import parse_profile

    data_dict = {
        "name": "r",
        "gear1": {"name": "a", "curve": "ellipse", "pivot": "focus", "a": 20.0, "b": 16.0},
        "gear2": {"name": "b", "lobes": 1},
        # the build's teeth: its default play at output.tolerance 0.001 is 6·tol/cos α
        "teeth": {"count": 25, "backlash": 0.006 / 0.9396926207859084},
        "output": {"tolerance": 1e-4},
        "bore": {"diameter": 3.0},
    }
    return drawn(parse_profile(data_dict)).parts()


def test_dxf_needs_far_fewer_vertices_than_chords(tmp_path):
    folder, report = build(tmp_path)
    for gear in report["gears"]:
        doc = ezdxf.readfile(folder / f"{gear['name']}.dxf")  # the cut layer: the outline as written
        dxf = sum(len(e) for e in doc.modelspace().query('LWPOLYLINE[layer=="CUT"]'))
        assert dxf * 4 < gear["part"]["vertices"]


def test_stl_and_3mf_are_watertight_with_the_right_volume(tmp_path):
    folder, report = build(tmp_path)
    for gear in report["gears"]:
        area, name = gear["part"]["area"], gear["name"]
        stl = trimesh.load(folder / f"{name}.stl")
        assert stl.is_watertight and stl.is_winding_consistent and stl.volume > 0
        assert stl.volume == pytest.approx(area * 4.0, rel=1e-6)  # float32 vertices
        triangles = report["files"][f"{name}.stl"]["triangles"]
        assert (folder / f"{name}.stl").stat().st_size == 84 + 50 * triangles  # binary STL
        scene = trimesh.load(folder / f"{name}.3mf")
        (mesh,) = scene.geometry.values()
        assert mesh.is_watertight and mesh.volume == pytest.approx(area * 4.0, rel=1e-7)  # 6-decimal text
        assert report["files"][f"{name}.3mf"]["triangles"] == len(mesh.faces)
    assembly = trimesh.load(folder / "assembly.3mf")
    assert len(assembly.geometry) == 2
    centres = sorted(assembly.graph[n][0][:3, 3][0] for n in assembly.graph.nodes_geometry)
    assert centres == pytest.approx([0.0, report["pair"]["center_distance"]], abs=1e-6)
    doc = ezdxf.readfile(folder / "assembly.dxf")
    assert not doc.audit().has_errors
    assert len([e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT"]) == 4


def test_counts_fall_as_the_tolerance_loosens(tmp_path):
    _, fine = build(tmp_path, tol=0.001, name="fine")
    _, coarse = build(tmp_path, tol=0.02, name="coarse")
    for kind in ("a.dxf", "a.stl", "b.3mf"):
        key = "vertices" if kind.endswith("dxf") else "triangles"
        assert coarse["files"][kind][key] < fine["files"][kind][key]


def test_chamfer_removes_a_45_degree_edge(tmp_path):
    """On a friction wheel (pitch curve part, no teeth) every edge takes the 45° chamfer."""
    path = tmp_path / "wheel.toml"
    text = SMALL.format(
        tol=0.001,
        chamfer=0.3,
        kerf=0,
        dxf="polyline",
        bore=3.0,
        bore_extra="",
        animation="false",
        formats='["dxf", "stl"]',
    )
    path.write_text(text.replace("[teeth]\ncount = 25\n", ""))
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 0
    folder = tmp_path / "out" / "small"
    report = json.loads((folder / "report.json").read_text())
    for gear in report["gears"]:
        mesh = trimesh.load(folder / f"{gear['name']}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent
        outline = cut_polygon(folder / f"{gear['name']}.dxf")
        edge = outline.exterior.length + sum(r.length for r in outline.interiors)
        # two 45° chamfers along every boundary remove c²/2 × length each (curvature adds
        # a term of order c³/radius)
        expected = gear["part"]["area"] * 4.0 - edge * 0.3**2
        assert mesh.volume == pytest.approx(expected, rel=5e-4)
        assert mesh.bounds[:, 2] == pytest.approx([0.0, 4.0])


def test_chamfer_on_toothed_gears(tmp_path):
    """Teeth take the chamfer too: short segments beside sharp tip corners are collapsed in the
    inset, so the solid stays watertight and its volume is the chamfer's to a few 1e-6."""
    folder, report = build(tmp_path, chamfer=0.2, formats='["dxf", "stl"]')
    for gear in report["gears"]:
        mesh = trimesh.load(folder / f"{gear['name']}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent
        outline = cut_polygon(folder / f"{gear['name']}.dxf")
        edge = outline.exterior.length + sum(r.length for r in outline.interiors)
        assert mesh.volume == pytest.approx(gear["part"]["area"] * 4.0 - edge * 0.2**2, rel=1e-4)


def test_chamfer_the_teeth_cannot_take_is_refused(tmp_path, capsys):
    path = tmp_path / "p.toml"
    path.write_text(  # refused before anything is written: at 0.01 mm, the solid format only
        SMALL.format(
            tol=0.01,
            chamfer=0.9,
            kerf=0,
            dxf="polyline",
            bore=3.0,
            bore_extra="",
            animation="false",
            formats='["stl"]',
        )
    )
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "output.chamfer = 0.9" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_kerf_grows_the_cut_path_by_half_the_kerf(tmp_path):
    folder, report = build(tmp_path, kerf=0.2, formats='["dxf"]')
    doc = ezdxf.readfile(folder / "a.dxf")
    assert "kerf" in doc.layers.get("CUT").description
    polygon = cut_polygon(doc)
    designed = shapely.Polygon(*_reference_rings(report, report["gears"][0]))
    # the path runs 0.1 mm outside the part everywhere, the bore 0.1 mm inside it
    assert _distance(polygon.exterior, designed.exterior) == pytest.approx(0.1, abs=0.002)
    assert polygon.interiors[0].distance(shapely.Point(0, 0)) == pytest.approx(1.5 - 0.1, abs=0.002)
    assert report["output"]["kerf"] == 0.2


def test_keyway_and_flat(tmp_path):
    # straight sides and a chord: their extremes are exact vertices at any tolerance
    coarse = {"tol": 0.01, "formats": '["dxf"]'}
    folder, _ = build(tmp_path, bore_extra="keyway_width = 1.0\nkeyway_depth = 0.5", name="key", **coarse)
    hole = cut_polygon(folder / "a.dxf").interiors[0]
    xs = np.asarray(hole.coords)[:, 0]
    assert xs.max() == pytest.approx(1.5 + 0.5, abs=1e-6)
    folder, _ = build(tmp_path, bore_extra="flat = 1.0", name="flat", **coarse)
    hole = cut_polygon(folder / "a.dxf").interiors[0]
    assert np.asarray(hole.coords)[:, 0].max() == pytest.approx(1.0, abs=1e-6)


def test_bore_that_leaves_no_wall_is_refused(tmp_path, capsys):
    path = tmp_path / "p.toml"
    # the near apex of a focus-pivoted ellipse a = 20, b = 16 is 8 mm from the pivot, its root
    # about 6.2 mm: an 11 mm bore leaves 0.7 mm, under one module
    path.write_text(
        SMALL.format(
            tol=0.01, chamfer=0, kerf=0, dxf="polyline", bore=11.0, bore_extra="", animation="false", formats='["dxf"]'
        )
    )
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "bore.diameter = 11" in err and "leave at least" in err
    assert not (tmp_path / "out").exists()


def test_animation_has_a_frame_per_step(tmp_path):
    folder, report = build(tmp_path, animation="true", tol=0.01, formats="[]")  # the GIF alone
    with Image.open(folder / "animation.gif") as gif:
        assert gif.n_frames == report["files"]["animation.gif"]["frames"] >= 24


def test_a_manifold_error_is_a_clear_error():
    flat = Outline((np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]),))
    with pytest.raises(DesignError, match="empty|not a valid"):
        extrude(flat, 1.0, name="sliver")


def test_every_flavour_describes_the_same_outline(tmp_path):
    shapes = {}
    for flavour in ("polyline", "lines-arcs", "polyline-flat"):
        folder, _ = _flavour(tmp_path, flavour)
        doc = ezdxf.readfile(folder / "a.dxf")
        if flavour == "lines-arcs":
            entities = [e for e in doc.modelspace() if e.dxf.layer == "CUT"]
            assert {e.dxftype() for e in entities} == {"LINE", "ARC"}
            shapes[flavour] = _chain(entities)
        else:
            shapes[flavour] = cut_polygon(doc)
            if flavour == "polyline-flat":
                bulges = [b for e in doc.modelspace().query("LWPOLYLINE") for *_, b in e.get_points("xyb")]
                assert not any(bulges)
        assert not doc.audit().has_errors  # after reading: the shapes are the file's as written
    for flavour in ("lines-arcs", "polyline-flat"):
        assert _distance(shapes[flavour].exterior, shapes["polyline"].exterior) <= 0.002


def _flavour(tmp_path, flavour: str):
    """The small pair's DXF in ``flavour`` (the full default build for "polyline")."""
    if flavour == "polyline":
        return build(tmp_path)
    return build(tmp_path, dxf=flavour, name=flavour.replace("-", "_"), formats='["dxf"]')


def _chain(entities) -> shapely.Polygon:
    """LINE and ARC entities chained end to end into closed loops (they must meet exactly)."""
    pieces = []
    for e in entities:
        if e.dxftype() == "ARC":
            pts = np.array([(v.x, v.y) for v in ezdxf.path.make_path(e).flattening(1e-5)])
        else:
            pts = np.array([(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)])
        pieces.append(pts)
    loops = []
    remaining = pieces[:]
    while remaining:
        loop = [remaining.pop(0)]
        while True:
            end = loop[-1][-1]
            if np.hypot(*(end - loop[0][0])) < 1e-9 and len(loop) > 1:
                break
            for k, piece in enumerate(remaining):
                if np.hypot(*(piece[0] - end)) < 1e-9:
                    loop.append(remaining.pop(k))
                    break
                if np.hypot(*(piece[-1] - end)) < 1e-9:
                    loop.append(remaining.pop(k)[::-1])
                    break
            else:
                raise AssertionError(f"open chain at {end}")
        loops.append(np.vstack([p[:-1] for p in loop]))
    loops.sort(key=lambda r: -shapely.Polygon(r).area)
    assert len(loops) == 2  # outline and bore, both closed
    return shapely.Polygon(loops[0], loops[1:])


def _openscad_area(openscad: str, dxf: Path, tmp_path: Path) -> float:
    """Import the CUT layer into OpenSCAD with fine arc tessellation, extrude 1 mm, export STL
    and read its volume back with trimesh: the imported area."""
    import subprocess

    scad = tmp_path / f"{dxf.parent.parent.name}.scad"
    scad.write_text(f'$fa = 0.5; $fs = 0.005;\nlinear_extrude(height = 1) import("{dxf}", layer = "CUT");\n')
    stl = scad.with_suffix(".stl")
    run = subprocess.run(
        [openscad, "-o", str(stl), str(scad)],
        capture_output=True,
        text=True,
        timeout=300,
        env={"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)},
    )
    assert run.returncode == 0, run.stderr
    return float(trimesh.load(stl).volume)


def test_openscad_imports_the_lines_arcs_file_at_the_right_area(tmp_path):
    """OpenSCAD drops LWPOLYLINE bulges (it draws each arc as its chord): the lines-arcs flavour
    comes in at the designed area, the polyline flavour as its chord polygon — which the sweep
    limit keeps within 0.25 % of the designed area (and no longer lets a bore be a triangle)."""
    import shutil

    openscad = shutil.which("openscad")
    if openscad is None:
        pytest.skip("openscad is not installed on this machine (apt-get install openscad to run this check)")
    folder, report = build(tmp_path, dxf="lines-arcs", name="scad_arcs")
    designed = report["gears"][0]["part"]["area"]
    assert _openscad_area(openscad, folder / "a.dxf", tmp_path) == pytest.approx(designed, rel=2e-4)
    folder, _ = build(tmp_path, dxf="polyline", name="scad_bulges")
    doc = ezdxf.readfile(folder / "a.dxf")
    rings = [
        np.array([q[:2] for q in e.get_points()]) for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT"
    ]
    chords = shapely.Polygon(
        max(rings, key=lambda r: shapely.Polygon(r).area), [r for r in rings if shapely.Polygon(r).area < 50]
    ).area
    imported = _openscad_area(openscad, folder / "a.dxf", tmp_path)
    assert imported == pytest.approx(chords, rel=2e-4)  # the bulges were ignored ...
    assert imported == pytest.approx(designed, rel=0.0025)  # ... at little cost


# ----------------------------------------------------------------------------- DXF for every reader


def _circle(radius: float, arcs: int, centre=(0.0, 0.0), clockwise: bool = False) -> ArcRing:
    """A circle as ``arcs`` equal arcs (bulge tan(θ/4), θ = ±2π/arcs)."""
    angles = np.arange(arcs) * 2 * np.pi / arcs * (-1 if clockwise else 1)
    vertices = np.column_stack([np.cos(angles), np.sin(angles)]) * radius + np.asarray(centre)
    return ArcRing(vertices, np.full(arcs, np.tan((-1 if clockwise else 1) * np.pi / (2 * arcs))))


def _shoelace(v: np.ndarray) -> float:
    return 0.5 * float(np.dot(v[:, 0], np.roll(v[:, 1], -1)) - np.dot(v[:, 1], np.roll(v[:, 0], -1)))


@pytest.mark.parametrize("arcs", [2, 3, 5])
def test_a_circle_is_split_into_the_fewest_arcs_whose_chords_keep_its_area(arcs):
    """A circle of radius r as n equal chords holds n·r²·sin(2π/n)/2: within 0.25 % of πr² takes
    n = 52 (51 hold 0.2528 % less); the written vertices stay on the circle."""
    share = 0.0025
    need = next(n for n in range(3, 200) if 1 - n * np.sin(2 * np.pi / n) / (2 * np.pi) <= share)
    assert need == 52
    (ring,) = limit_sweep([_circle(7.0, arcs)], regions=False, share=share)
    assert need <= len(ring.vertices) <= need + 1  # 52 split over 3 or 5 arcs is not quite equal
    assert np.hypot(*ring.vertices.T) == pytest.approx(7.0, abs=1e-12)
    assert 0 < 1 - _shoelace(ring.vertices) / (np.pi * 49) <= share  # chords inside, within the share
    assert ring_area_with_arcs(ring) == pytest.approx(np.pi * 49, rel=1e-12)  # the path is unchanged


def test_an_annulus_is_held_to_its_own_net_area():
    """A circle of radius 10 around a hole of radius 9 drawn as a plain 360-gon: the circle
    within 0.25 % of its own area would let its chords take 0.25 % · 100π, 1.3 % of the part
    (19π); the part's budget splits the arcs further, until the part is within 0.25 %."""
    angles = -np.arange(360) * 2 * np.pi / 360
    hole = ArcRing(9.0 * np.column_stack([np.cos(angles), np.sin(angles)]), np.zeros(360))
    part = 100 * np.pi + _shoelace(hole.vertices)
    alone = limit_sweep([_circle(10.0, 4), hole], regions=False)
    assert 1 - sum(_shoelace(r.vertices) for r in alone) / part > 0.01
    split = limit_sweep([_circle(10.0, 4), hole], regions=True)
    assert sum(_shoelace(r.vertices) for r in split) == pytest.approx(part, rel=CHORD_AREA)
    assert np.array_equal(split[1].vertices, hole.vertices)  # the plain hole is left alone


def test_dxf_header_extents_and_no_point_display(tmp_path):
    """$EXTMIN/$EXTMAX are the drawing's extents (ezdxf's own bounding box of the entities,
    arcs at their true extremes); no $PDMODE or $PDSIZE for Inkscape to warn about."""
    import ezdxf.bbox

    folder, _ = build(tmp_path)
    for name in ("a.dxf", "b.dxf", "assembly.dxf"):
        doc = ezdxf.readfile(folder / name)
        box = ezdxf.bbox.extents(doc.modelspace(), fast=False)
        assert tuple(doc.header["$EXTMIN"])[:2] == pytest.approx((box.extmin.x, box.extmin.y), abs=1e-6)
        assert tuple(doc.header["$EXTMAX"])[:2] == pytest.approx((box.extmax.x, box.extmax.y), abs=1e-6)
        assert "$PDMODE" not in doc.header and "$PDSIZE" not in doc.header
        assert doc.header["$INSUNITS"] == 4 and doc.header["$MEASUREMENT"] == 1


def test_engraving_is_polyline_and_the_cut_layer_takes_the_flavour(tmp_path):
    """Marks (pitch curve, pivot cross) are POLYLINE entities in every flavour — OpenSCAD reads
    no POLYLINE, so they never mix into the part — and every one is open: the pitch curve is
    dashed, so a program filling closed shapes cannot engrave its region (issue 24)."""
    for flavour, cut_kinds in (("polyline", {"LWPOLYLINE"}), ("lines-arcs", {"LINE", "ARC"})):
        folder, _ = _flavour(tmp_path, flavour)
        doc = ezdxf.readfile(folder / "a.dxf")
        assert not doc.audit().has_errors
        kinds = {(e.dxf.layer, e.dxftype()) for e in doc.modelspace()}
        assert {k for layer, k in kinds if layer == "CUT"} == cut_kinds
        assert {k for layer, k in kinds if layer == "MARK"} == {"POLYLINE"}
        marks = doc.modelspace().query("POLYLINE")
        assert not any(e.is_closed for e in marks)
        # the assembly dot: a diamond drawn round (five vertices, back to its start), not a dash
        marks = [
            e for e in marks if not (len(e.vertices) == 5 and e.vertices[0].dxf.location == e.vertices[4].dxf.location)
        ]
        assert len(marks) > 2 + 5  # the cross, and dashes
        dashes = [np.array([(v.dxf.location.x, v.dxf.location.y) for v in e.vertices]) for e in marks]
        dashes = [d for d in dashes if len(d) > 2 or np.hypot(*(d[1] - d[0])) > 2.5]  # not the cross
        drawn = sum(np.hypot(*np.diff(d, axis=0).T).sum() for d in dashes)
        perimeter = json.loads((folder / "report.json").read_text())["gears"][0]["perimeter"]
        assert drawn == pytest.approx(0.75 * perimeter, rel=1e-3)  # three quarters drawn, in dashes
        assert all(2.0 < np.hypot(*np.diff(d, axis=0).T).sum() < 3.5 for d in dashes)


class _EzdxfMarks:
    """ezdxf's own way with the engraving: a VERTEX entity a point, written by ``saveas``."""

    def __init__(self, doc):
        self.doc = doc

    def add(self, msp, rows, layer, *, close=False):
        msp.add_polyline2d(rows, format="xyb"[: len(rows[0])], close=close, dxfattribs={"layer": layer})

    def save(self, path):
        self.doc.saveas(path)


def test_engraving_written_as_text_is_what_ezdxf_writes(tmp_path, monkeypatch):
    """The engraving's vertices written as text (gearcad/export/dxf_marks.py) give the same bytes
    as ezdxf's own POLYLINE entities: closed and open, with bulges (positive, negative, zero and
    -0.0) and without, a -0.0 coordinate, on two layers, between the cut path's LWPOLYLINEs."""
    from gearcad.export import dxf
    from gearcad.export.drawing import Drawing

    t = np.linspace(0, 2 * np.pi, 7, endpoint=False)
    circle = np.column_stack([np.cos(t), np.sin(t)])
    bulges = np.array([0.1, -0.2, 0.0, -0.0, 0.3, 1e-17, 0.05])
    drawing = Drawing(
        closed={
            "CUT": [ArcRing(10 * circle, np.full(7, 0.07)), ArcRing(2 * circle[::-1], np.zeros(7))],
            "MARK": [ArcRing(7 * circle, bulges), ArcRing(3.5 * circle + 1 / 3, bulges[::-1])],
        },
        strokes={
            "MARK": [np.array([[-0.0, 1.5], [0.0, -1.5]]), ArcRing(5 * circle[:4], np.array([0.2, -0.1, 0.0, 0.4]))],
            "NOTE": [np.array([[1e-9, 2.0], [123456.789, -0.0], [3.0, 4.0]])],
        },
        descriptions={},
    )
    for flavour in ("polyline", "lines-arcs"):
        ours, theirs = tmp_path / f"ours-{flavour}.dxf", tmp_path / f"ezdxf-{flavour}.dxf"
        dxf.write_dxf(ours, drawing, flavour=flavour)
        with monkeypatch.context() as m:
            m.setattr(dxf, "Marks", _EzdxfMarks)
            dxf.write_dxf(theirs, drawing, flavour=flavour)
        assert ours.read_bytes() == theirs.read_bytes(), flavour
        doc = ezdxf.readfile(ours)
        assert not doc.audit().has_errors
        marks = doc.modelspace().query("POLYLINE")
        assert [e.is_closed for e in marks] == [True, True, False, False, False]
        assert [len(e.vertices) for e in marks][2:] == [2, 4, 3] and min(len(e.vertices) for e in marks[:2]) >= 7


def test_caps_cover_the_region_and_keep_every_vertex():
    """A toothed-like ring with a square hole: the cap's triangles, all counter-clockwise, add up
    to the shoelace area and use every vertex (the walls meet the cap there); a vertex exactly
    in line with its neighbours (which earcut drops) is kept too."""
    from gearcad.export.mesh import cap_triangles

    phi = np.linspace(0, 2 * np.pi, 4000, endpoint=False)
    r = 30 + np.cos(40 * phi)
    outer = np.column_stack([r * np.cos(phi), r * np.sin(phi)])
    hole = np.array([[-5.0, -5.0], [-5.0, 5.0], [5.0, 5.0], [5.0, -5.0]])  # clockwise
    inline = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]])  # (1, 0) in line
    for rings in ([outer, hole], [inline]):
        tri = cap_triangles(rings)
        v = np.vstack(rings)
        a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
        doubled = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
        assert np.all(doubled >= 0)
        shoelace = sum(0.5 * np.sum(q[:, 0] * np.roll(q[:, 1], -1) - q[:, 1] * np.roll(q[:, 0], -1)) for q in rings)
        assert doubled.sum() / 2 == pytest.approx(shoelace, rel=1e-12)
        assert np.unique(tri).size == len(v)
