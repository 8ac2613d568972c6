"""The bands of a carrier train's meshes and of a toothed body's rollers against closed forms.

An external mesh of circles: a centre distance Δa farther apart adds j = 2a(inv α' − inv α) of
play on gear 2's pitch circle (the normal play 2a'·cos α'·(inv α' − inv α) over cos α, with
a·cos α = a'·cos α'; ≈ 2·Δa·tan α), an edge offset δ on both gears takes 4·δ/cos α.  An internal
mesh (a pinion in a ring) has the sign reversed: on the operating circles the ring's space is
2r'(e/2r + inv α − inv α') and the pinion's tooth 2r'(s/2r + inv α − inv α'), so the play is
2a'(inv α − inv α') — it falls as the centres part.  The contact ratio is the textbook ε_α,
internal with the ring's tip circle inside its pitch circle.
"""

import math

import numpy as np
import pytest

from gearcad.fitting.band_mesh import mesh_band, mesh_play
from gearcad.fitting.band_trains import mesh_bands, roller_meshes, train_meshes, with_mesh_bands
from gearcad.mechanisms import carrier_train, roller_body

from .conftest import drafted

ALPHA = math.radians(20)


def _inv(x):
    return math.tan(x) - x


def _change(a, da):
    """Play gained on gear 2's pitch circle when an external mesh's centres part by da (exact involute)."""
    aw = math.acos(a * math.cos(ALPHA) / (a + da))
    return 2 * a * (_inv(aw) - _inv(ALPHA))


FINE = {"output.tolerance": 0.002}
"""Drafts are cheap; the closed forms to 1 % need outlines finer than the coarse 0.01 mm."""


@pytest.fixture(scope="module")
def internal():
    """planetary_internal: sun/planet external, planet/ring internal (the ring after its pinion)."""
    return drafted("planetary_internal", carrier_train.design, FINE)[1]


@pytest.fixture(scope="module")
def meshes(internal):
    return {name: g for name, g, *_ in train_meshes(internal, positions=4, written=False)}


def _band(g, *, edge=0.0, spread=0.0):
    return mesh_band(g, edge=(0.0, -edge, edge), spread=spread, tol=0.002, name="m")


def _moved(g, shift):
    """The play gained, position by position, with gear 2's pivot moved ``shift`` mm towards
    the tight side (mm; negative: away); both parts 0.02 mm smaller all round, so that they are
    free either way (an offset involute is an involute of the same base circle)."""
    smaller = (-0.02, -0.02)
    return np.mean(mesh_play(g, smaller, shift, 0.002, reach=1.0) - mesh_play(g, smaller, 0.0, 0.002, reach=1.0))


@pytest.mark.parametrize("name, a, sign", [("sun/planet", 27.0, 1), ("planet/ring", 27.0, -1)])
def test_centre_distance_error_matches_the_involute_closed_form_with_the_internal_sign(meshes, name, a, sign):
    g, da = meshes[name], 0.1
    # the tight side moves gear 2's pivot towards gear 1's (external) or away from it (internal)
    towards = np.sum(g.tighter * g.centre2, axis=1) / np.hypot(*g.centre2.T)
    assert np.allclose(towards, -sign)
    # the centres da apart: the pivot moved da away from gear 1's, by hand along the line of centres
    apart = -sign * da
    assert _moved(g, apart) == pytest.approx(sign * _change(a, da), rel=0.01)
    assert _moved(g, -apart) == pytest.approx(sign * _change(a, -da), rel=0.01)
    b = _band(g, spread=da)  # the band: the tight side loses about 2·Δa·tan α
    assert b.nominal[0] - b.band[0] == pytest.approx(2 * da * math.tan(ALPHA), rel=0.03)


