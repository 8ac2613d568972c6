"""Checks that can fail a build: exit status 3 for an interfering assembly or a jamming band,
``--allow CODE`` to accept one by name; ``design.ok`` and ``raise_failures`` in the API; the
library quiet on stderr."""

import contextlib
import io
import json
import logging

import pytest

import gearcad
from gearcad import batch
from gearcad.cli import main
from gearcad.errors import ChecksFailed

from .conftest import ROOT

CENTRE = str(ROOT / "profiles" / "elliptic_centre.toml")
OVERRIDES = {"gear1.eccentricity": 0.95, "teeth.count": 40, "output.tolerance": 0.01}
OVERRIDES |= {"output.charts": False, "output.animation": False, "output.formats": ["svg"]}
"""An interfering pair (sharp ends, many teeth) and a quick build of it (no chart data, SVG only)."""
INTERFERES = [arg for key, value in OVERRIDES.items() for arg in ("--set", f"{key}={json.dumps(value)}")]


@pytest.fixture(scope="module")
def interfering():
    """The interfering design, and what designing it wrote to stderr with no logging set up at
    all (no handler on the root logger, gearcad's at WARNING)."""
    root, lib = logging.getLogger(), logging.getLogger("gearcad")
    handlers, level = root.handlers[:], lib.level
    root.handlers, lib.level = [], logging.WARNING
    try:
        with contextlib.redirect_stderr(io.StringIO()) as err:
            d = gearcad.design(gearcad.load_profile(CENTRE, OVERRIDES))
    finally:
        root.handlers, lib.level = handlers, level
    return d, err.getvalue()


@pytest.fixture
def designed_once(monkeypatch, interfering):
    """The command line's design of :data:`OVERRIDES` is the module's (the same params give the
    same design: it is made once); what the command prints, exits with and writes is its own.  A
    command line that read other params would design anew, which fails the test."""
    (d, _), params = interfering, gearcad.load_profile(CENTRE, OVERRIDES)
    anew, design = [], batch.design

    def once(asked, stage="full"):
        if (asked, stage) == (params, "full"):
            return d
        anew.append(asked.name)
        return design(asked, stage)

    monkeypatch.setattr(batch, "design", once)
    yield
    assert anew == []  # --set KEY=VALUE read the same params as OVERRIDES: the design was shared


def test_an_interfering_design_is_not_ok_and_raises_unless_allowed(interfering):
    interfering, _ = interfering
    assert not interfering.ok and interfering.report()["ok"] is False
    # the band of the drawn pair bites beyond the writing tolerance too
    assert [f.code for f in interfering.failures()] == ["interference", "jams"]
    with pytest.raises(ChecksFailed, match=r"elliptic_centre: \[interference\] the toothed pair overlaps") as exc:
        interfering.raise_failures()
    assert exc.value.exit_code == 3 and exc.value.findings[0].code == "interference"
    assert interfering.raise_failures(allow=["interference", "jams"]) is interfering
    with pytest.raises(gearcad.ProfileError, match="not a finding code"):
        interfering.raise_failures(allow=["interferense"])


def test_check_exits_3_on_interference_and_build_0_when_allowed(tmp_path, capsys, designed_once):
    assert main(["check", CENTRE, *INTERFERES]) == 3
    err = capsys.readouterr().err
    assert "check failed: elliptic_centre: [interference]" in err and "--allow interference" in err
    out = tmp_path / "out"
    allow = ["--allow", "interference", "--allow", "jams"]
    assert main(["build", CENTRE, *INTERFERES, *allow, "--out", str(out)]) == 0
    assert (out / "elliptic_centre" / "report.json").is_file()


def test_build_writes_the_files_and_exits_3(tmp_path, capsys, designed_once):
    out = tmp_path / "out"
    assert main(["build", CENTRE, *INTERFERES, "--out", str(out)]) == 3
    assert (out / "elliptic_centre" / "report.json").is_file()
    assert "[interference]" in capsys.readouterr().err


def test_an_unknown_allowed_code_is_bad_input(tmp_path, capsys):
    assert main(["build", CENTRE, "--allow", "bogus", "--out", str(tmp_path / "out")]) == 2
    assert "--allow 'bogus': not a finding code" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_design_from_python_prints_nothing(interfering):
    """Findings are returned, not printed: with no logging set up at all a design with findings
    (and failures) writes nothing to stderr."""
    d, err = interfering
    assert d.findings and err == ""
