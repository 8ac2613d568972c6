"""The compound ring (gearcad.mechanisms.compound_ring): one part with external and internal teeth
of their own pitch radii, its speeds by the method of stopping against hand-worked closed forms,
and the seed's one-radius formula set beside them."""

import math

import numpy as np
import pytest

from gearcad.geometry.outline import ring_area
from gearcad.mechanisms import carrier_train, compound_ring

from .conftest import drafted, tooth_angle

RPM = 2 * math.pi / 60
# compound_ring.toml: gear1 20 teeth drives the ring's 40 outer teeth; gear3 (14) turns inside
# its 30 inner teeth; module 1.5 throughout
R1, R2_OUT, R2_IN, R3, M = 15.0, 30.0, 22.5, 10.5, 1.5


@pytest.fixture(scope="module")
def train():
    return drafted("compound_ring", carrier_train.design)


def test_the_compound_part_has_both_toothings_and_both_pitch_circles(train):
    params, _ = train
    spec = compound_ring.compound_part(params)
    outer, hole = np.hypot(*spec.outer.T), np.hypot(*spec.hole.T)
    assert spec.name == "ring" and spec.bore is None
    assert (outer.min(), outer.max()) == pytest.approx((R2_OUT - 1.25 * M, R2_OUT + M), abs=1e-9)
    # the inner teeth: a gear cut with addendum and dedendum swapped, reversed (clockwise)
    assert (hole.min(), hole.max()) == pytest.approx((R2_IN - M, R2_IN + 1.25 * M), abs=1e-9)
    assert ring_area(spec.outer) > 0 > ring_area(spec.hole)
    assert [float(np.hypot(*m[0])) for m in spec.marks] == pytest.approx([R2_OUT, R2_IN], abs=1e-9)


def test_the_ring_sits_on_the_carrier_by_its_two_radii(train):
    _, draft = train
    assert [pl.offset[0] for pl in draft.placements] == pytest.approx([0.0, R1 + R2_OUT, R1 + R2_OUT + R2_IN - R3])
    # gear3 is nudged on its own pitch circle, the ring on its outer one
    assert [(c.module, c.radius) for c in draft.contacts] == [(M, R2_OUT), (M, R3)]


def test_gear3_meets_the_inner_teeth_tooth_to_space(train):
    """Inside the ring both contacts are at angle 0 from the centres and both pitch circles run
    the same way: gear3's nearest tooth and the inner teeth's nearest space lie the same arc
    along them (found from the outlines alone)."""
    _, draft = train
    ring, gear3 = draft.parts[1], draft.parts[2]
    space = tooth_angle(ring.hole, draft.placements[1], 0.0, 2 * math.pi / 30)  # the hole's farthest reach
    tooth = tooth_angle(gear3.outer, draft.placements[2], 0.0, 2 * math.pi / 14)
    assert R2_IN * space == pytest.approx(R3 * tooth, abs=0.01 * M)


def test_speeds_by_stopping_against_closed_forms(train):
    """Relative to the carrier (ω = −20 rpm in the seed's sense): gear1 80 rpm; the ring −80·15/30
    = −40 rpm; gear3, turning inside, the same way: −40·22.5/10.5; each plus ω back."""
    params, draft = train
    block = draft.data["compound"]
    carrier = -params.carrier_rpm
    ring = -(params.gear1_rpm - carrier) * R1 / R2_OUT
    gear3 = ring * R2_IN / R3
    assert [g["omega_rpm"] for g in draft.data["gears"]] == pytest.approx(
        [params.gear1_rpm, ring + carrier, gear3 + carrier], rel=1e-12
    )
    assert block["omega3_rpm"] == pytest.approx(gear3 + carrier, rel=1e-12)
    assert block["omega3_by_velocities"] == pytest.approx(block["omega3"], rel=1e-12)
    assert block["radius_ratio"] == R2_IN / R2_OUT
    # the seed's formula, ω3 = −(ω1·r1 + ω·r1 + ω·r3)/r3, its ω the crank's rate as given
    w, w1 = params.carrier_rpm, params.gear1_rpm
    seed = -(w1 * R1 + w * R1 + w * R3) / R3
    assert block["omega3_seed_formula_rpm"] == pytest.approx(seed, rel=1e-12)
    assert any(f.code == "paper-claim" and f.where == "train.compound" for f in draft.findings)


def test_the_wall_between_the_toothings_is_root_to_root(train):
    """Outer root circle minus inner root circle: (30 − 1.25·1.5) − (22.5 + 1.25·1.5) = 3.75 mm."""
    _, draft = train
    entry = draft.data["gears"][1]
    assert entry["wall"] == pytest.approx((R2_OUT - 1.25 * M) - (R2_IN + 1.25 * M), abs=1e-12)
    assert (entry["inner_teeth"], entry["inner_pitch_radius"]) == (30, R2_IN)