@pytest.mark.parametrize("name", ["sun/planet", "planet/ring"])
def test_an_edge_offset_matches_the_tooth_thickness_closed_form(meshes, name):
    b = _band(meshes[name], edge=0.025)  # a laser's ±0.05 mm of kerf: ±0.025 mm on each edge
    expected = 4 * 0.025 / math.cos(ALPHA)
    assert b.nominal[0] - b.band[0] == pytest.approx(expected, rel=0.01)
    assert b.band[1] - b.nominal[1] == pytest.approx(expected, rel=0.01)


def test_a_ring_before_its_pinion_the_compound_ring():
    """The compound ring's internal teeth drive gear 3 inside them: the ring is gear 1 of the mesh."""
    draft = drafted("compound_ring", carrier_train.design, FINE)[1]
    g = {name: g for name, g, *_ in train_meshes(draft, positions=3, written=False)}["ring/gear3"]
    towards = np.sum(g.tighter * g.centre2, axis=1) / np.hypot(*g.centre2.T)
    assert np.allclose(towards, 1.0)  # away from the ring's pivot: the centres part
    assert _moved(g, 0.1) == pytest.approx(-_change(12.0, 0.1), rel=0.01)  # parting takes play
    assert _moved(g, -0.1) == pytest.approx(-_change(12.0, -0.1), rel=0.01)


def test_contact_ratio_is_the_textbook_one_external_and_internal(internal):
    m, alpha = 1.5, ALPHA
    contact = {name: c for name, _, _, c in train_meshes(internal, positions=2, written=False)}

    def arm(r):  # √(r_a² − r_b²) of a gear of pitch radius r, tip one module out
        return math.sqrt((r + m) ** 2 - (r * math.cos(alpha)) ** 2)

    pb = math.pi * m * math.cos(alpha)
    external = (arm(15) + arm(12) - 27 * math.sin(alpha)) / pb
    ring_tip = 39 * math.sin(alpha) - math.sqrt((39 - m) ** 2 - (39 * math.cos(alpha)) ** 2)
    # the ring's tip circle (37.5) passes inside the pinion's interference point T1 (37.79 from the
    # ring's centre): conjugate contact ends at T1, r1·sin α from the pitch point
    assert ring_tip > 12 * math.sin(alpha)
    inside = (arm(12) - 12 * math.sin(alpha) + 12 * math.sin(alpha)) / pb
    assert contact["sun/planet"].ratio == pytest.approx(external, rel=1e-9)
    assert contact["planet/ring"].ratio == pytest.approx(inside, rel=1e-9)
    assert np.all(contact["planet/ring"].pressure_angle == alpha)


def test_the_report_check_lines_and_verdict_of_a_laser_train():
    """A train drawn without backlash jams under a laser's stack: report, lines, findings, page."""
    from gearcad.export.html_band import section_bands

    done = with_mesh_bands(drafted("planetary_internal", carrier_train.design, {"process.kind": "laser"})[1])
    bands = done.data["bands"]
    assert [b["mesh"] for b in bands] == ["sun/planet", "planet/ring"]
    assert [b["internal"] for b in bands] == [False, True]
    assert all(b["verdict"] == "jams" and b["min"] < 0 < b["max"] for b in bands)
    assert bands[1]["center_distance_change"] < 0 < bands[0]["center_distance_change"]  # internal: closer
    assert bands[1]["contact"]["ratio_min"] > 1.5
    assert [f.code for f in done.findings].count("jams") == 2
    assert sum(line.startswith("band planet/ring (laser)") for line in done.details) == 1
    page = section_bands({"bands": bands, "process": done.data["process"]})
    assert "planet/ring (internal)" in page and "jams" in page and "contact ratio" in page


@pytest.fixture(scope="module")
def rollers():
    return drafted("roller_body_m3", roller_body.design)[1]


