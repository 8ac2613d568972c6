"""The calibration coupon (issue 20, deliverable 5): read back from the files it writes.

Expected values are independent of the code under test: areas from the first-order offset law
(A(d) = A + P·d + π·d² for a region whose boundary turns once, |error| ≤ π·d² for the
corners), engraved values from matplotlib's glyphs, watertightness from trimesh."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from matplotlib.textpath import TextPath

import gearcad
from gearcad.cli import main
from gearcad.fitting.coupon import STEPS, coupon_data

from .conftest import read_dxf

SPUR = "profiles/spur_pair.toml"
COARSE = ["output.tolerance=0.01", "output.charts=false", "output.animation=false"]
"""At 0.01 mm without chart data or animation: the coupon reads the parts and the play, not these."""


@pytest.fixture(scope="module")
def laser(tmp_path_factory):
    """The spur pair's coupon under a laser (kerf 0.2), written by the API from its design (the
    command line's run is the same call: see the refusal test)."""
    out = tmp_path_factory.mktemp("coupon") / "out"
    made = gearcad.design(gearcad.load_profile(SPUR, ['process.kind="laser"', *COARSE]))
    assert gearcad.coupon(made, out) == (out / "spur_pair-coupon").resolve()
    return out, coupon_data(made), made.parts()


@pytest.fixture(scope="module")
def printed():
    """The centre ellipses' coupon for a printer: two places (tight, loose) of a noncircular pair."""
    params = gearcad.load_profile("profiles/elliptic_centre.toml", ['process.kind="fdm"', *COARSE])
    return coupon_data(gearcad.design(params))


def _cut_polygons(path) -> list[shapely.Polygon]:
    """The CUT layer's closed rings read back, holes put into the ring that holds them."""
    doc = read_dxf(path)  # read once: both helpers only look
    rings = [
        shapely.Polygon([p[:2] for p in e.get_points("xy")])
        for e in doc.modelspace().query("LWPOLYLINE")
        if e.dxf.layer == "CUT"
    ]
    outers = [r for r in rings if not any(o is not r and o.contains(r) for o in rings)]
    return [shapely.Polygon(o.exterior, [h.exterior for h in rings if h is not o and o.contains(h)]) for o in outers]


def _mark_strokes(path) -> list[np.ndarray]:
    doc = read_dxf(path)  # read once: both helpers only look
    return [
        np.array([tuple(v.dxf.location)[:2] for v in e.vertices])
        for e in doc.modelspace().query("POLYLINE")
        if e.dxf.layer == "MARK"
    ]


def test_the_laser_coupon_as_written(laser):
    """One test for the laser coupon's files, so that its build runs once (not once per worker)."""
    _folder_of_four_files(*laser)
    _cut_rings_are_simple_and_offset_by_half_each_kerf(*laser)
    _steps_differ_by_their_kerf(*laser)
    _each_sector_carries_its_value_on_mark(*laser)
    _plate_is_watertight_with_the_paths_volume(*laser)


def _folder_of_four_files(out, data, parts):
    assert sorted(p.name for p in out.iterdir()) == ["spur_pair-coupon"]
    assert sorted(p.name for p in (out / "spur_pair-coupon").iterdir()) == [
        "coupon.3mf",
        "coupon.dxf",
        "coupon.svg",
        "coupon.txt",
    ]
    text = (out / "spur_pair-coupon" / "coupon.txt").read_text(encoding="utf-8")
    assert "set process.kerf = " in text and "0.10, 0.15, 0.20, 0.25, 0.30 mm" in text
    # a circle pair's play is the same all round: one place, five steps of two gears
    assert [p for p, _ in data.places] == ["any"] and data.steps == (0.1, 0.15, 0.2, 0.25, 0.3)
    assert len(data.pieces) == 10


