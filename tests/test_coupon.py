"""The calibration coupon (issue 20, deliverable 5): read back from the files it writes.

Expected values are independent of the code under test: areas from the first-order offset law
(A(d) = A + P·d + π·d² for a region whose boundary turns once, |error| ≤ π·d² for the
corners), engraved values from matplotlib's glyphs, watertightness from trimesh; the jig's hole
spacing against the report's centre distance; each step's play by an independent search on the
sectors read back from the DXF (the follower turned by bisection until it touches), and against
the involute's closed forms (4·offset/cos α per step, the feeler gap play·cos α)."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import shapely
from matplotlib.textpath import TextPath

import gearcad
from gearcad.cli import main
from gearcad.export.coupon import coupon_drawing
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
    return out, coupon_data(made), made.parts(), made.report()


@pytest.fixture(scope="module")
def printed():
    """The centre ellipses' coupon for a printer: two places (tight, loose) of a noncircular pair.
    Its backlash, chamfer and clearance given (near what the fit chooses, 0.325, 0.2, 0.074 mm):
    the coupon steps a pair as designed, and the fit's search, tested on its own, took half the
    fixture's 10 CPU-s."""
    given = ["teeth.backlash=0.35", "output.chamfer=0.2", "teeth.clearance=0.08"]
    params = gearcad.load_profile("profiles/elliptic_centre.toml", ['process.kind="fdm"', *COARSE, *given])
    return coupon_data(gearcad.design(params))


@functools.cache
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


@functools.cache
def _mark_strokes(path) -> list[np.ndarray]:
    doc = read_dxf(path)  # read once: both helpers only look
    return [
        np.array([tuple(v.dxf.location)[:2] for v in e.vertices])
        for e in doc.modelspace().query("POLYLINE")
        if e.dxf.layer == "MARK"
    ]


def test_the_laser_coupon_as_written(laser):
    """One test for the laser coupon's files, so that its build runs once (not once per worker)."""
    out, data, parts, report = laser
    _folder_of_four_files(out, data, parts)
    _cut_rings_are_simple_and_offset_by_half_each_kerf(out, data, parts)
    _steps_differ_by_their_kerf(out, data, parts)
    _each_sector_carries_its_value_on_mark(out, data, parts)
    _plate_is_watertight_with_the_paths_volume(out, data, parts)
    _every_piece_and_the_jig_carry_a_legible_label(out, data)
    _the_jigs_holes_are_the_centre_distance_apart(out, data, report)
    _each_steps_play_read_back(out, data)


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
    assert len(data.pieces) == 10 and len(data.plays) == 5
    assert "Play per step" in text and "at the marked tooth" in text


def _cut_rings_are_simple_and_offset_by_half_each_kerf(out, data, parts):
    read = _cut_polygons(out / "spur_pair-coupon" / "coupon.dxf")
    assert len(read) == len(data.pieces) + 1  # and the jig
    for polygon in read:
        assert polygon.is_valid and polygon.exterior.is_simple
    assert sorted(len(p.interiors) for p in read) == [1] * len(data.pieces) + [2]  # pin holes; the jig's two
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
        mine = [s for s in strokes if placed.contains(shapely.MultiPoint(s)) and len(s) != 4]  # not the mark
        glyphs = [
            p for p in TextPath((0, 0), f"{piece.value:.2f}", size=1).to_polygons(closed_only=False) if len(p) >= 3
        ]
        assert len(mine) == len(glyphs), piece.name  # "0.15": 0, the dot, 1, 5 → one stroke per outline
        box = np.ptp(np.vstack(mine), axis=0)
        extents = TextPath((0, 0), f"{piece.value:.2f}", size=1).get_extents()
        assert box.max() / box.min() == pytest.approx(extents.width / extents.height, rel=0.05)  # along x or y
    assert sum(len(s) for s in strokes) > 0


def _plate_is_watertight_with_the_paths_volume(out, data, parts):
    import trimesh

    scene = trimesh.load(out / "spur_pair-coupon" / "coupon.3mf")
    meshes = list(scene.geometry.values())
    assert len(meshes) == len(data.pieces) + 1  # and the jig
    assert all(m.is_watertight for m in meshes)
    expected = (sum(p.path.area for p in data.pieces) + data.jig.path.area) * data.thickness
    assert sum(m.volume for m in meshes) == pytest.approx(expected, rel=1e-6)


def _every_piece_and_the_jig_carry_a_legible_label(out, data):
    """Every cut piece read back holds engraved strokes (MARK) entirely inside it, at least 1.5 mm
    tall (the letters run along x or y); a follower's holds the triangle marking its tooth too."""
    strokes = _mark_strokes(out / "spur_pair-coupon" / "coupon.dxf")
    followers = 0
    for polygon in _cut_polygons(out / "spur_pair-coupon" / "coupon.dxf"):
        inside = [s for s in strokes if polygon.contains(shapely.MultiPoint(s))]
        letters = [s for s in inside if len(s) != 4]
        assert letters, polygon.bounds
        assert np.ptp(np.vstack(letters), axis=0).min() >= 1.5 - 1e-9
        followers += any(len(s) == 4 for s in inside)
    assert followers == len(data.steps)  # the follower's sectors: one place, five steps
    assert len(strokes) > 0


def _jig(out) -> shapely.Polygon:
    return next(p for p in _cut_polygons(out / "spur_pair-coupon" / "coupon.dxf") if len(p.interiors) == 2)