def test_each_roller_rolls_on_the_body_from_its_assembled_place(rollers):
    """At the assembly each roller's pivot and turn are its placement's (the body unturned), and
    rolling keeps it in mesh all the way round: the drawn play stays within the tolerance."""
    found = roller_meshes(rollers, positions=12)
    assert [name for name, *_ in found] == ["body/roller 1", "body/roller 2", "body/roller 3"]
    for (_, g, _, contact), placed in zip(found, rollers.placements[1:]):
        assert np.allclose(g.centre2[0], placed.offset, atol=1e-6)
        assert math.remainder(g.angle2[0] - placed.angle, 2 * math.pi) == pytest.approx(0, abs=1e-9)
        play = mesh_play(g, (0.0, 0.0), 0.0, 0.01, reach=1.0)
        assert not np.isnan(play).any() and np.all(play < 0.05)
        # the line of centres of the local mesh: the roller's axle on the body's normal, ρ out
        assert np.allclose(np.hypot(*(g.contact - g.centre2).T), 10.0295, atol=1e-3)
        assert 1.2 < contact.ratio.min() <= contact.ratio.max() < 2.0


@pytest.fixture(scope="module")
def roller_bands(rollers):
    return mesh_bands(rollers)


def test_the_body_reports_a_band_per_roller_proven(roller_bands):
    """Each roller's band is proven (the roller's axle moves along the body: :mod:`.moving`);
    with no process the outlines moved in by the tolerance are proven apart: the least play is
    at least −4·tol/cos α, the margin exact parts keep."""
    bands = roller_bands
    assert [b.band.mesh for b in bands] == ["body/roller 1", "body/roller 2", "body/roller 3"]
    assert all(b.band.fits and not b.internal for b in bands)  # no process: the drawn play
    for b in bands:
        cert = b.band.certificate
        assert cert.kind == "theorem" and cert.proven
        assert cert.lower == pytest.approx(-4 * 0.01 / math.cos(ALPHA)) and b.band.band[0] >= cert.lower


def test_the_built_pages_and_reports_carry_every_mesh(built):
    """Read back: each train's and the toothed body's report.json has a band (and contact) per
    mesh, and its page the table; with no process the drawn play fits."""
    import json

    expected = {
        "planetary_external": ["sun/idler", "idler/planet"],
        "planetary_internal": ["sun/planet", "planet/ring"],
        "compound_ring": ["gear1/ring", "ring/gear3"],
        "roller_body_m3": ["body/roller 1", "body/roller 2", "body/roller 3"],
    }
    for name, meshes in expected.items():
        report = json.loads((built / name / "report.json").read_text(encoding="utf-8"))
        assert [b["mesh"] for b in report["bands"]] == meshes
        assert all(b["verdict"] == "fits" and b["contact"]["ratio_min"] > 1.2 for b in report["bands"])
        assert [b["internal"] for b in report["bands"]] == [m in ("planet/ring", "ring/gear3") for m in meshes]
        page = (built / name / "index.html").read_text(encoding="utf-8")
        assert 'id="fit"' in page and f"<td>{meshes[-1]}" in page and "working pressure angle" in page


# ---- the backlash of trains and bodies: cut, chosen under a process, warned when fixed ----


def _tooth_arc(ring: np.ndarray, radius: float) -> float:
    """Material along a circle (for a ring's toothed hole: space), mm: the circle's length inside
    the outline, read off the drawn ring by shapely."""
    import shapely

    circle = shapely.Point(0, 0).buffer(radius, quad_segs=2048).exterior
    return shapely.intersection(shapely.Polygon(ring), circle).length


def test_train_backlash_thins_each_gear_and_widens_the_ring_spaces_by_half():
    """The drawn parts read back: a gear's tooth on the pitch circle is πm/2 − b/2 long, a ring's
    space (its hole inside the pitch circle) πm/2 + b/2, each within the outline tolerance."""
    b, m = 0.3, 1.5
    parts = drafted("planetary_internal", carrier_train.design, {**FINE, "train.backlash": b})[1].parts
    for part, z in zip(parts[:2], (20, 16)):
        assert _tooth_arc(part.outer, m * z / 2) / z == pytest.approx(math.pi * m / 2 - b / 2, abs=0.001)
    ring = parts[2]
    assert _tooth_arc(ring.hole, m * 52 / 2) / 52 == pytest.approx(math.pi * m / 2 + b / 2, abs=0.001)


