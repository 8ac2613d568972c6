"""The Python API: what the README's "Python" section shows runs as written, and ``check``
refuses exactly what ``build`` refuses."""

import re
import shutil

import pytest

import gearcad
from gearcad.cli import main

from .conftest import ROOT


def _readme_python_blocks() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Python", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, flags=re.S)


def test_the_readme_example_runs(tmp_path, monkeypatch):
    blocks = _readme_python_blocks()
    assert blocks, "the README has a Python section with an example"
    shutil.copytree(ROOT / "profiles", tmp_path / "profiles")
    monkeypatch.chdir(tmp_path)
    scope = {"__name__": "readme_example"}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), scope)  # noqa: S102 - our own README
    for name, test in list(scope.items()):
        if name.startswith("test_") and callable(test):
            test()
    assert (tmp_path / "out" / "spur_pair" / "report.json").is_file()


def test_api_exports():
    assert {"load_profile", "parse_profile", "design", "check", "build", "profile_schema"} <= set(gearcad.__all__)
    for name in gearcad.__all__:
        assert getattr(gearcad, name) is not None
    with pytest.raises(AttributeError):
        gearcad.no_such_thing  # noqa: B018


def test_design_gives_parts_findings_and_report():
    d = gearcad.design(ROOT / "profiles" / "spur_pair.toml")
    assert [p.name for p in d.parts()] == ["pinion", "gear"]
    report = d.report()
    assert report["schema"] == 2 and report["mechanism"] == "gear-pair"
    assert {"parts", "assembly", "warnings", "files", "output"} <= set(report)
    for part, block in zip(d.parts(), report["parts"]):
        outer = part.outline.outer
        assert outer.dtype.name == "float64" and outer.shape[1] == 2
        assert block["area"] == pytest.approx(part.outline.area) and block["area"] > 0
    assert report["assembly"]["fits"]


def test_params_built_in_python_are_validated():
    with pytest.raises(gearcad.ProfileError, match=r"gear1\.radius"):
        gearcad.parse_profile({"gear1": {"curve": "circle", "radius": -1}})
    with pytest.raises(gearcad.ProfileError):
        gearcad.load_profile(ROOT / "profiles" / "spur_pair.toml", overrides={"teeth.pressure_angle_deg": 90})


# the same list for check and build: both accept or both refuse with the same message
OVERRIDES = [
    [],
    ["bore.diameter=200"],
    ["output.chamfer=2.4"],
    ["output.chamfer=1.0", "output.thickness=1.5"],
    ["output.kerf=1.9", "output.tolerance=0.01"],
    ["pair.center_distance=49"],
    ["teeth.clearance=5"],
]


@pytest.mark.parametrize("overrides", OVERRIDES, ids=lambda o: " ".join(o) or "as written")
def test_check_and_build_agree(tmp_path, capsys, overrides):
    profile = str(ROOT / "profiles" / "elliptic_focus.toml")
    sets = [arg for o in overrides for arg in ("--set", o)]
    quick = ["--set", "output.charts=false", "--set", "output.animation=false", "--set", 'output.formats=["dxf"]']
    checked = main(["check", profile, *sets, *quick])
    check_err = capsys.readouterr().err
    built = main(["build", profile, "--out", str(tmp_path / "out"), *sets, *quick])
    build_err = capsys.readouterr().err
    assert checked == built, (check_err, build_err)
    assert check_err == build_err
    if built != 0:
        assert len(build_err.strip().splitlines()) == 1 and not (tmp_path / "out").exists()


@pytest.mark.parametrize("profile", sorted((ROOT / "profiles").glob("*.toml")), ids=lambda p: p.stem)
def test_check_proves_every_assembly(profile, capsys):
    """``gearcad check`` prints the interference figure of every mechanism (at a coarse tolerance:
    the proof is the same, on fewer vertices; the build at the profile's own is proved by the
    ``built`` fixture)."""
    assert main(["check", str(profile), "--set", "output.tolerance=0.01"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"overlap [0-9.e+-]+ mm²", out), out
