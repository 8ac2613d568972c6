"""The gear-pair mechanism (gearcad.mechanisms.gear_pair): its draft for the circular reference
pair (module 2, 20:40 teeth) against the textbook — centre distance, teeth, phasing, the mesh
proven over a cycle, the motion — and the untoothed pitch curves rolling on each other."""

import math

import numpy as np
import pytest

from gearcad.geometry.outline import ring_area
from gearcad.mechanisms import gear_pair

from .conftest import COARSE, drafted, profile, tooth_angle

M, Z1, Z2, RPM = 2.0, 20, 40, 100.0
R1, R2 = M * Z1 / 2, M * Z2 / 2  # 20 and 40 mm


@pytest.fixture(scope="module")
def spur():
    return drafted("spur_pair", gear_pair.design)


def test_gears_sit_a_sum_of_pitch_radii_apart(spur):
    _, draft = spur
    assert [s.name for s in draft.parts] == ["pinion", "gear"]
    assert draft.placements[0].offset == (0.0, 0.0)
    assert draft.placements[1].offset == pytest.approx((R1 + R2, 0.0), abs=1e-9)
    assert [pl.angle for pl in draft.placements] == [0.0, 0.0]


@pytest.mark.parametrize("k,r,z", [(0, R1, Z1), (1, R2, Z2)], ids=["pinion", "gear"])
def test_teeth_between_root_and_tip_circles_with_the_pitch_circle_engraved(spur, k, r, z):
    _, draft = spur
    spec = draft.parts[k]
    radius = np.hypot(*spec.outer.T)
    assert (radius.min(), radius.max()) == pytest.approx((r - 1.25 * M, r + M), abs=1e-6)
    outside = radius > r
    assert np.count_nonzero(outside & ~np.roll(outside, 1)) == z
    assert ring_area(spec.outer) > 0
    assert np.hypot(*spec.marks[0].T) == pytest.approx(r, abs=1e-9)
    assert spec.wall == M


def test_a_tooth_meets_a_space_on_the_line_of_centres(spur):
    _, draft = spur
    tooth = tooth_angle(draft.parts[0].outer, draft.placements[0], 0.0, 2 * math.pi / Z1)
    space = tooth_angle(draft.parts[1].outer, draft.placements[1], math.pi, 2 * math.pi / Z2, space=True)
    assert R1 * tooth == pytest.approx(-R2 * (space - math.pi), abs=0.01 * M)


def test_the_mesh_is_proven_over_a_cycle_not_nudged(spur):
    """The pair proves its own mesh at every position (a Proof), so the contact asks no nudge; the
    teeth touch nowhere as placed, and turned a little they bite."""
    _, draft = spur
    (contact,) = draft.contacts
    assert (contact.first, contact.second, contact.module, contact.nudge) == (0, 1, M, False)
    (mesh,) = draft.proofs
    assert mesh.positions >= Z1  # at least one position per pinion tooth
    assert mesh.max_overlap <= mesh.allowed_overlap < mesh.nudged_min_overlap


def test_motion_is_half_the_driver_angle(spur):
    _, draft = spur
    (table,) = draft.tables
    rows = dict(zip(table.columns, table.rows.T))
    np.testing.assert_allclose(rows["follower_angle_rad"], rows["driver_angle_rad"] * R1 / R2, atol=1e-12)
    np.testing.assert_allclose(rows["ratio"], R1 / R2, rtol=1e-12)
    np.testing.assert_allclose(rows["follower_speed_rad_s"], RPM * 2 * math.pi / 60 * R1 / R2, rtol=1e-12)
    angles = draft.motion.angles  # the driver turns clockwise, the mate the other way
    np.testing.assert_allclose(angles[:, 1], -angles[:, 0] * R1 / R2, atol=1e-12)


def test_without_teeth_the_parts_are_the_pitch_circles_rolling_on_each_other():
    params = profile("spur_pair", COARSE, unset=["teeth"])
    draft = gear_pair.design(params)
    for spec, r in zip(draft.parts, (R1, R2)):
        assert np.hypot(*spec.outer.T) == pytest.approx(r, abs=1e-9)
    (contact,) = draft.contacts
    # they touch along about the smaller radius, and may overlap by the tolerance along it
    assert (contact.module, contact.length) == (None, R1)
    assert draft.proofs == ()