def test_a_backlash_too_large_is_refused_naming_the_key():
    from gearcad.errors import DesignError

    with pytest.raises(DesignError, match=r"train.backlash = 2.4: .* the largest backlash module 1.5 takes is 2.356"):
        drafted("planetary_external", carrier_train.design, {"train.backlash": 2.4})


@pytest.fixture(scope="module")
def laser_train():
    """planetary_internal under a laser's defaults, its backlash left to gearcad (coarse outlines)."""
    from gearcad.fitting import design

    from .conftest import COARSE, profile

    return design(profile("planetary_internal", {**COARSE, "process.kind": "laser"}))


def _worst(params, backlash):
    """The tightest worst case over a train's meshes (mm less the margin) cut with ``backlash``."""
    from gearcad.fitting.fit import made
    from gearcad.fitting.mesh_fit import with_backlash

    bands = mesh_bands(carrier_train.design(with_backlash(made(params), backlash)))
    return min(mb.band.band[0] - mb.band.margin for mb in bands)


def test_a_laser_train_gets_the_smallest_backlash_that_fits(laser_train):
    """Every mesh fits with the chosen b, reported and cut; with b less the resolution
    (max(tol, 1 % of b)) and a tolerance more, the worst case jams — measured here, not by the
    chooser; and b is the closed form 4·δ/cos α + 2·Δa·tan α plus the margin (circles: the play
    grows one for one with b), within the resolution."""
    bands, p = laser_train.data["bands"], laser_train.params
    b, tol = p.train.backlash, p.output.tolerance
    assert [x["verdict"] for x in bands] == ["fits", "fits"]
    assert all(x["backlash"] == b and x["backlash_chosen"] for x in bands)
    assert laser_train.data["train"]["backlash"] == b
    assert any(line.startswith(f"train.backlash = {b:.4f} mm (chosen") for line in laser_train.details)
    assert min(x["min"] for x in bands) >= 2 * tol
    resolution = max(tol, 0.01 * b)
    assert _worst(p, b - resolution - tol) < 0  # smaller by more than the resolution: it jams
    closed = 4 * 0.025 / math.cos(ALPHA) + 2 * 0.1 * math.tan(ALPHA) + 2 * tol
    assert closed - tol <= b <= closed + resolution + tol


def test_a_fixed_backlash_too_small_warns_with_the_value_needed():
    """train.backlash = 0.05 under a laser: each mesh jams, and the warning's value frees it
    (about the closed form: the play grows one for one with the backlash)."""
    import re

    from gearcad.fitting import design

    from .conftest import COARSE, profile

    done = design(profile("planetary_external", {**COARSE, "process.kind": "laser", "train.backlash": 0.05}))
    warned = [f.message for f in done.findings if f.code == "backlash-fixed"]
    assert [f.code for f in done.findings].count("jams") == 2 and len(warned) == 2
    need = max(float(re.search(r"train.backlash = ([0-9.]+) mm", w).group(1)) for w in warned)
    closed = 4 * 0.025 / math.cos(ALPHA) + 2 * 0.1 * math.tan(ALPHA) + 2 * 0.01
    assert need == pytest.approx(closed, abs=0.012)
    assert "train.backlash +" in [f.message for f in done.findings if f.code == "jams"][0]


def test_fdm_tips_in_roots_no_backlash_frees_them():
    """FDM's defaults: both edges +0.3 mm (0.1 + the elephant foot) and the centres 0.2 mm off take
    0.8 mm from a radial clearance of 0.25·1.5 = 0.375 mm: the finding says no backlash helps."""
    from gearcad.fitting.band_trains import _jams, radial_room

    from .conftest import COARSE, profile

    params = profile("planetary_external", {**COARSE, "process.kind": "fdm"})
    assert radial_room(params, 1.5) == pytest.approx(0.375 - 0.6 - 0.2)
    chamfered = profile("roller_body_m3", {**COARSE, "process.kind": "fdm", "output.chamfer": 0.2})
    assert radial_room(chamfered, 1.6) == pytest.approx(0.4 - 0.2 - 0.2)
    gears = drafted("planetary_external", carrier_train.design, {"train.backlash": 1.0})[1]
    band = mesh_band(train_meshes(gears, 3)[0][1], edge=(0.0, -0.1, 0.3), spread=0.2, tol=0.01, name="m", backlash=1.0)
    assert not band.fits  # a full millimetre of backlash and still jammed
    assert "the tips reach the mate's roots" in _jams(band, False, "train.backlash", -0.425)


