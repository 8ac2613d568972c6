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

from gearcad.mechanisms import carrier_train, roller_body
from gearcad.mechanisms.band_mesh import mesh_band, mesh_play
from gearcad.mechanisms.band_trains import mesh_bands, roller_meshes, train_meshes, with_mesh_bands

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
    return {name: g for name, g, *_ in train_meshes(internal, positions=4)}


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
    g = {name: g for name, g, *_ in train_meshes(draft, positions=3)}["ring/gear3"]
    towards = np.sum(g.tighter * g.centre2, axis=1) / np.hypot(*g.centre2.T)
    assert np.allclose(towards, 1.0)  # away from the ring's pivot: the centres part
    assert _moved(g, 0.1) == pytest.approx(-_change(12.0, 0.1), rel=0.01)  # parting takes play
    assert _moved(g, -0.1) == pytest.approx(-_change(12.0, -0.1), rel=0.01)


def test_contact_ratio_is_the_textbook_one_external_and_internal(internal):
    m, alpha = 1.5, ALPHA
    contact = {name: c for name, _, _, c in train_meshes(internal, positions=2)}

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


def test_the_body_reports_a_band_per_roller(rollers):
    bands = mesh_bands(rollers)
    assert [b.band.mesh for b in bands] == ["body/roller 1", "body/roller 2", "body/roller 3"]
    assert all(b.band.fits and not b.internal for b in bands)  # no process: the drawn play


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
