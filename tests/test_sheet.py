"""Cutting sheets and print plates: every placed part laid out apart, on the sheet or bed, read back."""

import itertools
import math
import tomllib
import zipfile
from collections import Counter
from dataclasses import replace
from functools import reduce

import ezdxf
import numpy as np
import pytest
import shapely
import trimesh
from svgelements import SVG, Group
from svgelements import Path as SvgPath

import gearcad
from gearcad.errors import DesignError
from gearcad.export.dxf import write_dxf
from gearcad.export.mesh import SolidItem, extrude
from gearcad.export.plate import write_plate
from gearcad.export.sheet import sheet_drawing
from gearcad.export.svg import write_svg
from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.outline import rotate
from gearcad.mechanisms import Placement, layouts
from gearcad.mechanisms.layouts import pack

from .conftest import ROOT

FLAT = 1e-3  # mm: arcs flattened this finely when measured (areas to ~1e-5 relative)


def rollers(**output):
    """The body on three rollers, smooth (no teeth) and coarse, so it designs in a fraction of a
    second: one body with a bore, one roller part the assembly places three times."""
    raw = tomllib.loads((ROOT / "profiles" / "roller_body_m3.toml").read_text(encoding="utf-8"))
    del raw["teeth"]
    raw["output"].update(charts=False, animation=False, tolerance=0.02, **output)
    return gearcad.design(gearcad.parse_profile(raw))


@pytest.fixture(scope="module")
def design():
    return rollers()


def resized(design, **output):
    """The same design with other [output] sizes (the layouts read nothing else of the profile)."""
    params = design.params
    return replace(design, params=params.model_copy(update={"output": params.output.model_copy(update=output)}))


def sheet_layout(design):
    return layouts.sheet_layout(design.parts(), design.placements, design.params.output)


def plate_layout(design):
    return layouts.plate_layout(design.parts(), design.placements, design.params.output)


def placed_polygon(part, placement: Placement) -> shapely.Polygon:
    """The part's cut rings (arcs flattened) turned and moved as the sheet places them."""
    rings = [rotate(arc_points(r, FLAT), placement.angle) + np.asarray(placement.offset) for r in part.cut]
    return shapely.Polygon(rings[0], rings[1:])


def even_odd_area(rings: list[np.ndarray]) -> float:
    """Area inside an odd number of the rings: parts and their holes, however each is oriented."""
    return reduce(lambda a, b: a.symmetric_difference(b), (shapely.Polygon(r) for r in rings)).area


def designed_area(design) -> float:
    """Every part's designed area, as often as the assembly places it."""
    areas = {p.name: p.outline.area for p in design.parts()}
    return sum(areas[pl.part] for pl in design.placements)


# ---- the packer --------------------------------------------------------------------------------


def test_pack_fills_a_square_exactly_and_refuses_one_more():
    assert pack([(1.0, 1.0)] * 4, 2.0, 2.0) == [
        (0.0, 0.0, False),
        (1.0, 0.0, False),
        (0.0, 1.0, False),
        (1.0, 1.0, False),
    ]
    assert pack([(1.0, 1.0)] * 5, 2.0, 2.0) is None


def test_pack_turns_what_fits_only_turned():
    # a 3 × 1 strip fits a 1 × 3 region only standing up; two 2 × 1 halves of a 2 × 2 square lie flat
    assert pack([(3.0, 1.0)], 1.0, 3.0) == [(0.0, 0.0, True)]
    assert pack([(1.0, 2.0), (1.0, 2.0)], 2.0, 2.0) == [(0.0, 0.0, True), (0.0, 1.0, True)]


# ---- sheets ------------------------------------------------------------------------------------


def test_sheet_places_every_part_as_often_as_the_assembly(design):
    layout = sheet_layout(design)
    assert Counter(pl.part for pl in layout) == Counter(pl.part for pl in design.placements) == {"body": 1, "roller": 3}