def test_the_rollers_share_one_band_found_at_their_own_turns(rollers, roller_bands):
    """The three rollers meet the body alike a third of a turn apart: about roller 1's tightest
    place roller 2's play, measured on its own 120° of the body earlier, is roller 1's; and its
    band is roller 1's, its worst place 120° earlier."""
    found = roller_meshes(rollers)
    shared = roller_bands
    turns = shared[0].band.worst_phi + np.linspace(-0.01, 0.01, 5)
    one, two = found[0][1].pair, found[1][1].pair
    smaller = (-0.01, -0.01)
    play1 = mesh_play(one.at(turns).mesh, smaller, 0.0, 0.01, reach=1.0)
    play2 = mesh_play(two.at(turns - 2 * math.pi / 3).mesh, smaller, 0.0, 0.01, reach=1.0)
    assert play2 == pytest.approx(play1, abs=1e-6)
    assert shared[1].band.band == shared[0].band.band and shared[1].band.certificate == shared[0].band.certificate
    assert shared[1].band.worst_phi == pytest.approx((shared[0].band.worst_phi - 2 * math.pi / 3) % (2 * math.pi))


def test_a_rollers_instant_centre_is_its_pitch_point(rollers):
    """The roller rolls on the body's pitch curve: the instant centre of its motion in the
    body's frame, from the placements' stencils, is the pitch point; with the axle moved s
    towards the body it is s/(1 + ρκ) in from it along the normal (I = C + J·C'/ω, C on the
    parallel at ρ − s), and |ω| = (1/ρ + κ)·ds/dτ."""
    from gearcad.fitting.moving import local

    g = roller_meshes(rollers, positions=6)[0][1].pair
    frame, rho = rollers.detail.pitch, g.arm
    m = g.mesh
    s = frame.arc_at(-m.phi1)
    kappa = frame.curvature(s)
    _, omega, _, instant, _ = local(g.place, m.phi1, 0.0)
    assert np.allclose(instant, m.contact, atol=1e-6)
    speed = ((frame.arc_at(-(m.phi1 - 1e-5)) - frame.arc_at(-(m.phi1 + 1e-5))) % frame.perimeter) / 2e-5
    assert np.allclose(np.abs(omega), (1 / rho + kappa) * speed, rtol=1e-6)
    _, _, _, moved, _ = local(g.place, m.phi1, 0.3)
    assert np.allclose(moved, m.contact + (0.3 / (1 + rho * kappa))[:, None] * m.tighter, atol=1e-6)