def _the_jigs_holes_are_the_centre_distance_apart(out, data, report):
    """The jig's holes read back: their centres the report's centre distance apart (within the
    tolerance), each cut kerf/2 inside the pin's Ø2 mm (the beam's centre in the hole's waste), as
    are the nominal step's sectors' holes; the engraved centre distance inside the jig."""
    jig = _jig(out)
    holes = sorted((shapely.Polygon(h) for h in jig.interiors), key=lambda h: h.centroid.x)
    e = report["pair"]["center_distance"]
    assert e == pytest.approx(60.0)  # the spur pair's (20 + 40) · 2 / 2
    spacing = holes[0].centroid.distance(holes[1].centroid)
    assert abs(spacing - e) <= data.tolerance and abs(holes[0].centroid.y - holes[1].centroid.y) <= 1e-9
    kerf = data.nominal
    for hole in holes:
        assert hole.area == pytest.approx(math.pi * (1.0 - kerf / 2) ** 2, abs=2 * math.pi * data.tolerance)
    nominal = [p for p in data.pieces if p.value == pytest.approx(kerf)]
    for piece in nominal:
        assert shapely.Polygon(piece.path.interiors[0]).area == pytest.approx(holes[0].area, rel=0.02)


def _each_steps_play_read_back(out, data):
    """The sectors read back, made (shrunk by kerf/2, shapely's buffer), put on the jig as read
    (the driver's teeth towards the follower's pivot, the follower's towards the driver's), the
    driver held: the follower turned each way by bisection until the two touch.  Its free turn ×
    the follower's pitch radius (40 mm) is the play: within 2 µm of the coupon's proven bracket;
    the steps differ by the closed form 4·(0.05/2)/cos 20°, and the feeler gap is play·cos 20°."""
    read = _cut_polygons(out / "spur_pair-coupon" / "coupon.dxf")
    holes = sorted((shapely.Polygon(h).centroid for h in _jig(out).interiors), key=lambda c: c.x)
    e = holes[0].distance(holes[1])
    radius = e * 40 / 60  # the follower's pitch radius: 40 of the 60 mm
    kerf, alpha = data.nominal, math.radians(20)

    def piece(p):  # the polygon read back that is this piece's path, moved back to its pivot
        placed = shapely.affinity.translate(p.path, *p.offset)
        match = max(read, key=lambda r: shapely.intersection(r, placed).area)
        made = match.buffer(-kerf / 2, quad_segs=16)
        return shapely.affinity.translate(made, -p.offset[0], -p.offset[1])

    found = []
    for p, d, f in zip(data.plays, data.pieces[:5], data.pieces[5:]):
        driver = shapely.affinity.rotate(piece(d), -90, origin=(0, 0))
        follower = shapely.affinity.translate(shapely.affinity.rotate(piece(f), 90, origin=(0, 0)), e, 0)

        def apart(turn, follower=follower, driver=driver):
            return not shapely.intersects(driver, shapely.affinity.rotate(follower, turn, origin=(e, 0)))

        if p.play is None:  # binds: touching at every turn sampled within the bound (the code proves it)
            bound = math.degrees(p.bound / radius)
            assert not any(apart(t) for t in np.linspace(-bound, bound, 41)), p.value
            found.append(None)
            continue
        assert apart(0.0)
        ends = []
        for sign in (1, -1):
            free, step = 0.0, sign * 0.01 / radius * 180 / math.pi  # 0.01 mm on the pitch circle
            while apart(free + step):
                free += step
            stuck = free + step
            for _ in range(30):
                mid = (free + stuck) / 2
                free, stuck = (mid, stuck) if apart(mid) else (free, mid)
            ends.append(free)
        found.append(math.radians(ends[0] - ends[1]) * radius)
    per_step = 4 * 0.05 / 2 / math.cos(alpha)  # four flanks, each 0.025 mm along its normal
    plays = [p for p in data.plays if p.play is not None]
    assert len(plays) >= 3 and all(p.play is None for p in data.plays[len(plays) :])
    for p, mine in zip(plays, found):
        assert p.play[0] - 2e-6 <= mine <= p.play[1] + 2e-6, (p.value, p.play, mine)
        assert p.play[1] - p.play[0] <= 1e-4
        # the gauge's gap at the marked tooth's flanks is the play across the normal: within 3 %, or
        # 2.5 µm where the play itself is a few µm (the gap is taken at one place on the marked
        # flanks; the contact that stops the turn may lie elsewhere on the tooth)
        assert p.feeler[0] == pytest.approx(p.play[0] * math.cos(alpha), rel=0.03, abs=0.0025)
    for a, b in zip(plays, plays[1:]):
        assert a.play[0] - b.play[0] == pytest.approx(per_step, rel=0.02)
    if len(plays) < len(data.plays):  # the first that binds: the closed form leaves it no play
        assert plays[-1].play[1] - per_step < 0


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
    # a printed edge drawn c further inside comes out smaller: the play grows with the step
    for place in ("tight", "loose"):
        plays = [p.play for p in data.plays if p.place == place]
        assert all(p is not None for p in plays) and all(a[1] < b[0] for a, b in zip(plays, plays[1:]))
    drawing = coupon_drawing(data, cut_layer="CUT", mark_layer="MARK")
    for piece in data.pieces:
        placed = shapely.affinity.translate(piece.nominal, *piece.offset)
        assert any(placed.contains(shapely.MultiPoint(s)) for s in drawing.strokes["MARK"]), piece.name


def test_a_mechanism_without_a_pair_is_refused_in_one_line(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["coupon", "profiles/roller_body_m3.toml", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "mechanism = 'roller-body'" in err[0]
    assert not out.exists()
    assert main(["coupon", SPUR, "--out", str(out)]) == 2  # no process: nothing to step
    assert "process.kind = 'none'" in capsys.readouterr().err and not out.exists()
