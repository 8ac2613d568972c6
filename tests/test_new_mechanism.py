"""A mechanism added through the registry alone (issue 36): two smooth friction wheels, defined
here and nowhere else — its params model registered in ``profiles.MODEL_OF``, its entry in
``mechanisms.MECHANISMS`` — is designed, proven both ways, built, paged, fuzzed and documented
without a line of gearcad changed.  The registration is undone after each test."""

import json
import math
import sys
from typing import Literal

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pydantic import Field

import gearcad
from gearcad import profiles
from gearcad.geometry.rings import circle_ring
from gearcad.mechanisms import MECHANISMS
from gearcad.mechanisms.base import Motion
from gearcad.mechanisms.finish import Contact, Draft, PartSpec
from gearcad.mechanisms.parts import Placement
from gearcad.mechanisms.registry import Mechanism
from gearcad.profiles.common import OutputParams, ParamsModel
from gearcad.profiles.reference import reference_markdown
from gearcad.tolerances import budget

from .test_fuzz import run_check  # imported before any registration: its KINDS are the registry's own

NAME = "friction-pair"


class FrictionPairParams(ParamsModel):
    """Two smooth wheels rolling on each other."""

    name: str = "profile"
    title: str = ""
    mechanism: Literal["friction-pair"] = "friction-pair"
    r1: float = Field(gt=1.0, le=500.0)
    """The driver's radius, mm."""
    r2: float = Field(gt=1.0, le=500.0)
    """The follower's radius, mm."""
    gap: float = Field(default=0.0, ge=-1.0, le=50.0)
    """How much further apart than r1 + r2 the wheels stand, mm (a fault, for the test)."""
    output: OutputParams = OutputParams()


def design(p: FrictionPairParams) -> Draft:
    """The friction pair's draft: two discs touching on the line of centres, the follower turning
    r1/r2 as fast the other way."""
    fine = budget(p.output.tolerance).fine
    parts = (PartSpec("driver", circle_ring(p.r1, fine)), PartSpec("follower", circle_ring(p.r2, fine)))
    e = p.r1 + p.r2 + p.gap
    phi = np.linspace(0.0, 2 * math.pi, 24, endpoint=False)
    return Draft(
        params=p,
        mechanism=NAME,
        summary=f"friction pair: E = {e:g} mm, ratio {p.r1 / p.r2:.4g}",
        findings=(),
        parts=parts,
        placements=(Placement("driver"), Placement("follower", 0.0, (e, 0.0))),
        contacts=(Contact(0, 1, length=min(p.r1, p.r2), touch="rolling"),),
        data={"wheels": {"r1": p.r1, "r2": p.r2, "center_distance": e}},
        units={"length": "mm"},
        motion=Motion(("driver", "follower"), np.column_stack([phi, -phi * p.r1 / p.r2])),
        placed="the two smooth wheels touch where they roll on each other",
        where="wheels",
    )


@pytest.fixture
def registered(monkeypatch):
    """The friction pair registered for one test (the registry's two tables, nothing else)."""
    monkeypatch.setitem(profiles.MODEL_OF, NAME, FrictionPairParams)
    monkeypatch.setitem(MECHANISMS, NAME, Mechanism(NAME, __name__))
    return NAME


def _profile(**keys) -> dict:
    return {"mechanism": NAME, "name": "wheels", "r1": 20.0, "r2": 30.0, "output": {"tolerance": 0.02}, **keys}


def test_designed_and_proven_both_ways(registered):
    d = gearcad.design(_profile())
    assert d.mechanism == NAME and d.assembly.fits and d.failures() == ()
    assert d.assembly.gap <= 2 * 0.02 and d.assembly.overlap <= d.assembly.allowed
    far = gearcad.design(_profile(gap=10.0))  # a smooth wheel 10 mm away must NOT fit
    assert not far.assembly.fits and far.assembly.gap == pytest.approx(10.0, abs=0.02)
    assert [f.code for f in far.failures()] == ["interference"]
    pressed = gearcad.design(_profile(gap=-0.5))
    assert not pressed.assembly.fits and pressed.assembly.overlap > pressed.assembly.allowed


def test_built_and_paged(registered, tmp_path):
    data = _profile(output={"tolerance": 0.02, "formats": ["svg", "dxf"], "animation": False, "charts": False})
    (result,) = gearcad.build([data], tmp_path)
    folder = tmp_path / "wheels"
    assert (folder / "driver.svg").is_file() and (folder / "follower.dxf").is_file()
    report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    assert report["mechanism"] == NAME and report["assembly"]["fits"] and "gap" in report["assembly"]
    page = (folder / "index.html").read_text(encoding="utf-8")
    assert "the two smooth wheels touch where they roll on each other" in page
    assert "meshing parts touch" not in page


def test_fuzzed(registered):
    outcomes = []

    @settings(max_examples=6, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
    @given(r1=st.floats(-5, 80), r2=st.floats(0.5, 80), gap=st.sampled_from([0.0, 10.0, "x"]))
    def run(r1, r2, gap):
        outcomes.append(run_check(_profile(r1=r1, r2=r2, gap=gap)))

    run()
    assert "design" in outcomes and any(o.startswith("ProfileError") for o in outcomes)


def test_documented(registered):
    schema = gearcad.profile_schema()
    assert any(
        d.get("title") == "FrictionPairParams" or "r2" in d.get("properties", {}) for d in schema["$defs"].values()
    )
    page = reference_markdown(schema)
    assert f"## {NAME}" in page and "| `r2` | number > 1, ≤ 500 |" in page


def test_the_registration_is_undone():
    assert NAME not in MECHANISMS and NAME not in profiles.MODEL_OF and sys.modules[__name__].design