def test_a_rollers_bound_between_positions_is_never_above_a_dense_sweep(rollers, roller_bands):
    """The proof's bound over an interval about a measured position (:func:`.tube.tube` for the
    roller's moving pivot) is never above the least play a dense sweep (41 positions an interval)
    measures there, and within 4 µm of it: both parts 0.01 mm smaller, the axle 0.05 mm towards
    the body (the play about 7 µm), five intervals 0.006 rad of the body wide about its tightest
    place; and the five bounded together (:func:`.tube.tubes`, as the proof asks for them) are the
    five bounded one by one."""
    from gearcad.fitting.moving import MovingMeasures
    from gearcad.fitting.tube import tube, tubes

    g = roller_meshes(rollers, positions=6)[0][1].pair
    measures, smaller, spread, h = MovingMeasures(), (-0.01, -0.01), 0.05, 0.003
    centres = roller_bands[0].band.worst_phi + 2 * h * np.arange(-2, 3)
    sites, _ = measures.sites(g.at(centres), smaller, spread, 0.01, 1.0)
    ratio = measures.ratio(g, spread)
    dense = centres[:, None] + np.linspace(-h, h, 41)[None, :]
    plays = mesh_play(g.at(dense.ravel()).mesh, smaller, spread, 0.01, reach=1.0).reshape(dense.shape)
    one_by_one = []
    for site, c, least in zip(sites, centres, plays.min(axis=1)):
        bounds = tuple(float(b[0]) for b in ratio(np.array([c - h]), np.array([c + h])))
        one_by_one.append(tube(site, h, 0.0, bounds))
        proven = 2 * one_by_one[-1] * g.arm
        assert least - 0.004 <= proven <= least + 1e-6, (c, proven, least)
    together = tubes(sites, np.full(len(sites), h), 0.0, np.column_stack(ratio(centres - h, centres + h)), 0.0)
    assert np.allclose(together, one_by_one, rtol=1e-12, atol=0.0), (together, one_by_one)


def test_a_train_mesh_is_proven_and_no_more_optimistic_than_a_dense_sweep(laser_train):
    """Each mesh of a carrier train is proven as a pair about fixed centres over one pitch (each
    outline repeats a tooth): report.json's certified least play is never above the least that
    band_mesh — another engine, the parts placed by their placements — finds at 96 positions over
    every tooth, and the verdict keeps the margin."""
    p = laser_train.params
    edge, spread, tol = p.process.edge(p.output.chamfer), p.process.center_spread(), p.output.tolerance
    meshes = train_meshes(carrier_train.design(p), 96)
    for band, (name, g, *_) in zip(laser_train.data["bands"], meshes):
        assert band["mesh"] == name and band["certificate"] == "theorem" and band["proven"]
        dense = mesh_band(g, edge=edge, spread=spread, tol=tol, name=name, backlash=p.train.backlash)
        assert band["certified_min"] <= dense.band[0] + 1e-6, (name, band["certified_min"], dense.band[0])
        assert band["certified_min"] >= 2 * tol


def test_the_compound_rings_outer_mesh_is_proven_over_its_outer_teeth():
    """compound_ring's gear1/ring meets the ring's 40 outer teeth (not its 30 inner ones): its
    outline repeats by an outer tooth, so the mesh is proven over one pitch; under a laser the
    certified least is never above the least band_mesh (another engine) finds at 96 positions
    all round on the same made parts, and within 3 µm of it (at 0.21 mm of backlash: at 0.2 its
    written paths, 10 µm from the held outlines at this tolerance, jam by the margin's measure)."""
    from dataclasses import replace

    from gearcad.fitting.band_trains import _repeats
    from gearcad.fitting.written import written_regions, written_shapes

    from .conftest import COARSE, profile

    p = profile("compound_ring", {**COARSE, "process.kind": "laser", "train.backlash": 0.21})
    draft = carrier_train.design(p)
    ring = written_shapes(draft)[1]  # as the files write it
    assert _repeats(ring.exterior, 40) and not _repeats(ring.exterior, 30)
    name, g, *_ = train_meshes(draft, 96)[0]
    assert name == "gear1/ring" and g.pair is not None
    band = mesh_bands(draft)[0].band
    edge, spread, tol = p.process.edge(p.output.chamfer), p.process.center_spread(), p.output.tolerance
    # the same made parts: the regions the cut paths bound, grown by each edge less the beam's radius
    (gear1, ring, *_), beam = written_regions(draft)
    made = replace(g, shapes=(gear1, ring))
    dense = mesh_band(made, edge=tuple(e - beam for e in edge), spread=spread, tol=tol, name=name, backlash=0.21).band[
        0
    ]
    cert = band.certificate
    assert cert.kind == "theorem" and cert.proven
    assert dense - 0.003 <= cert.lower <= dense + 1e-6, (cert.lower, dense)
