"""The README and docs/: the reference covers every schema key, the numbers stated are the
golden ones, the quick start stays two commands, and the commands the README shows work."""

import json
import re
import tomllib

import numpy as np
import pytest

from gearcad.cli import main
from gearcad.profiles import load_profile, profile_schema
from gearcad.profiles.reference import reference_markdown

from .conftest import ROOT

DOCS = ROOT / "docs"
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _all_text() -> str:
    return README + "".join(p.read_text(encoding="utf-8") for p in sorted(DOCS.glob("*.md")))


def _keys(schema: dict, node: dict, prefix: str = "") -> set[str]:
    """Every dotted key under ``node``, walked here without gearcad's own walker."""
    while "$ref" in node:
        node = schema["$defs"][node["$ref"].split("/")[-1]]
    found = set()
    for variant in node.get("oneOf", ()):
        found |= _keys(schema, variant, prefix)
    for key, sub in node.get("properties", {}).items():
        found.add(prefix + key)
        found |= _keys(schema, sub, f"{prefix}{key}.")
    return found


@pytest.fixture(scope="module")
def schema() -> dict:
    return profile_schema()


def test_the_reference_names_every_key_of_the_schema(schema):
    keys = _keys(schema, schema)
    assert {"bore.flat", "bore.pilot", "output.sheet", "output.bed", "output.gap", "teeth.helix_angle_deg"} <= keys
    page = (DOCS / "reference.md").read_text(encoding="utf-8")
    missing = sorted(k for k in keys if f"| `{k}` |" not in page)
    assert not missing, f"docs/reference.md lacks {missing}: python3 -m gearcad.profiles.reference docs/reference.md"
    assert re.search(r"\| `bore\.flat` \|[^\n]*distance from the bore's centre", page)


def test_the_reference_is_what_the_schema_generates(schema):
    page = (DOCS / "reference.md").read_text(encoding="utf-8")
    assert page == reference_markdown(schema), "regenerate: python3 -m gearcad.profiles.reference docs/reference.md"


def test_every_golden_number_is_stated_in_the_readme_or_docs(golden):
    text = _all_text().replace("−", "-")
    unstated = []
    for block, entries in golden.items():
        for name, e in entries.items() if not block.startswith("_") else ():
            if "text" in e:
                ok = [e["text"] in _all_text()]
            else:
                digits = e.get("digits", 0)
                ok = [f"{v:.{digits}f}" in text or f"{v:g}" in text for v in np.atleast_1d(e["value"])]
            if not all(ok):
                unstated.append(f"{block}.{name}")
    assert not unstated


def test_the_readme_is_a_quick_start_that_links_its_docs():
    start = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    first_block = start.split("```")[1]
    assert [ln for ln in first_block.splitlines() if ln.strip()] == ["python3 tasks.py build", "python3 tasks.py test"]
    assert len(README.splitlines()) < 250
    links = re.findall(r"\]\((docs/[^)#]+)\)", README)
    assert {"docs/reference.md", "docs/papers.md", "docs/maths.md", "docs/files.md", "docs/mechanisms.md"} <= set(links)
    assert all((ROOT / link).is_file() for link in links)
    for page in DOCS.glob("*.md"):  # links between pages resolve too
        for link in re.findall(r"\]\(([^)#:]+)\)", page.read_text(encoding="utf-8")):
            assert (page.parent / link).exists(), f"{page.name} links {link}"
    assert 'out" by' not in _all_text()  # the garbled fragment once in the errata
    assert "ω2/ω1" in (DOCS / "mechanisms.md").read_text(encoding="utf-8")
    assert "pip install" in README and "[test]" in README


def test_new_writes_a_profile_and_its_schema_that_an_editor_can_use(tmp_path, capsys, schema):
    assert main(["new", "my_gears", "--from", "elliptic_focus", "--dir", str(tmp_path / "mine")]) == 0
    profile, beside = tmp_path / "mine" / "my_gears.toml", tmp_path / "mine" / "profile.schema.json"
    text = profile.read_text(encoding="utf-8")
    assert text.splitlines()[0] == "#:schema ./profile.schema.json"
    assert json.loads(beside.read_text(encoding="utf-8")) == json.loads(json.dumps(schema))
    data = tomllib.loads(text)
    assert data["name"] == "my_gears" and "my_gears" in data["title"]
    assert data["gear1"] == tomllib.loads((ROOT / "profiles" / "elliptic_focus.toml").read_text())["gear1"]
    assert load_profile(profile).name == "my_gears"
    assert main(["new", "my_gears", "--dir", str(tmp_path / "mine")]) == 2  # never overwrites
    assert profile.read_text(encoding="utf-8") == text
    assert main(["new", "../escape", "--dir", str(tmp_path / "other")]) == 2
    assert main(["new", "x", "--from", "no_such_example", "--dir", str(tmp_path / "other")]) == 2
    assert not (tmp_path / "other").exists() and not (tmp_path / "escape.toml").exists()
    err = capsys.readouterr().err
    assert "exists already" in err and "name = '../escape'" in err and "elliptic_focus" in err


def test_a_renamed_variant_gets_its_own_title():
    path = ROOT / "profiles" / "spur_pair.toml"
    original = load_profile(path)
    renamed = load_profile(path, ["name=wide"])
    assert renamed.name == "wide" and renamed.title == f"{original.title} (wide)"
    assert load_profile(path, ["name=wide", "title=Mine"]).title == "Mine"
    assert load_profile(path, {"name": "wide"}).title == renamed.title


def test_a_build_says_when_it_replaces_an_earlier_one(tmp_path, capsys):
    cheap = ["--set", "output.charts=false", "--set", "output.animation=false", "--set", 'output.formats=["dxf"]']
    cheap += ["--set", "output.tolerance=0.01"]
    argv = ["build", str(ROOT / "profiles" / "spur_pair.toml"), "--out", str(tmp_path), *cheap, "--unset", "teeth"]
    assert main(argv) == 0
    assert "replaces" not in capsys.readouterr().out
    assert main(argv) == 0
    assert f"replaces {tmp_path / 'spur_pair'}" in capsys.readouterr().out


def test_compare_shows_two_designs_side_by_side(capsys):
    spur = str(ROOT / "profiles" / "spur_pair.toml")
    assert main(["compare", spur, spur, "--unset", "teeth", "--set", "gear1.radius=25"]) == 0
    out = capsys.readouterr().out
    (row,) = [ln for ln in out.splitlines() if " pair.center_distance " in ln]
    assert row.startswith("*") and row.split()[-2:] == ["60", "75"]  # E = r1 + r2 = 3·r1 for 1:2
    assert "0 finding(s)" in out


def test_the_readme_names_the_test_modules_there_are():
    """Every test module the README's Development section names exists, and every mechanism of
    the registry has its own, importing its module directly."""
    from gearcad.mechanisms import MECHANISMS

    section = README.split("## Development", 1)[1]
    named = set(re.findall(r"`(test_[a-z0-9_]+)`", section))
    have = {p.stem for p in (ROOT / "tests").glob("test_*.py")}
    assert named and named <= have, named - have
    for m in MECHANISMS.values():
        assert f"test_{m.module}" in named, m.name
        text = (ROOT / "tests" / f"test_{m.module}.py").read_text(encoding="utf-8")
        assert re.search(rf"from gearcad\.mechanisms import [^\n]*\b{m.module}\b", text), m.module
