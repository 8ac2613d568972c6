"""The Python API: what the README's "Python" section shows runs as written, and ``check``
refuses exactly what ``build`` refuses."""

import json
import math
import re
import shutil

import pytest

import gearcad
from gearcad.cli import main
from gearcad.mechanisms import MECHANISMS

from .conftest import COARSE, PROFILES, ROOT, profile

LEAN = ["output.charts=false", "output.animation=false", 'output.formats=["dxf"]', "output.tolerance=0.01"]
"""A build that writes only DXF files at 0.01 mm (the ``built`` fixture writes every file once)."""
COARSE_SET = LEAN[:2] + LEAN[3:]


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
    d = gearcad.design(profile("spur_pair", COARSE))
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


# the same list for check and build: both accept or both refuse with the same message (at 0.01 mm:
# where they refuse and what they say does not hang on the tolerance; the kerf case sets it itself)
OVERRIDES = [
    ([], 0),
    (["bore.diameter=200"], 2),  # a bore wider than the gear
    (["output.chamfer=2.4"], 2),  # deeper than the teeth
    (["output.chamfer=1.0", "output.thickness=1.5"], 2),  # more than half the thickness
    (["output.kerf=1.9", "output.tolerance=0.01"], 2),  # a beam wider than a tooth space
    (["pair.center_distance=49"], 2),  # the pair cannot close there
    (["teeth.clearance=5"], 2),  # an offset that wears the teeth away
]


@pytest.mark.parametrize("overrides,code", OVERRIDES, ids=[" ".join(o) or "as written" for o, _ in OVERRIDES])
def test_check_and_build_agree(tmp_path, capsys, overrides, code):
    # the band bounded by the estimate (a third of the CPU of the theorem's, as written): what
    # the two must agree on is what they refuse, a design error here; the theorem's band of the
    # profile as written is the ``built`` report's (test_every_assembly_is_proved)
    path = str(ROOT / "profiles" / "elliptic_focus.toml")
    quick = [arg for o in (*LEAN, 'output.certificate="estimate"', *overrides) for arg in ("--set", o)]
    checked = main(["check", path, *quick])
    check_err = capsys.readouterr().err
    built = main(["build", path, "--out", str(tmp_path / "out"), *quick])
    build_err = capsys.readouterr().err
    assert checked == built == code, (check_err, build_err)
    assert check_err == build_err
    if built != 0:
        assert len(build_err.strip().splitlines()) == 1 and not (tmp_path / "out").exists()


def test_every_assembly_is_proved(built):
    """Every example's build proved its assembly at the profile's own tolerance: report.json's
    ``assembly`` block holds the figure ``gearcad check`` prints (the test below), within what
    is allowed."""
    assert PROFILES  # the loop below cannot pass by finding none
    for path in PROFILES:
        report = json.loads((built / path.stem / "report.json").read_text())
        block = report["assembly"]
        assert math.isfinite(block["overlap"]) and 0 <= block["overlap"] <= block["allowed_overlap"], path.stem
        assert block["fits"] and report["ok"], path.stem


def test_check_proves_the_assembly_of_each_mechanism(capsys):
    """``gearcad check`` prints the interference figure of every mechanism (one profile of each,
    at 0.05 mm: the proof is the same, on fewer vertices — 7 CPU-s for the six, 10 at 0.01 mm;
    every profile's at its own tolerance is in its report.json, the test above).  The bands'
    least play bounded by the estimate, not the theorem: the assembly's figure is the same (the
    theorem's band of every profile is in the ``built`` reports the test above reads), at 3.4
    CPU-s for the six designs instead of 5.9."""
    kinds = {"spur_pair": "gear-pair", "planetary_external": "carrier-train", "roller_body_m3": "roller-body"}
    kinds["rolling_wheel"] = "rolling-wheel"
    kinds["nc_internal"] = "nc-internal"
    kinds["nc_square"] = "nc-planetary"
    assert set(kinds.values()) == set(MECHANISMS)  # one of each: a new mechanism joins this list
    names = [str(ROOT / "profiles" / f"{name}.toml") for name in kinds]
    coarser = [*LEAN[:2], "output.tolerance=0.05", 'output.certificate="estimate"']
    assert main(["check", *names, *[arg for o in coarser for arg in ("--set", o)]]) == 0
    out = capsys.readouterr().out
    blocks = re.split(r"^(?=\S)", out, flags=re.M)
    assert [b.split(":")[0] for b in blocks if b] == list(kinds), out
    for block in filter(None, blocks):
        assert re.search(r"^  assembly: max overlap [0-9.e+-]+ mm²", block, flags=re.M), block