def _cut_rings_are_simple_and_offset_by_half_each_kerf(out, data, parts):
    read = _cut_polygons(out / "spur_pair-coupon" / "coupon.dxf")
    assert len(read) == len(data.pieces)
    for polygon in read:
        assert polygon.is_valid and polygon.exterior.is_simple and len(polygon.interiors) == 1  # the pilot hole
    for piece in data.pieces:
        placed = shapely.affinity.translate(piece.path, *piece.offset)
        match = max(read, key=lambda r: shapely.intersection(r, placed).area)
        assert match.area == pytest.approx(placed.area, rel=1e-9)
        # the sector is the gear's own outline cut down: it lies inside the turned gear, and most
        # of its edge (the teeth) is the gear's edge
        rings = [np.asarray(r) for r in parts[piece.gear].outline.rings]
        gear = shapely.affinity.rotate(
            shapely.Polygon(rings[0], rings[1:]), piece.turn, origin=(0, 0), use_radians=True
        )
        assert shapely.difference(piece.nominal, gear).area <= 1e-9
        edge = shapely.get_coordinates(piece.nominal.exterior)
        on_gear = shapely.distance(shapely.points(edge), gear.exterior) <= 1e-6
        assert on_gear.mean() > 0.5
        # first order: the beam's centre kerf/2 outside every edge, into every hole
        d = piece.value / 2
        perimeter = piece.nominal.length  # holes shrink as the outline grows: both add area
        expected = piece.nominal.area + perimeter * d
        assert abs(match.area - expected) <= 2 * math.pi * d * d + 1e-3, (piece.name, match.area, expected)


def _steps_differ_by_their_kerf(out, data, parts):
    """Adjacent steps of one sector differ by P·0.025 mm² (0.05 mm of kerf, half each side)."""
    for gear in (0, 1):
        pieces = [p for p in data.pieces if p.gear == gear]
        perimeter = pieces[0].nominal.length
        for a, b in zip(pieces, pieces[1:]):
            assert b.path.area - a.path.area == pytest.approx(perimeter * (b.value - a.value) / 2, rel=0.03)


def _each_sector_carries_its_value_on_mark(out, data, parts):
    strokes = _mark_strokes(out / "spur_pair-coupon" / "coupon.dxf")
    for piece in data.pieces:
        placed = shapely.affinity.translate(piece.nominal, *piece.offset)
        mine = [s for s in strokes if placed.contains(shapely.MultiPoint(s))]
        glyphs = [
            p for p in TextPath((0, 0), f"{piece.value:.2f}", size=1).to_polygons(closed_only=False) if len(p) >= 3
        ]
        assert len(mine) == len(glyphs), piece.name  # "0.15": 0, the dot, 1, 5 → one stroke per outline
        box = np.ptp(np.vstack(mine), axis=0)
        extents = TextPath((0, 0), f"{piece.value:.2f}", size=1).get_extents()
        assert box[0] / box[1] == pytest.approx(extents.width / extents.height, rel=0.05)
    assert sum(len(s) for s in strokes) > 0


def _plate_is_watertight_with_the_paths_volume(out, data, parts):
    import trimesh

    scene = trimesh.load(out / "spur_pair-coupon" / "coupon.3mf")
    meshes = list(scene.geometry.values())
    assert len(meshes) == len(data.pieces)
    assert all(m.is_watertight for m in meshes)
    expected = sum(p.path.area for p in data.pieces) * data.thickness
    assert sum(m.volume for m in meshes) == pytest.approx(expected, rel=1e-6)


def test_a_printer_steps_the_xy_compensation_at_the_tight_and_loose_places(printed):
    data = printed
    assert data.key == "process.xy_compensation"
    assert data.steps == pytest.approx([data.nominal + s for s in STEPS])
    assert [p for p, _ in data.places] == ["tight", "loose"] and len(data.pieces) == 20
    for piece in data.pieces:
        assert piece.path.is_valid and piece.nominal.is_valid
        # a printed edge comes out c outside: the coupon draws it c inside
        c = piece.value
        perimeter = piece.nominal.length  # holes shrink as the outline grows: both add area
        assert abs(piece.path.area - (piece.nominal.area - perimeter * c)) <= 2 * math.pi * c * c + 1e-3
    labels = {p.label for p in data.pieces}
    assert "+0.05 T" in labels and "-0.10 L" in labels


def test_a_mechanism_without_a_pair_is_refused_in_one_line(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["coupon", "profiles/roller_body_m3.toml", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "mechanism = 'roller-body'" in err[0]
    assert not out.exists()
    assert main(["coupon", SPUR, "--out", str(out)]) == 2  # no process: nothing to step
    assert "process.kind = 'none'" in capsys.readouterr().err and not out.exists()
