"""The finishing line (gearcad.mechanisms.finish): any draft made into the complete design — parts
with their cut paths, the assembly proven by one overlap policy — tested on a hand-made draft of
two discs, whose overlap is a closed form (the lens of two circles)."""

import math

import numpy as np
import pytest

from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.rings import circle_ring
from gearcad.mechanisms.finish import Contact, Draft, PartSpec, finish
from gearcad.mechanisms.parts import Placement
from gearcad.tolerances import budget

from .conftest import COARSE, profile

R = 10.0


@pytest.fixture(scope="module")
def params():
    return profile("rolling_wheel", {**COARSE, "output.formats": ["svg"]})


def _discs(params, distance: float, length: float = 0.0) -> Draft:
    fine = budget(params.output.tolerance).fine
    disc = circle_ring(R, fine)
    return Draft(
        params=params,
        mechanism="discs",
        summary="two discs",
        findings=(),
        parts=(PartSpec("a", disc), PartSpec("b", disc)),
        placements=(Placement("a"), Placement("b", 0.3, (distance, 0.0))),
        contacts=(Contact(0, 1, length=length),),
        data={},
        units={},
        where="discs",
    )


def _lens(r: float, d: float) -> float:
    """The area two circles of radius r, d apart, share."""
    return 2 * r * r * math.acos(d / (2 * r)) - d / 2 * math.sqrt(4 * r * r - d * d)


def test_apart_they_fit_and_every_part_is_cut(params):
    d = finish(_discs(params, 2 * R + 1.0))
    assert d.assembly.fits and d.assembly.overlap == 0.0 and d.findings == ()
    assert [p.name for p in d.parts()] == ["a", "b"]
    for part in d.parts():  # each cut path a circle of radius R, kerf 0
        (ring,) = [r for r in part.cut if np.hypot(*r.vertices[0]) > 5]
        assert np.hypot(*arc_points(ring, 1e-4).T) == pytest.approx(R, abs=params.output.tolerance)
    assert {s.part for s in d.sheet} == {"a", "b"} and d.plate == ()  # svg asked, no 3mf


def test_overlapping_discs_are_measured_and_reported(params):
    distance = 2 * R - 0.5
    d = finish(_discs(params, distance))
    assert d.assembly.overlap == pytest.approx(_lens(R, distance), rel=0.01)
    assert not d.assembly.fits and d.assembly.allowed == 0.0
    (found,) = d.findings
    assert (found.code, found.where) == ("interference", "discs")


def test_plain_outlines_may_overlap_by_the_tolerance_along_their_contact(params):
    """A contact of length L may overlap 2·tol·L: a lens within it fits, one beyond it does not
    (the lens measured on outlines within the tolerance is within 1 % of the exact one)."""
    tol = params.output.tolerance
    distance = 2 * R - 0.5
    lens = _lens(R, distance)
    fits = finish(_discs(params, distance, length=1.1 * lens / (2 * tol)))
    assert fits.assembly.allowed == pytest.approx(1.1 * lens, rel=1e-12) and fits.assembly.fits
    assert not finish(_discs(params, distance, length=0.9 * lens / (2 * tol))).assembly.fits


# ---------------------------------------------------------------------------------------------
# every touch's proof fails both ways: moved apart and moved together, each verdict flips


def _pair(params, distance: float, contact: Contact, ring=None, angle: float = 0.3) -> Draft:
    ring = circle_ring(R, budget(params.output.tolerance).fine) if ring is None else ring
    return Draft(
        params=params,
        mechanism="discs",
        summary="two parts",
        findings=(),
        parts=(PartSpec("a", ring), PartSpec("b", ring)),
        placements=(Placement("a"), Placement("b", angle, (distance, 0.0))),
        contacts=(contact,),
        data={},
        units={},
        where="pair",
    )


def test_apart_must_not_touch_and_only_that(params):
    apart = Contact(0, 1, touch="apart")
    assert finish(_pair(params, 2 * R + 10.0, apart)).assembly.fits  # 10 mm away: fine, apart
    near = finish(_pair(params, 2 * R - 0.2, apart))
    assert not near.assembly.fits and near.assembly.gap is None and near.findings[0].code == "interference"


def test_rolling_wheels_must_touch_and_not_bite(params):
    """Smooth wheels roll on each other: touching they fit; 10 mm apart they do NOT (a gap wider
    than 2·tol); pressed 0.5 mm together they overlap by a lens far beyond 2·tol·L."""
    rolling = Contact(0, 1, length=R, touch="rolling")
    tol = params.output.tolerance
    touching = finish(_pair(params, 2 * R, rolling)).assembly
    assert touching.fits and touching.gap <= 2 * tol and touching.allowed_gap == pytest.approx(2 * tol)
    far = finish(_pair(params, 2 * R + 10.0, rolling))
    assert not far.assembly.fits and far.assembly.overlap == 0.0
    assert far.assembly.gap == pytest.approx(10.0, abs=tol)  # the gap between two circles: d − 2R
    assert "no contact" in far.findings[0].message
    just_apart = finish(_pair(params, 2 * R + 3 * tol, rolling)).assembly  # a gap of 3·tol: too wide
    assert not just_apart.fits and just_apart.overlap == 0.0
    pressed = finish(_pair(params, 2 * R - 0.5, rolling)).assembly
    assert not pressed.fits and pressed.overlap == pytest.approx(_lens(R, 2 * R - 0.5), rel=0.01)
    assert far.assembly.as_dict()["gap"] > 9
    assert "gap" not in finish(_pair(params, 2 * R, Contact(0, 1))).assembly.as_dict()  # only a rolling one


def _toothed(n: int, depth: float) -> np.ndarray:
    """A wheel of ``n`` smooth teeth, r = R + depth·cos(nθ), counter-clockwise (36 points a tooth)."""
    theta = np.linspace(0.0, 2 * np.pi, 36 * n, endpoint=False)
    r = R + depth * np.cos(n * theta)
    return np.column_stack([r * np.cos(theta), r * np.sin(theta)])


def test_a_mesh_must_bite_when_nudged_and_not_beyond_its_allowance(params):
    """Two wheels of 20 rounded teeth, a tip of one in a space of the other on the line of
    centres, 2R apart: they touch at a point and bite when turned, so they fit.  10 mm apart
    they still do not overlap, but turned they do not bite: they do NOT fit.  1 mm closer the
    teeth overlap: they do not fit either."""
    n, module = 20, 2 * R / 20
    ring = _toothed(n, 0.15 * module)
    mesh = Contact(0, 1, module=module, radius=R, touch="mesh")
    facing = np.pi + np.pi / n  # the mate's space faces the first's tip at θ = 0

    def proof(distance):
        return finish(_pair(params, distance, mesh, ring=ring, angle=facing))

    meshed = proof(2 * R).assembly
    assert meshed.overlap <= meshed.allowed < meshed.nudged and meshed.fits
    far = proof(2 * R + 10.0)
    assert far.assembly.overlap == 0.0 and far.assembly.nudged == 0.0 and not far.assembly.fits
    assert "do not engage" in far.findings[0].message
    pressed = proof(2 * R - 1.0).assembly
    assert pressed.overlap > pressed.allowed and not pressed.fits


def test_a_contact_says_what_touch_it_is():
    assert Contact(0, 1, module=1.0).touch == "mesh" and Contact(0, 1, length=2.0).touch == "rolling"
    assert Contact(0, 1).touch == "apart"
    with pytest.raises(ValueError, match="touch"):
        Contact(0, 1, touch="glued")
    with pytest.raises(ValueError, match="a rolling contact"):
        Contact(0, 1, touch="rolling")  # rolling along no length
