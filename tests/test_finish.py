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
