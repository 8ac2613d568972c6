"""The rolling-wheel mechanism (gearcad.mechanisms.rolling_wheel): its draft — two plain wheels
that must not touch, the rack's length and the motion — against closed forms (seed 000)."""

import math

import numpy as np
import pytest

from gearcad.geometry.outline import ring_area
from gearcad.mechanisms import rolling_wheel
from gearcad.tolerances import budget

from .conftest import drafted


@pytest.fixture(scope="module")
def drive():
    """rolling_wheel.toml: driver r = 20, rolling wheel R = 60, centres L = 300 across and H = 150
    up; the wheel rolls 200 mm towards the driver."""
    return drafted("rolling_wheel", rolling_wheel.design)


r, R, L, H, TRAVEL = 20.0, 60.0, 300.0, 150.0, 200.0


def test_two_round_wheels_where_the_drive_puts_them(drive):
    params, draft = drive
    fine = budget(params.output.tolerance).fine
    assert [s.name for s in draft.parts] == ["wheel1", "wheel2"]
    for spec, radius in zip(draft.parts, (r, R)):
        assert np.hypot(*spec.outer.T) == pytest.approx(radius, abs=1e-9)  # vertices on the circle
        # chords within the fine tolerance: the area falls short of πr² by less than the sag strip
        area = ring_area(spec.outer)
        assert 0 < math.pi * radius**2 - area <= 2 * math.pi * radius * fine
        assert spec.marks == () and spec.hole is None
    assert [pl.offset for pl in draft.placements] == [(L, H), (0.0, 0.0)]


def test_the_wheels_must_not_touch_and_do_not(drive):
    _, draft = drive
    (contact,) = draft.contacts
    assert (contact.first, contact.second, contact.module, contact.length) == (0, 1, None, 0.0)
    assert math.hypot(L, H) > r + R  # so the proof's "no overlap at all" can hold


def test_rack_length_and_ratios_by_closed_form(drive):
    _, draft = drive
    geometry, motion = draft.data["geometry"], draft.data["motion"]
    # eq. 1: the rack from the driver's tangent point to the wheel's, l² = L² + H² − (R − r)²
    assert geometry["rack_length_start"] == pytest.approx(math.sqrt(L**2 + H**2 - (R - r) ** 2), rel=1e-12)
    assert geometry["rack_length_paper_eq2"] == pytest.approx(math.sqrt(L**2 + H**2 + (R - r) ** 2), rel=1e-12)
    assert motion["ratio_horizontal_rack"] == r / (2 * R)
    # rolling without slip: over the travel the wheel turns travel / R
    assert motion["phi2_end"] == pytest.approx(TRAVEL / R, rel=1e-9)
    assert motion["law_difference"] < 1e-9
    assert any(f.code == "paper-formula" for f in draft.findings)  # the misprinted eq. 2


def test_a_horizontal_rack_gives_the_linear_law():
    """H = R − r: the rack stays level and φ2 = φ1·r/(2R) exactly, ω3 = 0."""
    motion = drafted("rolling_wheel", rolling_wheel.design, {"drive.H": R - r})[1].detail
    np.testing.assert_allclose(motion.by_contour, motion.phi1 * r / (2 * R), rtol=1e-12)
    assert not motion.omega3.any()
