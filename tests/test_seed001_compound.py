"""Seed 001's second scheme as real parts (profiles/compound_ring.toml): gear 1 drives a compound
ring externally, gear 3 turns inside its internal teeth, each toothing with its own pitch radius.

Expected numbers are worked out here by hand from the profile's values (pitch radius m·z/2, the
method of stopping written out, the seed's formula as printed), never read from gearcad."""

import math

import numpy as np
import pytest
import shapely

import gearcad
from gearcad.errors import DesignError, ProfileError
from gearcad.trains import compound as CP

from .conftest import COARSE, ROOT

PROFILE = ROOT / "profiles" / "compound_ring.toml"
TOL = 0.001  # the profile's output.tolerance, mm
RPM = 2 * math.pi / 60
# the profile: module 1.5, teeth [20, 40, 14], ring's internal teeth 30, 60 and 20 rpm, ε1 = 1 rad/s²
M, Z1, Z2, Z3, Z2_IN = 1.5, 20, 40, 14, 30
R1, R2_OUT, R2_IN, R3 = M * Z1 / 2, M * Z2 / 2, M * Z2_IN / 2, M * Z3 / 2  # 15, 30, 22.5, 10.5 mm
W1, W, E1 = 60 * RPM, 20 * RPM, 1.0


@pytest.fixture(scope="module")
def design():
    return gearcad.design(gearcad.load_profile(PROFILE))


def _omega3(w1, w, r1, r2_out, r2_in, r3):
    """ω3 = −(ω1 + ω)·r1·r2_inner/(r2_outer·r3) − ω: stopped, Ω1·r1 = −Ω2·r2_out, Ω2·r2_in = Ω3·r3."""
    return -(w1 + w) * r1 * r2_in / (r2_out * r3) - w


def _seed(w1, w, r1, r3):
    """The seed's printed ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3 (one r2 for both toothings)."""
    return -(w1 * r1 + w * r1 + w * r3) / r3


def test_speeds_by_stopping_match_the_closed_form_and_the_fixed_frame(design):
    gears = design.data["gears"]
    assert [g["name"] for g in gears] == ["gear1", "ring", "gear3"]
    omega = np.array([g["omega"] for g in gears])
    expected = [W1, -(W1 + W) * R1 / R2_OUT - W, _omega3(W1, W, R1, R2_OUT, R2_IN, R3)]
    np.testing.assert_allclose(omega, expected, rtol=1e-12)
    assert omega[2] / RPM == pytest.approx(-80 * 15 * 22.5 / (30 * 10.5) - 20, rel=1e-12)  # −105.714 rpm
    # accelerations follow the same chain (ε = 0 for the carrier)
    assert gears[2]["epsilon"] == pytest.approx(_omega3(E1, 0.0, R1, R2_OUT, R2_IN, R3), rel=1e-12)
    # the fixed-frame velocity analysis with the radii written out here
    meshes = (CP.Mesh("external", R1, R2_OUT), CP.Mesh("internal", R2_IN, R3))
    np.testing.assert_allclose(CP.chain_by_velocities(meshes, omega1=W1, carrier=W, carrier_angle=1.0), omega)
    assert design.data["train"]["velocity_analysis_difference"] < 1e-12
    block = design.data["compound"]
    assert block["omega3"] == pytest.approx(block["omega3_by_velocities"], abs=1e-12)
    assert block["radius_ratio"] == 0.75 and (block["r2_outer"], block["r2_inner"]) == (R2_OUT, R2_IN)
    # centres on the carrier line: external step r1 + r2_outer, internal step r2_inner − r3
    assert [g["centre"] for g in gears] == pytest.approx([0.0, 45.0, 57.0], abs=1e-12)


def test_the_seeds_formula_is_reported_beside_the_true_speed(design):
    block = design.data["compound"]
    seed = _seed(W1, W, R1, R3)
    assert seed / RPM == pytest.approx(-1410 / 10.5)  # −134.29 rpm, whatever gear 2's radii
    assert block["omega3_seed_formula"] == pytest.approx(seed, rel=1e-12)
    assert block["omega3_seed_formula_rpm"] == pytest.approx(-134.2857142857, rel=1e-10)
    # the seed's formula is the equal-radii case of the closed form
    assert _omega3(W1, W, R1, R2_OUT, R2_OUT, R3) == pytest.approx(seed, rel=1e-12)
    (claim,) = [f for f in design.findings if f.code == "paper-claim"]
    assert claim.where == "train.compound"
    assert "-105.7 rpm" in claim.message and "-134.3 rpm" in claim.message and "0.75" in claim.message


def _radii(ring: np.ndarray) -> np.ndarray:
    return np.hypot(ring[:, 0], ring[:, 1])


def _tips(ring: np.ndarray, near: float, band: float) -> int:
    """How many separate runs of the closed ring lie within ``band`` of radius ``near``."""
    inside = np.abs(_radii(ring) - near) < band
    return int(np.count_nonzero(inside & ~np.roll(inside, 1)))


