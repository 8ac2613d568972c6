"""What makers open first (issue 24): DXF views and paper settings, the sheet's page and names,
the pitch curve engraved so that no filling program engraves a region, the print plate apart
by its twisted footprints with room for a skirt, pilot holes and the assembly texts explained."""

import itertools
import json
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
import trimesh

from gearcad.export.dxf import PAPER_MARGIN_MM
from gearcad.export.sheet import NAME_HEIGHT_MM, name_strokes
from gearcad.mechanisms.layouts import SKIRT_MM

from .conftest import read_dxf
from .test_html import CHROMIUM


def _report(built, name):
    return json.loads((built / name / "report.json").read_text(encoding="utf-8"))


@pytest.mark.parametrize("profile", ["elliptic_focus", "walker", "roller_body_m3"])
def test_dxf_opens_on_the_part_and_prints_it_at_full_size(built, profile):
    for path in sorted((built / profile).glob("*.dxf")):
        doc = read_dxf(path)
        (x0, y0, _), (x1, y1, _) = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
        (view,) = doc.viewports.get("*Active")
        cx, cy = view.dxf.center.x, view.dxf.center.y
        assert (cx, cy) == pytest.approx(((x0 + x1) / 2, (y0 + y1) / 2), abs=1e-9), path.name
        assert view.dxf.height >= max(x1 - x0, y1 - y0), path.name  # the whole drawing in any wide window
        assert doc.header["$PSVPSCALE"] == 1.0
        assert tuple(doc.header["$PINSBASE"])[:2] == pytest.approx((PAPER_MARGIN_MM - x0, PAPER_MARGIN_MM - y0))


def test_every_engraved_path_is_open_so_a_fill_cannot_engrave_a_region(built):
    """A closed pitch curve crossing the teeth, filled, engraves −68 % … +309 % of the wrong area;
    dashed it cannot be filled. The dashes still follow the pitch curve: 3/4 of its length."""
    for profile in ("elliptic_focus", "walker", "spur_pair"):
        report = _report(built, profile)
        for gear in report["gears"]:
            doc = read_dxf(built / profile / f"{gear['name']}.dxf")
            marks = doc.modelspace().query(f'POLYLINE[layer=="{report["output"]["layers"]["mark"]}"]')
            assert marks and not any(e.is_closed for e in marks), (profile, gear["name"])
            length = 0.0
            for e in marks:
                pts = np.array([(p.x, p.y) for p in ezdxf.path.make_path(e).flattening(0.001)])
                length += np.hypot(*np.diff(pts, axis=0).T).sum()
            cross = 4 * next(p["pivot"]["cross"] for p in report["parts"] if p["name"] == gear["name"])
            m = gear["teeth"]["module"]  # the assembly dot: a diamond of half-diagonal 0.25·m, drawn round
            dot = 4 * np.sqrt(2) * 0.25 * m if gear["teeth"] else 0.0
            assert length - cross - dot == pytest.approx(0.75 * gear["perimeter"], rel=2e-3), (profile, gear["name"])
    text = (built / "elliptic_focus" / "driver.svg").read_text(encoding="utf-8")
    marks = text.split('<g id="mark"')[1].split("</g>")[0]
    assert "Z" not in marks  # no closed path among the marks


def test_the_sheet_svg_is_the_sheet_and_previews_with_visible_lines(built):
    report = _report(built, "elliptic_centre")
    text = (built / "elliptic_centre" / "sheet.svg").read_text(encoding="utf-8")
    w, h = (600, 400)  # output.sheet's default, which the profile keeps
    assert f'width="{w}mm" height="{h}mm" viewBox="0 -{h} {w} {h}"' in text
    assert "@media screen" in text and "vector-effect: non-scaling-stroke" in text
    assert set(re.findall(r'stroke-width="([^"]+)"', text)) == {"0.01"}  # the laser's hairline kept
    assert report["parts"]


def test_the_sheet_names_each_part_inside_it(built):
    """Names are engraved in outline letters inside each part (the centre ellipse's two gears look
    alike): extra MARK paths in sheet.dxf, each inside one part, none over the pivot."""
    doc = read_dxf(built / "elliptic_centre" / "sheet.dxf")
    cut = [
        np.array([(x, y) for x, y, *_ in e.get_points()]) for e in doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    ]
    parts = [shapely.Polygon(c) for c in cut if shapely.Polygon(c).area > 100]
    assert len(parts) == 2
    glyphs = [e for e in doc.modelspace().query('POLYLINE[layer=="MARK"]') if e.is_closed or len(e) > 8]
    inside = [
        sum(p.contains(shapely.Point(g.vertices[0].dxf.location.x, g.vertices[0].dxf.location.y)) for g in glyphs)
        for p in parts
    ]
    assert all(n >= 6 for n in inside)  # "driver" and "follower": at least one outline per letter