def test_sheet_parts_are_apart_and_on_the_sheet(design):
    out = design.params.output
    parts = {p.name: p for p in design.parts()}
    polygons = [placed_polygon(parts[pl.part], pl) for pl in sheet_layout(design)]
    assert all(p.is_valid and p.area > 0 for p in polygons)
    for a, b in itertools.combinations(polygons, 2):
        assert a.distance(b) >= out.gap - 1e-6
    w, h = out.sheet
    sheet = shapely.box(out.gap, out.gap, w - out.gap, h - out.gap)
    assert all(sheet.buffer(1e-6).contains(p) for p in polygons)
    # and nothing is lost on the way: the placed polygons have the designed areas
    assert sum(p.area for p in polygons) == pytest.approx(designed_area(design), rel=1e-3)


def test_sheet_too_small_for_one_part_is_refused_on_one_line(design):
    with pytest.raises(DesignError) as err:
        sheet_layout(resized(design, sheet=(120.0, 120.0)))
    text = str(err.value)
    assert "\n" not in text and "output.sheet = [120, 120] mm" in text and "body" in text and "even alone" in text


def test_sheet_too_small_for_all_parts_names_a_size_that_takes_them(design):
    # the body (its box about 180 × 163 mm, 186 × 169 with the margins) fits a 188 mm square, and so
    # does each roller (20 mm), but no roller fits beside or above the body; the size the message
    # names must take them all
    for part in design.parts():
        assert sheet_layout(replace(design, placements=(Placement(part.name),)))  # alone, each fits
    with pytest.raises(DesignError) as err:
        sheet_layout(resized(design, sheet=(188.0, 188.0)))
    text = str(err.value)
    assert "\n" not in text and text.startswith("output.sheet = [188, 188] mm") and "body, roller ×3" in text
    w, h = (float(v) for v in text.split("a sheet of ")[1].split(" mm")[0].split(" × "))
    assert len(sheet_layout(resized(design, sheet=(w, h)))) == 4


def cut_rings_from_dxf(path, layer: str) -> list[np.ndarray]:
    doc = ezdxf.readfile(path)
    rings = []
    for e in doc.modelspace().query(f'LWPOLYLINE POLYLINE CIRCLE[layer=="{layer}"]'):
        points = np.array([(v.x, v.y) for v in ezdxf.path.make_path(e).flattening(FLAT)])
        rings.append(points)
    return rings


def cut_rings_from_svg(path) -> list[np.ndarray]:
    svg = SVG.parse(str(path), reify=False)
    (cut,) = [g for g in svg.elements() if isinstance(g, Group) and g.id == "cut"]
    rings = []
    for element in cut.select():
        if isinstance(element, SvgPath):
            n = max(400, int(element.length() / FLAT**0.5))  # chord error ~ (length/n)²/(8r)
            pts = element.npoint(np.linspace(0, 1, n, endpoint=False))
            rings.append(np.column_stack([pts[:, 0], -pts[:, 1]]))  # back to y up
    return rings


def test_sheet_files_read_back_to_the_designed_areas(design, tmp_path):
    out = design.params.output
    drawing = sheet_drawing(design)
    write_dxf(tmp_path / "sheet.dxf", drawing, flavour=out.dxf)
    write_svg(tmp_path / "sheet.svg", drawing, cut_layer=out.cut_layer, mark_layer=out.mark_layer, title="sheet")
    expected = designed_area(design)  # the body with its bore, and three rollers
    # the rollers are circles of the profile's radius, 0.1 R with R = 100 mm, with a 1 mm pilot hole
    assert design.part("roller").outline.area == pytest.approx(math.pi * (10.0**2 - 0.5**2), rel=1e-3)
    from_dxf = cut_rings_from_dxf(tmp_path / "sheet.dxf", out.cut_layer)
    from_svg = cut_rings_from_svg(tmp_path / "sheet.svg")
    assert len(from_dxf) == len(from_svg) == 8  # body, its bore, three rollers and their pilot holes
    assert even_odd_area(from_dxf) == pytest.approx(expected, rel=0.005)
    assert even_odd_area(from_svg) == pytest.approx(expected, rel=0.005)


# ---- print plates ------------------------------------------------------------------------------


