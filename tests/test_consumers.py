"""The real programs makers use read gearcad's files right with their default settings (issue 12).

Each program runs where it is installed and skips, naming its install command, where not;
``python3 tasks.py consumers`` installs them all (Debian packages) and runs this file in full.

* OpenSCAD 2021.01: ``import("part.dxf")`` plain and with ``layer = "CUT"``, exported to SVG and
  measured: the part's designed area within 0.5 %, one piece, its holes kept.
* Inkscape 1.2: its own DXF import (``dxf_input.py``, the code File ▸ Open runs, with the
  dialog's defaults) — headless, since ``inkscape file.dxf`` opens that dialog even on the
  command line; the ``CUT`` layer's paths measured with svgelements, no warning printed.
* LibreCAD 2.2: ``librecad dxf2pdf`` (``-c -s 1``: centred on the page at 1:1, which only
  places the drawing) — runs, the page rendered by pdftoppm is not blank, and the red (``CUT``)
  strokes of the PDF measured: the designed area within 0.5 %.
* PrusaSlicer 2.5: ``--info`` on every STL and 3MF says manifold with nothing repaired, at the
  designed volume; ``--export-gcode`` slices an STL and a 3MF.
* lib3mf 1.8 (Debian's lib3mf1, through its C interface): every 3MF reads in strict mode with
  no warning, every mesh manifold and oriented.
* FreeCAD 0.20: its default STEP import reads every part's STEP file as one valid closed solid
  of the part's name, and every assembly as one valid solid per placed part.
* A reader that ignores bulges: the vertices of every closed ring alone (no bulges) enclose
  the ring's area within 0.5 %, and every part's within 0.5 %.

The slower programs (Inkscape, LibreCAD, PrusaSlicer's slicing, FreeCAD) take a representative subset
of parts by default; ``GEARCAD_CONSUMERS=all`` runs every part of every profile (what
``tasks.py consumers`` does).  ``GEARCAD_CONSUMERS_REPORT=file.json`` writes every measured area
error there (docs/consumers.md's table comes from such a run).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import json
import locale
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import ezdxf.path
import numpy as np
import pytest
import shapely

from .conftest import read_dxf

ALL = os.environ.get("GEARCAD_CONSUMERS", "") == "all"
REPRESENTATIVE = {
    ("elliptic_focus", "driver"),  # teeth on a noncircular pitch curve, pilot hole
    ("planetary_internal", "ring"),  # internal teeth: a thin annulus, the hardest area budget
    ("roller_body_m3", "body"),  # the largest part, with a bore
    ("rolling_wheel", "wheel1"),  # a plain circle
}
SHARE = 0.005  # every reader: the designed area within 0.5 %
INSTALL = "python3 tasks.py consumers"
INK = "{http://www.inkscape.org/namespaces/inkscape}"
SVG = "{http://www.w3.org/2000/svg}"
MEASURED: dict[str, dict[str, float]] = {}  # program -> "profile/part" -> relative area error


@pytest.fixture(scope="module", autouse=True)
def _measurements():
    """Write what was measured to $GEARCAD_CONSUMERS_REPORT (if set) once the module is done."""
    yield
    target = os.environ.get("GEARCAD_CONSUMERS_REPORT")
    if target and MEASURED:
        Path(target).write_text(json.dumps(MEASURED, indent=1, sort_keys=True) + "\n", encoding="utf-8")


def _record(program: str, profile: str, name: str, measured: float, designed: float) -> None:
    MEASURED.setdefault(program, {})[f"{profile}/{name}"] = measured / designed - 1


def _program(name: str, package: str) -> str:
    path = shutil.which(name)
    if path is None:
        pytest.skip(f"{name} is not installed: apt-get install -y {package} (or {INSTALL})")
    return path


def _parts(built: Path, *, subset: bool = False) -> list[tuple[str, str, float, int, Path]]:
    """(profile, part, designed area mm², holes, folder) for every part built."""
    rows = []
    for report_path in sorted(built.glob("*/report.json")):
        report = json.loads(report_path.read_text(encoding="utf-8"))
        for part in report["parts"]:
            key = (report_path.parent.name, part["name"])
            if subset and not ALL and key not in REPRESENTATIVE:
                continue
            rows.append((*key, part["area"], part["holes"], report_path.parent))
    assert rows
    return rows


def _xor_area(rings) -> shapely.MultiPolygon | shapely.Polygon:
    """The region the rings enclose under the even-odd rule (how every reader here fills)."""
    region = shapely.Polygon()
    for ring in rings:
        if len(ring) >= 3:
            region = region.symmetric_difference(shapely.Polygon(ring).buffer(0))
    return region


def _region_shape(region) -> tuple[int, int]:
    """(pieces, holes) of a region."""
    polygons = list(getattr(region, "geoms", [region]))
    return len(polygons), sum(len(p.interiors) for p in polygons)


# ----------------------------------------------------------------------------------- OpenSCAD


def _openscad_region(openscad: str, dxf: Path, tmp_path: Path, layer: str | None):
    """OpenSCAD's import of the DXF exported as SVG (its 2-D polygons as one even-odd path)."""
    arg = f'"{dxf}"' + (f', layer = "{layer}"' if layer else "")
    scad = tmp_path / f"{dxf.parent.name}-{dxf.stem}-{layer or 'plain'}.scad"
    scad.write_text(f"import({arg});\n")
    out = scad.with_suffix(".svg")
    run = subprocess.run(
        [openscad, "-o", str(out), str(scad)],
        capture_output=True,
        text=True,
        timeout=120,
        env={"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "HOME": str(tmp_path)},
    )
    assert run.returncode == 0 and out.exists(), run.stderr
    rings = []
    for d in re.findall(r'<path d="(.*?)"', out.read_text(encoding="utf-8"), re.S):
        for sub in d.split("M")[1:]:
            rings.append([tuple(map(float, xy.split(","))) for xy in re.findall(r"[-+0-9.eE]+,[-+0-9.eE]+", sub)])
    warnings = [ln for ln in run.stderr.splitlines() if ln.startswith(("WARNING", "ERROR"))]
    return _xor_area(rings), warnings


@pytest.mark.parametrize("layer", [None, "CUT"], ids=["plain", "layer-CUT"])
def test_openscad_imports_every_part_at_its_area(built, tmp_path, layer):
    """What a user types, ``import("driver.dxf")``, gives the part: the engraving is written as
    POLYLINE entities, which OpenSCAD skips with a warning (it reads no POLYLINE), so the
    pitch curve no longer cancels the outline; arcs are split so their chords stay within
    0.25 % (OpenSCAD ignores bulges)."""
    openscad = _program("openscad", "openscad")
    for profile, name, area, holes, folder in _parts(built):
        region, warnings = _openscad_region(openscad, folder / f"{name}.dxf", tmp_path, layer)
        where = f"{profile}/{name}.dxf ({layer or 'plain import'})"
        _record(f"openscad {layer or 'plain'}", profile, name, region.area, area)
        assert region.area == pytest.approx(area, rel=SHARE), where
        assert _region_shape(region) == (1, holes), where
        skipped = {re.search(r"Entity '(\w+)'", w).group(1) for w in warnings if "Unsupported DXF Entity" in w}
        assert skipped <= {"POLYLINE", "VERTEX", "SEQEND"}, where
        assert len(warnings) == (len(skipped) if layer is None else 0), (where, warnings)


# ------------------------------------------------------------------- readers that ignore bulges


def _entity_rings(doc, layer: str, kinds: str, distance: float = 1e-5) -> list[tuple[np.ndarray, np.ndarray]]:
    """(vertices only, arcs flattened to ``distance`` mm) of every closed polyline on the layer."""
    rings = []
    for e in doc.modelspace().query(kinds):
        if e.dxf.layer != layer or not e.is_closed:
            continue
        if e.dxftype() == "LWPOLYLINE":
            vertices = np.array([p[:2] for p in e.get_points("xy")])
        else:
            vertices = np.array([tuple(v.dxf.location)[:2] for v in e.vertices])
        fine = np.array([(p.x, p.y) for p in ezdxf.path.make_path(e).flattening(distance)])
        rings.append((vertices, fine))
    return rings


def _areas_with_arcs(doc, layer: str, kinds: str) -> list[tuple[np.ndarray, float]]:
    """(vertices only, the area the ring encloses with its arcs) of every closed polyline on the
    layer: the area in closed form, worked out by hand (not with gearcad's or ezdxf's bulge code),
    the shoelace of the vertices plus, for each arc, the circular segment between it and its chord,
    (θ − sin θ)·ρ²/2 with θ = 4·atan(bulge), ρ = chord / (2·|sin(θ/2)|)."""
    rings = []
    for e in doc.modelspace().query(kinds):
        if e.dxf.layer != layer or not e.is_closed:
            continue
        if e.dxftype() == "LWPOLYLINE":
            xyb = np.array(e.get_points("xyb"), dtype=float)
        else:
            xyb = np.array([(*tuple(v.dxf.location)[:2], v.dxf.bulge) for v in e.vertices], dtype=float)
        x, y, bulge = xyb.T
        dx, dy = np.roll(x, -1) - x, np.roll(y, -1) - y
        polygon = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
        theta = 4 * np.arctan(bulge[bulge != 0])
        radius2 = (dx**2 + dy**2)[bulge != 0] / (4 * np.sin(theta / 2) ** 2)
        rings.append((xyb[:, :2], abs(polygon + float(np.sum((theta - np.sin(theta)) * radius2 / 2)))))
    return rings


def test_a_reader_ignoring_bulges_still_gets_every_outline(built):
    """Every closed ring's vertices alone enclose its area (with its arcs, in closed form) within
    0.5 % — no bore or pitch circle comes out a triangle — and every part's cut rings, read that
    way, enclose its designed area within 0.5 %."""
    for profile, name, area, holes, folder in _parts(built):
        doc = read_dxf(folder / f"{name}.dxf")
        cut = _areas_with_arcs(doc, "CUT", "LWPOLYLINE")
        assert len(cut) == 1 + holes, (profile, name)
        for vertices, exact in cut + _areas_with_arcs(doc, "MARK", "POLYLINE"):
            assert shapely.Polygon(vertices).area == pytest.approx(exact, rel=SHARE), (profile, name)
        chords = _xor_area([v for v, _ in cut])
        _record("vertices only", profile, name, chords.area, area)
        assert chords.area == pytest.approx(area, rel=SHARE), (profile, name)
        assert _region_shape(chords) == (1, holes)


def test_engraving_is_written_where_openscad_cannot_mistake_it_for_the_part(built):
    """Only CUT holds region-forming entities (LWPOLYLINE, or LINE/ARC); MARK only POLYLINE —
    and no engraved stroke runs along a cut path (a laser would engrave, then cut, one line)."""
    for path in sorted(built.glob("*/*.dxf")):
        doc = read_dxf(path)
        kinds = {(e.dxf.layer, e.dxftype()) for e in doc.modelspace()}
        assert {k for layer, k in kinds if layer == "MARK"} <= {"POLYLINE"}, path
        assert {k for layer, k in kinds if layer == "CUT"} <= {"LWPOLYLINE", "LINE", "ARC"}, path
        # every engraved stroke (open: the dashes, the crosses; or closed) leaves the cut paths
        # somewhere by more than 0.01 mm — the cut rings' vertices alone, whose chords lie within
        # the tolerance of their arcs, far under that
        space = doc.modelspace()
        rings = [np.array(e.get_points("xy")) for e in space.query("LWPOLYLINE") if e.dxf.layer == "CUT"]
        edges = np.concatenate([np.stack([v, np.roll(v, -1, 0)], 1) for v in rings] or [np.empty((0, 2, 2))])
        edges = shapely.STRtree(shapely.linestrings(edges))

        def leaves(vertices) -> bool:  # a vertex with no cut edge within 0.01 mm
            xy = np.array([tuple(v.dxf.location)[:2] for v in vertices])
            return len(np.unique(edges.query(shapely.points(xy), predicate="dwithin", distance=0.01)[0])) < len(xy)

        strokes = [e.vertices for e in space.query("POLYLINE")]
        assert strokes or "assembly" not in path.stem, path  # (an assembly engraves its pitch curves at least)
        for vs in strokes:  # its ends and middle first: the whole stroke only where those lie on a cut
            assert leaves([vs[0], vs[len(vs) // 2], vs[-1]]) or leaves(vs), (path, vs[0].dxf.location)


# ------------------------------------------------------------------------------------ Inkscape

_DXF_INPUT = Path("/usr/share/inkscape/extensions/dxf_input.py")


def _inkscape_import() -> Path:
    _program("inkscape", "inkscape")
    if not _DXF_INPUT.exists():
        pytest.skip(f"Inkscape's DXF import extension is missing: apt-get install -y inkscape (or {INSTALL})")
    system = subprocess.run(["/usr/bin/python3", "-c", "import lxml, numpy"], capture_output=True)
    if system.returncode != 0:
        pytest.skip(
            f"Inkscape's extensions need python3-lxml and python3-numpy: apt-get install -y "
            f"python3-lxml python3-numpy (or {INSTALL})"
        )
    return _DXF_INPUT


def _svg_layer_rings(svg_text: str, layer: str) -> list[list[tuple[float, float]]]:
    """The closed subpaths of an Inkscape layer, arcs and curves sampled finely (px)."""
    from svgelements import Close, Line, Move
    from svgelements import Path as SvgPath

    rings, points = [], []
    for group in ET.fromstring(svg_text).iter(SVG + "g"):
        if group.get(INK + "label") != layer:
            continue
        assert group.get("transform") is None
        for element in group.iter(SVG + "path"):
            assert element.get("transform") is None
            for seg in SvgPath(element.get("d")):
                if isinstance(seg, Move):
                    if points:
                        rings.append(points)
                    points = [(seg.end.x, seg.end.y)]
                elif isinstance(seg, Close):
                    rings.append(points)
                    points = []
                elif isinstance(seg, Line):
                    points.append((seg.end.x, seg.end.y))
                else:
                    points += [(q[0], q[1]) for q in seg.npoint(np.linspace(0, 1, 65)[1:])]
            if points:
                rings.append(points)
                points = []
    return rings


def test_inkscape_imports_the_dxf_at_the_designed_area(built):
    """Inkscape's DXF import with its defaults (manual scale 1: 1 mm = 96/25.4 px): the CUT
    layer at the designed area, the MARK layer kept apart, and nothing printed — no more
    "$PDMODE is ignored" on every import."""
    script = _inkscape_import()
    px = 96 / 25.4
    for profile, name, area, holes, folder in _parts(built, subset=True):
        run = subprocess.run(
            ["/usr/bin/python3", str(script), str(folder / f"{name}.dxf")],
            capture_output=True,
            text=True,
            timeout=120,
            cwd=script.parent,
            env={"PATH": "/usr/bin:/bin"},
        )
        assert run.returncode == 0 and not run.stderr.strip(), (profile, name, run.stderr)
        region = _xor_area(_svg_layer_rings(run.stdout, "CUT"))
        _record("inkscape", profile, name, region.area / px**2, area)
        assert region.area / px**2 == pytest.approx(area, rel=SHARE), (profile, name)
        assert _region_shape(region) == (1, holes), (profile, name)
        assert _svg_layer_rings(run.stdout, "MARK"), (profile, name)  # the engraving is there too


# ------------------------------------------------------------------------------------ LibreCAD


def _librecad_pdf(librecad: str, dxf: Path, tmp_path: Path, options=("-c", "-s", "1")) -> Path:
    """``librecad dxf2pdf`` writes <name>.pdf beside its input: run it on a copy."""
    work = tmp_path / f"{dxf.parent.name}-{dxf.stem}{'-plain' if not options else ''}"
    work.mkdir()
    shutil.copy(dxf, work / dxf.name)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", HOME=str(tmp_path), XDG_RUNTIME_DIR=str(tmp_path))
    run = subprocess.run(
        [librecad, "dxf2pdf", *options, dxf.name], capture_output=True, text=True, timeout=120, cwd=work, env=env
    )
    pdf = work / f"{dxf.stem}.pdf"
    assert run.returncode == 0 and pdf.exists() and pdf.stat().st_size > 0, run.stdout + run.stderr
    return pdf


def _pdf_stroke_region(pdf: Path, colour: str):
    """The region enclosed by the PDF's strokes of one colour (pdftocairo's SVG of the page),
    mm: strokes noded and polygonised, faces combined even-odd."""
    from shapely.ops import polygonize, unary_union

    svg = pdf.with_suffix(".svg")
    subprocess.run(["pdftocairo", "-svg", str(pdf), str(svg)], check=True, timeout=120)
    lines = []
    pattern = r'<path style="([^"]*)" d="([^"]*)"(?: transform="matrix\(([^)]*)\)")?'
    for style, d, matrix in re.findall(pattern, svg.read_text(encoding="utf-8")):
        if f"stroke:{colour}" not in style:
            continue
        a, b, c, dd, e, f = (float(x) for x in matrix.split(",")) if matrix else (1, 0, 0, 1, 0, 0)
        for sub in re.split(r"(?=M)", d):
            nums = [float(x) for x in re.findall(r"-?[0-9.]+", sub)]
            pts = [(a * x + c * y + e, b * x + dd * y + f) for x, y in zip(nums[0::2], nums[1::2])]
            if len(set(pts)) >= 2:
                lines.append(shapely.LineString(pts))
    faces = polygonize(unary_union(lines))
    return shapely.affinity.scale(_xor_area([list(p.exterior.coords) for p in faces]), 25.4 / 72, 25.4 / 72)


def test_librecad_prints_every_part_at_its_area(built, tmp_path):
    """``librecad dxf2pdf`` runs headless, the page is not blank, and its red CUT strokes
    enclose the designed area (0.05 % over: its 1200 dpi grid)."""
    import shapely.affinity  # noqa: F401 - used by _pdf_stroke_region

    librecad = _program("librecad", "librecad")
    _program("pdftoppm", "poppler-utils")
    for profile, name, area, holes, folder in _parts(built, subset=True):
        pdf = _librecad_pdf(librecad, folder / f"{name}.dxf", tmp_path)
        png = subprocess.run(["pdftoppm", "-r", "20", "-gray", "-singlefile", str(pdf), str(pdf.with_suffix(""))])
        assert png.returncode == 0
        assert _dark_pixels(pdf.with_suffix(".pgm")) > 0, (profile, name)
        region = _pdf_stroke_region(pdf, "rgb(100%,0%,0%)")
        _record("librecad", profile, name, region.area, area)
        assert region.area == pytest.approx(area, rel=SHARE), (profile, name)
        assert _region_shape(region) == (1, holes), (profile, name)


def test_librecad_prints_a_part_with_no_options(built, tmp_path):
    """``librecad dxf2pdf`` with no options (as a maker first tries it) prints the whole part at
    1:1 from the DXF's paper settings ($PSVPSCALE, $PINSBASE), not a blank page."""
    import shapely.affinity  # noqa: F401 - used by _pdf_stroke_region

    librecad = _program("librecad", "librecad")
    for profile, name, area, holes, folder in _parts(built, subset=True)[:3]:
        pdf = _librecad_pdf(librecad, folder / f"{name}.dxf", tmp_path, options=())
        region = _pdf_stroke_region(pdf, "rgb(100%,0%,0%)")
        assert region.area == pytest.approx(area, rel=SHARE), (profile, name)
        assert _region_shape(region) == (1, holes), (profile, name)


def _dark_pixels(pgm: Path) -> int:
    from PIL import Image

    with Image.open(pgm) as image:
        return int(np.count_nonzero(np.asarray(image) < 200))


# --------------------------------------------------------------------------------- PrusaSlicer

_REPAIRS = ("open_edges", "degenerate_facets", "edges_fixed", "facets_removed", "facets_reversed", "backwards_edges")


def _meshes(built: Path, *, subset: bool) -> list[tuple[Path, float | None]]:
    rows = []
    for _profile, name, *_, folder in _parts(built, subset=subset):
        report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
        for kind in ("stl", "3mf"):
            rows.append((folder / f"{name}.{kind}", report["files"][f"{name}.{kind}"]["volume"]))
    return rows


def _prusa_info(slicer: str, path: Path) -> list[dict[str, str]]:
    """``prusa-slicer --info``: one block of ``key = value`` lines per object."""
    run = subprocess.run([slicer, "--info", str(path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    blocks = re.split(r"^\[.*\]$", run.stdout, flags=re.M)[1:]
    return [dict(re.findall(r"^(\w+) = +(.*)$", block, re.M)) for block in blocks]


def test_prusaslicer_reads_every_mesh_without_repairs(built):
    """Every part's STL and 3MF, and the plates and assemblies: each object manifold, nothing
    repaired (PrusaSlicer lists open edges, reversed or removed facets when it had to), one
    piece, at the designed volume."""
    slicer = _program("prusa-slicer", "prusa-slicer")
    for path, volume in _meshes(built, subset=not ALL):
        (info,) = _prusa_info(slicer, path)
        assert info["manifold"] == "yes" and not set(info) & set(_REPAIRS), (path, info)
        assert info["number_of_parts"].strip() == "1", path
        assert float(info["volume"]) == pytest.approx(volume, rel=1e-4), path  # float32 vertices
        _record(f"prusa-slicer {path.suffix[1:]}", path.parent.name, path.stem, float(info["volume"]), volume)
    folders = sorted({f for *_, f in _parts(built, subset=not ALL)})
    for path in [folder / name for folder in folders for name in ("plate.3mf", "assembly.3mf")]:
        report = json.loads((path.parent / "report.json").read_text(encoding="utf-8"))
        objects = _prusa_info(slicer, path)
        assert objects and all(o["manifold"] == "yes" and not set(o) & set(_REPAIRS) for o in objects), path
        assert sum(int(o["number_of_facets"]) for o in objects) == report["files"][path.name]["triangles"], path


def test_prusaslicer_slices_an_stl_and_a_3mf(built, tmp_path):
    slicer = _program("prusa-slicer", "prusa-slicer")
    files = (
        [p for p, _ in _meshes(built, subset=True)]
        if ALL
        else [
            built / "roller_body_m3" / "roller.stl",
            built / "rolling_wheel" / "wheel1.3mf",
        ]
    )
    for path in files:
        gcode = tmp_path / f"{path.parent.name}-{path.name}.gcode"
        run = subprocess.run(
            [slicer, "--export-gcode", "-o", str(gcode), str(path)], capture_output=True, text=True, timeout=300
        )
        assert run.returncode == 0 and "Slicing result exported" in run.stdout, run.stdout + run.stderr
        text = gcode.read_text(encoding="utf-8", errors="replace")
        assert re.search(r"^G1 .*E", text, re.M), path  # moves that extrude


# ------------------------------------------------------------------------------------- FreeCAD

FREECAD_SUBSET = {
    ("elliptic_focus", "driver"),  # teeth on a noncircular pitch curve: planes and cylinders
    ("herringbone_elliptic", "driver"),  # twisted teeth: B-spline flanks, a chamfered bore
    ("rolling_wheel", "assembly"),  # an assembly (the smallest)
}
"""What FreeCAD reads by default (a FreeCAD process reads ~1 MB of STEP a second) of what
``built_step`` wrote (the herringbone's only with ``GEARCAD_CONSUMERS=all``, which reads all)."""
FREECAD_SCRIPT = """
import json, sys
import FreeCAD, Import, Part
for path in json.loads(sys.argv[-1]):
    if path.endswith("assembly.step"):
        shape = Part.read(path)
        closed = [s.isValid() and s.isClosed() for s in shape.Solids]
        print("GEARCAD", json.dumps([path, len(closed), shape.isValid(), closed]))
        continue
    doc = FreeCAD.newDocument()
    Import.insert(path, doc.Name)  # File > Import with the default preferences
    found = [o for o in doc.Objects if hasattr(o, "Shape")]
    print("GEARCAD", json.dumps([path, [o.Label for o in found], [len(o.Shape.Solids) for o in found],
          [o.Shape.isValid() and all(s.isClosed() for s in o.Shape.Solids) for o in found]]))
    FreeCAD.closeDocument(doc.Name)
"""


def test_freecad_imports_every_step_part_as_one_valid_solid(request, tmp_path):
    """FreeCAD 0.20's default STEP import (``Import.insert``, what File ▸ Import runs) reads each
    part's file as one object of the part's name holding one valid closed solid; each assembly
    (read by ``Part.read``: FreeCAD 0.20.2's ``Import.insert`` ends in a segmentation fault on
    every STEP assembly in FreeCADCmd, its own exported App::Part too) as one valid closed
    solid per placed part.  The files are tests/conftest.py's ``built_step`` (0.01 mm): by
    default :data:`FREECAD_SUBSET`."""
    freecad = shutil.which("freecadcmd") or shutil.which("FreeCADCmd")
    if freecad is None:
        pytest.skip(f"FreeCAD is not installed: apt-get install -y freecad (or {INSTALL})")
    built_step = request.getfixturevalue("built_step")
    paths, placed = [], {}
    for folder in sorted(p for p in built_step.iterdir() if p.is_dir()):
        report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
        for name in [p["name"] for p in report["parts"]] + ["assembly"]:
            if ALL or (folder.name, name) in FREECAD_SUBSET:
                paths.append(str(folder / f"{name}.step"))
        placed[str(folder / "assembly.step")] = report["files"]["assembly.step"]["components"]
    script = tmp_path / "freecad_step.py"
    script.write_text(FREECAD_SCRIPT, encoding="utf-8")
    run = subprocess.run(
        [freecad, str(script), json.dumps(paths)], capture_output=True, text=True, timeout=600, cwd=tmp_path
    )
    lines = [json.loads(line[len("GEARCAD ") :]) for line in run.stdout.splitlines() if line.startswith("GEARCAD ")]
    assert [line[0] for line in lines] == paths, run.stdout[-2000:] + run.stderr[-2000:]
    for path, *read in lines:
        if path in placed:
            count, valid, closed = read
            assert count == placed[path] and valid and all(closed), (path, read)
        else:
            labels, solids, valid = read
            assert labels == [Path(path).stem] and solids == [1] and all(valid), (path, read)


# -------------------------------------------------------------------------------------- lib3mf


class _Lib3mf:
    """Debian's lib3mf1 through its C interface (NMR_DLLInterfaces.h, version 1.8)."""

    def __init__(self):
        name = ctypes.util.find_library("3MF") or "lib3MF.so.1"
        try:
            self.lib = ctypes.CDLL(name)
        except OSError:
            pytest.skip(f"lib3mf is not installed: apt-get install -y lib3mf1 (or {INSTALL})")

    def _ok(self, result: int, what: str, instance=None) -> None:
        if result != 0:
            code, message = ctypes.c_uint(), ctypes.c_char_p()
            if instance is not None:
                self.lib.lib3mf_getlasterror(instance, ctypes.byref(code), ctypes.byref(message))
            raise AssertionError(f"lib3mf {what}: {result & 0xFFFFFFFF:#x} {message.value!r}")

    def read(self, path: Path) -> tuple[list[str], list[tuple[bool, int]], int]:
        """Warnings of a strict read, (manifold and oriented, triangles) per mesh object, and the
        triangles of every build item (a mesh placed three times counts three times)."""
        # lib3mf sets the process's C locale to "C" (ASCII), which would make every later
        # text read of this process ASCII: put back what Python chose at start-up
        saved = locale.setlocale(locale.LC_ALL)
        try:
            return self._read(path)
        finally:
            locale.setlocale(locale.LC_ALL, saved)

    def _read(self, path: Path) -> tuple[list[str], list[tuple[bool, int]], int]:
        lib, ref, ptr = self.lib, ctypes.byref, ctypes.c_void_p
        model, reader, it, items = ptr(), ptr(), ptr(), ptr()
        self._ok(lib.lib3mf_createmodel(ref(model)), "createmodel")
        try:
            self._ok(lib.lib3mf_model_queryreader(model, b"3mf", ref(reader)), "queryreader")
            self._ok(lib.lib3mf_reader_setstrictmodeactive(reader, 1), "strict mode")
            self._ok(lib.lib3mf_reader_readfromfileutf8(reader, str(path).encode()), f"read {path}", reader)
            count = ctypes.c_uint()
            self._ok(lib.lib3mf_reader_getwarningcount(reader, ref(count)), "warnings")
            warnings = []
            for k in range(count.value):
                code, need, text = ctypes.c_uint(), ctypes.c_uint(), ctypes.create_string_buffer(1024)
                lib.lib3mf_reader_getwarningutf8(reader, k, ref(code), text, 1024, ref(need))
                warnings.append(f"{code.value}: {text.value.decode(errors='replace')}")
            meshes = []
            self._ok(lib.lib3mf_model_getmeshobjects(model, ref(it)), "mesh objects")
            more = ctypes.c_int()
            while True:
                self._ok(lib.lib3mf_resourceiterator_movenext(it, ref(more)), "next")
                if not more.value:
                    break
                mesh, manifold, triangles = ptr(), ctypes.c_int(), ctypes.c_uint()
                self._ok(lib.lib3mf_resourceiterator_getcurrent(it, ref(mesh)), "current")
                self._ok(lib.lib3mf_meshobject_ismanifoldandoriented(mesh, ref(manifold)), "manifold")
                self._ok(lib.lib3mf_meshobject_gettrianglecount(mesh, ref(triangles)), "triangles")
                lib.lib3mf_release(mesh)
                meshes.append((bool(manifold.value), triangles.value))
            placed = 0
            self._ok(lib.lib3mf_model_getbuilditems(model, ref(items)), "build items")
            while True:
                self._ok(lib.lib3mf_builditemiterator_movenext(items, ref(more)), "next item")
                if not more.value:
                    break
                item, thing, is_mesh, triangles = ptr(), ptr(), ctypes.c_int(), ctypes.c_uint()
                self._ok(lib.lib3mf_builditemiterator_getcurrent(items, ref(item)), "current item")
                self._ok(lib.lib3mf_builditem_getobjectresource(item, ref(thing)), "item object")
                self._ok(lib.lib3mf_object_ismeshobject(thing, ref(is_mesh)), "is mesh")
                assert is_mesh.value, f"{path}: a build item that is not a mesh"
                self._ok(lib.lib3mf_meshobject_gettrianglecount(thing, ref(triangles)), "item triangles")
                lib.lib3mf_release(thing)
                lib.lib3mf_release(item)
                placed += triangles.value
            return warnings, meshes, placed
        finally:
            for handle in (items, it, reader, model):
                if handle.value:
                    lib.lib3mf_release(handle)


def test_lib3mf_validates_every_3mf(built):
    lib3mf = _Lib3mf()
    files = sorted(built.glob("*/*.3mf"))
    assert files
    for path in files:
        report = json.loads((path.parent / "report.json").read_text(encoding="utf-8"))
        warnings, meshes, placed = lib3mf.read(path)
        assert warnings == [] and meshes and all(ok for ok, _ in meshes), (path, warnings, meshes)
        assert placed == report["files"][path.name]["triangles"], path
    with pytest.raises(AssertionError, match="lib3mf read"):
        lib3mf.read(Path(__file__))  # and it does refuse what is not a 3MF


# --------------------------------------------------------------------------- reproducible bytes

_BUILD = """
import sys
from pathlib import Path
from gearcad.cli import main
sys.exit(main(["build", *sys.argv[2:], "--out", sys.argv[1]]))
"""


def test_every_file_is_the_same_whatever_the_hash_seed(tmp_path, built):
    """A process with another hash seed writes every file of a profile byte for byte as the
    suite's own build did (ezdxf once ordered the DXF CLASSES section by a set): the same
    design built twice, in two processes, at two seeds."""
    root = Path(__file__).resolve().parent.parent
    profiles = sorted((root / "profiles").glob("*.toml")) if ALL else [root / "profiles" / "elliptic_focus.toml"]
    seed = "5" if os.environ.get("PYTHONHASHSEED") == "4" else "4"
    env = dict(os.environ, PYTHONHASHSEED=seed, PYTHONPATH=str(root))
    command = [sys.executable, "-c", _BUILD, str(tmp_path), *map(str, profiles)]
    run = subprocess.run(command, env=env, cwd=root, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=900)
    assert run.returncode == 0, run.stderr.decode()
    for profile in profiles:
        here, there = tmp_path / profile.stem, built / profile.stem
        first = sorted(p.relative_to(here) for p in here.rglob("*") if p.is_file())
        assert first == sorted(p.relative_to(there) for p in there.rglob("*") if p.is_file())
        assert {".dxf", ".svg", ".stl", ".3mf", ".json", ".png"} <= {p.suffix for p in first}
        differ = [str(p) for p in first if (here / p).read_bytes() != (there / p).read_bytes()]
        assert differ == [], profile.stem