def test_the_compound_ring_is_one_part_with_both_toothings(design):
    ring = design.part("ring")
    assert [p.name for p in design.parts()].count("ring") == 1 and ring.pivot == "hole"
    outer, hole = ring.fine.rings
    assert len(ring.outline.rings) == 2
    # external teeth: tips at r_out + m, roots at r_out − 1.25·m, 40 tips
    assert _radii(outer).max() == pytest.approx(R2_OUT + M, abs=TOL)
    assert _radii(outer).min() == pytest.approx(R2_OUT - 1.25 * M, abs=TOL)
    assert _tips(outer, R2_OUT + M, 0.05 * M) == Z2
    # internal teeth: their tips (the hole's nearest points) at r_in − m_in, roots at r_in + 1.25·m_in, 30 tips
    assert _radii(hole).min() == pytest.approx(R2_IN - M, abs=TOL)
    assert _radii(hole).max() == pytest.approx(R2_IN + 1.25 * M, abs=TOL)
    assert _tips(hole, R2_IN - M, 0.05 * M) == Z2_IN
    # a simple hole, clockwise, wholly inside the outer ring: one part with one hole
    polygon = shapely.Polygon(outer, [hole])
    assert polygon.is_valid and shapely.Polygon(outer).contains(shapely.Polygon(hole))
    assert shapely.LinearRing(outer).is_ccw and not shapely.LinearRing(hole).is_ccw
    # the wall between the root circles, measured and as reported: (r_out − 1.25·m) − (r_in + 1.25·m)
    wall = (R2_OUT - 1.25 * M) - (R2_IN + 1.25 * M)
    assert wall == 3.75 and wall >= 2 * M
    assert design.data["gears"][1]["wall"] == pytest.approx(wall, abs=1e-12)
    assert _radii(outer).min() - _radii(hole).max() == pytest.approx(wall, abs=2 * TOL)
    entry = design.data["gears"][1]
    assert (entry["inner_teeth"], entry["inner_module"], entry["inner_pitch_radius"]) == (Z2_IN, M, R2_IN)


def test_the_assembly_fits_and_bites_when_turned(design):
    a = design.assembly
    assert a.fits and a.overlap <= a.allowed < a.nudged
    parts = {p.name: p for p in design.parts()}
    placed = {pl.part: pl for pl in design.placements}

    def overlap(name, other, turn):
        pl, at = placed[name], placed[other]
        mate = parts[other].outline.polygon(at.angle, at.offset)
        return mate.intersection(parts[name].outline.polygon(pl.angle + turn, pl.offset)).area

    # gear 3 in the ring's internal teeth and gear 1 on its external ones: ~0 as placed; half a
    # pitch turned, tooth onto tooth, they overlap by a good part of a tooth's area
    for name, other, z in (("gear3", "ring", Z3), ("ring", "gear1", Z2)):
        assert overlap(name, other, 0.0) <= a.allowed
        assert overlap(name, other, math.pi / z) > 0.3 * M * M
        assert min(overlap(name, other, d) for d in (-0.01, 0.01)) > a.allowed


def test_an_inner_module_of_its_own():
    """Internal teeth of module 1 (44 teeth): gear 3 is cut with that module too.  Closed forms
    only (speeds, module, wall), so at :data:`COARSE` (0.01 mm outlines, no chart data), and the
    bands bounded by the estimate (the assembly's interference proof is the same; 0.46 CPU-s
    against the theorem's 0.78)."""
    inner = {"train.compound.inner_module": 1.0, "train.compound.inner_teeth": 44}
    p = gearcad.load_profile(PROFILE, {**COARSE, **inner, "output.certificate": "estimate"})
    d = gearcad.design(p)
    r2_in, r3 = 1.0 * 44 / 2, 1.0 * Z3 / 2
    assert d.data["gears"][2]["omega"] == pytest.approx(_omega3(W1, W, R1, R2_OUT, r2_in, r3), rel=1e-12)
    assert d.data["gears"][2]["module"] == 1.0 and d.data["gears"][1]["wall"] == pytest.approx(
        (R2_OUT - 1.25 * M) - (r2_in + 1.25 * 1.0)
    )
    assert d.assembly.fits


@pytest.mark.parametrize(
    "overrides,key,words",
    [
        ({"train.compound.inner_teeth": 32}, "train.compound.inner_teeth = 32", "give at most 31 inner teeth"),
        ({"train.compound.inner_teeth": 25}, "train.compound.inner_teeth = 25", "give at least 26"),
        ({"train.compound.gear": "gear1"}, "train.compound.gear = 'gear1'", "it allows 'ring'"),
        ({"train.compound.gear": 7}, "train.compound.gear = 7", "'gear1', 'ring', 'gear3'"),
        ({"train.compound.inner_module": 2.0}, "train.compound.inner_teeth = 30", "train.teeth[1] ≥ 52"),
        ({"train.compound.gear": True}, "train.compound.gear = true", "a gear's name"),
    ],
)
def test_bad_compounds_give_one_line_naming_the_key(overrides, key, words):
    with pytest.raises(ProfileError) as info:
        gearcad.load_profile(PROFILE, overrides)
    (line,) = str(info.value).splitlines()
    assert f"{PROFILE}: {key}: " in line and words in line


def test_the_wall_rule_is_the_closed_form_at_its_edge():
    """31 inner teeth leave exactly 2·m = 3 mm of wall (30 − 1.875 − 23.25 − 1.875): accepted."""
    p = gearcad.load_profile(PROFILE, {"train.compound.inner_teeth": 31})
    assert (R2_OUT - 1.25 * M) - (M * 31 / 2 + 1.25 * M) == pytest.approx(2 * M)
    assert p.inner_teeth == 31 and p.compound == 1


def test_a_ring_with_outer_teeth_needs_the_compound_table():
    p = gearcad.load_profile(PROFILE, {"train.compound": None})
    with pytest.raises(DesignError, match=r"ring would need internal teeth .* \[train.compound\]"):
        gearcad.design(p)


def test_a_gear_inside_a_ring_cannot_itself_be_a_ring():
    """Gear 2 turns inside gear 1 (60) and round gear 3 (10): it would need external and internal
    teeth on one pitch circle, and a compound gear needs an external mesh before it."""
    data = {"mechanism": "carrier-train", "train": {"module": 1, "teeth": [60, 30, 10], "meshes": ["internal"] * 2}}
    with pytest.raises(DesignError, match="gear2 would need internal teeth") as info:
        gearcad.check(data)
    assert "[train.compound]" not in str(info.value)