def test_plate_read_back_places_every_part_on_the_bed_apart(design, tmp_path):
    out = design.params.output
    solids = {p.name: extrude(p.outline, out.thickness, name=p.name) for p in design.parts()}
    path = tmp_path / "plate.3mf"
    assert len(design.plates) == 1 and len(design.plate) == len(design.placements)  # all on the default bed
    items = [SolidItem(solids[pl.part], pl.angle, (*pl.offset, 0.0)) for pl in design.plate]
    triangles = write_plate(path, design, items)
    assert triangles == sum(solids[pl.part].triangle_count for pl in design.placements)
    scene = trimesh.load(path)
    placed = []
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        placed.append((name, scene.geometry[name].copy().apply_transform(transform)))
    assert Counter(name for name, _ in placed) == Counter(pl.part for pl in design.placements)
    bed_w, bed_h = out.bed
    boxes = []
    for name, mesh in placed:
        (x0, y0, z0), (x1, y1, z1) = mesh.bounds
        assert z0 == pytest.approx(0.0, abs=1e-9) and z1 == pytest.approx(out.thickness, abs=1e-6)
        assert out.gap - 1e-6 <= x0 and x1 <= bed_w - out.gap + 1e-6
        assert out.gap - 1e-6 <= y0 and y1 <= bed_h - out.gap + 1e-6
        assert mesh.volume == pytest.approx(solids[name].volume, rel=1e-6)
        boxes.append(shapely.box(x0, y0, x1, y1))
    for a, b in itertools.combinations(boxes, 2):
        assert a.distance(b) >= out.gap - 1e-6
    with zipfile.ZipFile(path) as z:
        model = z.read("3D/3dmodel.model").decode()
    assert model.count("<object ") == 2 and model.count("<item ") == 4  # one roller object, three items
    assert "--dont-arrange" in model


def _footprints(design, layout) -> list[shapely.Polygon]:
    """Each placed part's outline as a polygon on the bed (independent of the layout's boxes)."""
    parts = {p.name: p for p in design.parts()}
    return [placed_polygon(parts[pl.part], pl) for pl in layout]


def test_a_small_bed_takes_the_parts_on_several_plates(design):
    """Issue 37 item 13: parts that do not fit one bed go on more plates, each on the bed."""
    body = layouts.footprint_box(max(design.parts(), key=lambda p: p.outline.area))
    side = max(body.width, body.height) + 2 * layouts.SKIRT_MM + 1.0  # the body alone, no roller beside it
    small = resized(design, bed=(side, side))
    plates = plate_layout(small)
    assert len(plates.plates) > 1 and plates.too_large == ()
    # every placement on exactly one plate
    assert Counter(pl.part for plate in plates.plates for pl in plate) == Counter(pl.part for pl in design.placements)
    gap, skirt = design.params.output.gap, layouts.SKIRT_MM
    tol = design.params.output.tolerance  # a written path strays from its outline by up to this
    for plate in plates.plates:
        shapes = _footprints(design, plate)
        for shape in shapes:
            x0, y0, x1, y1 = shape.bounds
            assert min(x0, y0) >= max(gap, skirt) - tol and x1 <= side - skirt + tol and y1 <= side - skirt + tol
        for a, b in itertools.combinations(shapes, 2):
            assert a.distance(b) >= gap - 2 * tol
    # largest first: the first plate holds the largest part
    largest = max(design.parts(), key=lambda p: p.outline.area).name
    assert largest in {pl.part for pl in plates.plates[0]}


def test_a_part_larger_than_the_bed_is_named_with_the_bed_it_needs(design):
    body = max(design.parts(), key=lambda p: p.outline.area)
    x0, y0, x1, y1 = shapely.Polygon(body.outline.outer).bounds
    tiny = resized(design, bed=(60.0, 60.0))
    plates = plate_layout(tiny)
    left = {b.part for b in plates.too_large}
    assert body.name in left and all(body.name not in {pl.part for pl in p} for p in plates.plates)
    need = plates.needs(next(b for b in plates.too_large if b.part == body.name))
    # the bed it needs is larger than the part with its skirt, and takes it alone
    assert need[0] * need[1] >= (x1 - x0 + 2 * layouts.SKIRT_MM) * (y1 - y0 + 2 * layouts.SKIRT_MM) * 0.5
    again = layouts.plate_layout(
        [body], [Placement(body.name, 0.0, (0.0, 0.0))], tiny.params.output.model_copy(update={"bed": need})
    )
    assert again.too_large == () and len(again.plates) == 1
