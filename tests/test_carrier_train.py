"""The carrier-train mechanism (gearcad.mechanisms.carrier_train): its draft against closed forms —
where the gears sit, their teeth, which of them mesh, how they are phased, their speeds."""

import math

import numpy as np
import pytest

from gearcad.geometry.outline import ring_area
from gearcad.mechanisms import carrier_train

from .conftest import drafted, tooth_angle

M = 1.5  # both examples' module
RPM = 2 * math.pi / 60


@pytest.fixture(scope="module")
def external():
    """Sun 20, idler 14, planet 26 teeth, all external, on a crank (planetary_external.toml)."""
    return drafted("planetary_external", carrier_train.design)


def _tips(ring: np.ndarray, pitch_radius: float) -> int:
    """The teeth of a ring: how often it crosses out past its pitch circle."""
    outside = np.hypot(ring[:, 0], ring[:, 1]) > pitch_radius
    return int(np.count_nonzero(outside & ~np.roll(outside, 1)))


def test_gears_sit_a_sum_of_pitch_radii_apart_and_each_mesh_is_a_contact(external):
    _, draft = external
    radii = [M * z / 2 for z in (20, 14, 26)]  # 15, 10.5, 19.5 mm
    assert [s.name for s in draft.parts] == ["sun", "idler", "planet"]
    assert [pl.offset for pl in draft.placements] == [(0.0, 0.0), (25.5, 0.0), (55.5, 0.0)]
    assert [(c.first, c.second, c.module) for c in draft.contacts] == [(0, 1, M), (1, 2, M)]
    # each mate is nudged on its own pitch circle
    assert [c.radius for c in draft.contacts] == pytest.approx(radii[1:], abs=1e-12)
    assert all(c.nudge for c in draft.contacts)


@pytest.mark.parametrize("k,teeth", [(0, 20), (1, 14), (2, 26)])
def test_each_gear_has_its_teeth_between_root_and_tip_circles(external, k, teeth):
    """Rack-cut teeth: tips at r + m, roots at r − 1.25 m, z of them, counter-clockwise."""
    _, draft = external
    spec, r = draft.parts[k], M * teeth / 2
    radius = np.hypot(*spec.outer.T)
    assert radius.max() == pytest.approx(r + M, abs=1e-9)
    assert radius.min() == pytest.approx(r - 1.25 * M, abs=1e-9)
    assert _tips(spec.outer, r) == teeth
    assert ring_area(spec.outer) > 0
    # the pitch circle is engraved; the shaft hole is the profile's bore
    assert np.hypot(*spec.marks[0].T) == pytest.approx(r, abs=1e-9)
    assert spec.bore.diameter == 5.0 and spec.wall == M


def test_a_tooth_meets_a_space_at_every_contact(external):
    """Found from the outlines alone: the first gear's tooth nearest the line of centres and the
    mate's nearest tooth space lie the same arc from the contact, on opposite sides of the line
    (external pitch circles run opposite ways)."""
    _, draft = external
    for c in draft.contacts:
        a, b = (draft.parts[i] for i in (c.first, c.second))
        za, zb = (_tips(s.outer, np.hypot(*s.marks[0][0])) for s in (a, b))
        ra, rb = (float(np.hypot(*s.marks[0][0])) for s in (a, b))
        tooth = tooth_angle(a.outer, draft.placements[c.first], 0.0, 2 * math.pi / za)
        space = tooth_angle(b.outer, draft.placements[c.second], math.pi, 2 * math.pi / zb, space=True)
        assert ra * tooth == pytest.approx(-rb * (space - math.pi), abs=0.01 * M), (a.name, b.name)


def test_speeds_follow_willis_along_the_train(external):
    """Relative to the carrier (the seed's sense: the crank's ω projected as −ω) each external mesh
    turns its mate the other way at the ratio of pitch radii."""
    params, draft = external
    gears = draft.data["gears"]
    carrier = -params.carrier_rpm * RPM
    relative = [params.gear1_rpm * RPM - carrier]
    for r_from, r_to in [(15.0, 10.5), (10.5, 19.5)]:
        relative.append(-relative[-1] * r_from / r_to)
    assert [g["omega_relative_to_carrier"] for g in gears] == pytest.approx(relative, rel=1e-12)
    assert [g["omega"] for g in gears] == pytest.approx([w + carrier for w in relative], rel=1e-12)
    assert draft.data["train"]["velocity_analysis_difference"] < 1e-12


def test_an_internal_mesh_makes_a_ring_with_a_rim():
    """planetary_internal: the ring's teeth are a clockwise hole reaching from r − m to r + 1.25 m,
    inside a rim 3.75 m beyond the pitch circle; its centre lies a difference of radii away."""
    params, draft = drafted("planetary_internal", carrier_train.design)
    rings = [s for s in draft.parts if s.hole is not None]
    assert len(rings) == 1
    (ring,) = rings
    k = [s.name for s in draft.parts].index(ring.name)
    z, m = params.teeth[k], params.modules[k]
    r = m * z / 2
    hole = np.hypot(*ring.hole.T)
    assert ring_area(ring.hole) < 0 and _tips(ring.hole, r) == z
    assert (hole.min(), hole.max()) == pytest.approx((r - m, r + 1.25 * m), abs=1e-9)
    assert np.hypot(*ring.outer.T) == pytest.approx(r + 3.75 * m, abs=1e-9)
    centres = [pl.offset[0] for pl in draft.placements]
    for j, mesh in enumerate(params.meshes):
        r_from, r_to = (params.modules[i] * params.teeth[i] / 2 for i in (j, j + 1))
        assert abs(centres[j + 1] - centres[j]) == pytest.approx(
            r_from + r_to if mesh == "external" else abs(r_from - r_to), abs=1e-12
        )


def test_a_wide_backlash_still_engages_when_turned():
    """The nudged test turns each mate beyond the mesh's designed play: with train.backlash 0.6 mm
    (what FDM's fit chooses) a turn of the budget's 0.2 mm alone never reached the mate's flank and
    the check said the teeth do not engage (exit 3 for every printed train)."""
    from gearcad.fitting import design

    from .conftest import QUICK, profile

    done = design(profile("planetary_external", {**QUICK, "train.backlash": 0.6}))
    assert done.assembly.nudged > done.assembly.allowed
    assert not [f for f in done.findings if f.code == "interference"]