def test_names_take_what_room_there_is():
    room = shapely.box(0, 0, 60, 20)
    strokes = name_strokes("follower", room)
    allpts = np.vstack(strokes)
    assert room.contains(shapely.MultiPoint(allpts))
    assert NAME_HEIGHT_MM[0] <= np.ptp(allpts[:, 1]) <= 1.3 * NAME_HEIGHT_MM[1]
    assert name_strokes("follower", shapely.box(0, 0, 3, 3)) == []  # no legible size fits


def test_the_herringbone_plate_keeps_gap_and_skirt_with_twisted_solids(built):
    """Boxes of the placed solids as written (twisted teeth reach past the base outline): at
    least output.gap apart, and SKIRT_MM from the bed's edges."""
    scene = trimesh.load(built / "herringbone_elliptic" / "plate.3mf")
    boxes = []
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        xyz = trimesh.transform_points(scene.geometry[name].vertices, transform)
        boxes.append((*xyz[:, :2].min(axis=0), *xyz[:, :2].max(axis=0)))
    bed_w, bed_h = 250.0, 210.0  # output.bed's default
    gap = 3.0  # output.gap's default
    for x0, y0, x1, y1 in boxes:
        assert min(x0, y0, bed_w - x1, bed_h - y1) >= SKIRT_MM - 1e-6
    for a, b in itertools.combinations(boxes, 2):
        assert shapely.box(*a).distance(shapely.box(*b)) >= gap - 1e-6


def test_rollers_get_a_pilot_and_the_page_says_whose_the_bore_is(built):
    report = _report(built, "roller_body_m3")
    pivots = {p["name"]: p["pivot"] for p in report["parts"]}
    assert pivots["body"]["marked_by"] == "bore" and pivots["roller"]["marked_by"] == "pilot"
    page = (built / "roller_body_m3" / "index.html").read_text(encoding="utf-8")
    assert "no bore given" not in page and "bore.diameter is body&#x27;s shaft" in page


def test_assembly_captions_say_what_touches(built):
    walker = (built / "walker" / "index.html").read_text(encoding="utf-8")
    assert "plane of its own" in walker and "mechanism does not move" not in walker
    wheel = (built / "rolling_wheel" / "index.html").read_text(encoding="utf-8")
    assert "not touching" in wheel and "they touch" not in wheel
    assert "meshing parts touch" in (built / "spur_pair" / "index.html").read_text(encoding="utf-8")


def test_a_normal_module_says_why_the_count_differs(built):
    """β = 25°, module 1: the count follows the transverse module 1/cos β (issue 24, item 15)."""
    report = _report(built, "herringbone_elliptic")
    (note,) = [w for w in report["warnings"] if w["code"] == "teeth-fit"]
    z = report["gears"][0]["teeth"]["count"]
    assert "normal module" in note["message"] and f"{1 / np.cos(np.radians(25)):.4f}" in note["message"]
    assert f"has {z} teeth" in note["message"] and "teeth.count" in note["message"]


def test_the_walker_plates_fit_a_common_bed_and_its_leg_is_named(built):
    """Issue 37 item 13: the walker's parts on the default 250 × 210 mm bed; the shoe part (385 × 332 mm)
    is on no plate and a ``bed`` finding names it with the bed it needs."""
    report = _report(built, "walker")
    beds = [f for f in report["warnings"] if f["code"] == "bed"]
    assert [f["where"] for f in beds] == ["shoe"] and "output.bed=[" in beds[0]["message"]
    for path in sorted((built / "walker").glob("plate*.3mf")):
        scene = trimesh.load(path)
        (x0, y0, _), (x1, y1, _) = scene.bounds
        assert x0 >= 0 and y0 >= 0 and x1 <= 250 and y1 <= 210, path.name
        assert "shoe" not in scene.geometry


@pytest.mark.skipif(
    not Path(CHROMIUM).is_file(), reason="no chromium: install it with `apt-get install -y chromium` (Debian)"
)
def test_a_browser_shows_the_sheet_svgs_parts_on_its_first_screen(built, tmp_path):
    """Issue 37 item 12 in a real browser: chromium opens the walker's sheet.svg (the largest
    sheet, parts at their real size) at 1000 × 700 px and its first screen shows cut lines
    (#ff0000) spread over a part's size, not a blank page (in place of reading the SVG's paths
    with svgelements, which took 8 s)."""
    from PIL import Image

    from .test_html import chromium

    png = tmp_path / "sheet.png"
    chromium((built / "walker" / "sheet.svg").as_uri(), png, tmp_path, size=(1000, 700))
    pixels = np.asarray(Image.open(png).convert("RGB")).astype(int)
    red = (pixels[..., 0] > 180) & (pixels[..., 1] < 110) & (pixels[..., 2] < 110)
    rows, cols = np.nonzero(red)
    assert len(rows) > 300, "no cut line on the first screen of sheet.svg"
    assert rows.max() - rows.min() > 100 and cols.max() - cols.min() > 100  # a part, not a stray mark
