"""The command line, through main(argv): builds, checks, and bad input."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from gearcad.cli import main
from gearcad.findings import CODES

from .conftest import PROFILES, ROOT, read_dxf

COARSE = ["--set", "output.charts=false", "--set", "output.animation=false", "--set", "output.tolerance=0.01"]
"""No chart data, no animation, outlines at 0.01 mm: where a test looks at what the command does,
not at fine outlines (the ``built`` fixture makes every profile at its own tolerance once)."""
LEAN = [*COARSE, "--set", 'output.formats=["dxf"]']
"""A build that writes only the DXF files: where a test looks at what the build does, not at
every file (the ``built`` fixture writes them all once)."""


def _area(polyline) -> float:
    """The signed area of a closed LWPOLYLINE with bulges, in closed form: the polygon of its
    vertices (shoelace) plus, for each arc, the circular segment between it and its chord,
    (θ − sin θ)·ρ²/2 with θ = 4·atan(bulge) and ρ = chord / (2·sin(θ/2)) (exact, no flattening)."""
    x, y, bulge = np.array(polyline.get_points("xyb"), dtype=float).T
    dx, dy = np.roll(x, -1) - x, np.roll(y, -1) - y
    polygon = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    theta = 4 * np.arctan(bulge)
    arc = bulge != 0
    radius2 = (dx**2 + dy**2)[arc] / (4 * np.sin(theta[arc] / 2) ** 2)
    return polygon + float(np.sum((theta[arc] - np.sin(theta[arc])) * radius2 / 2))


def _tree(folder: Path) -> dict:
    return {p.relative_to(folder): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _pair_reports(built):
    reports = [json.loads(p.read_text()) for p in sorted(built.glob("*/report.json"))]
    pairs = [r for r in reports if r["mechanism"] == "gear-pair"]
    assert len(pairs) == 6
    return pairs


def test_every_profile_builds_its_files(built):
    names = {p.stem for p in PROFILES}
    assert {p.name for p in built.iterdir() if p.is_dir()} == names and (built / "index.html").is_file()
    for name in names:
        report = json.loads((built / name / "report.json").read_text())
        for f in report["files"]:
            assert (built / name / f).is_file(), f
    for report in _pair_reports(built):
        name = report["name"]
        for f in report["files"]:
            assert (built / name / f).is_file(), f
        assert {
            "pitch_curves.png",
            "kinematics.png",
            "mesh.png",
            "kinematics.csv",
            "assembly.dxf",
            "assembly.3mf",
            "animation.gif",
        } <= set(report["files"])
        for gear in report["gears"]:
            assert {f"{gear['name']}.{ext}" for ext in ("dxf", "stl", "3mf")} <= set(report["files"])


def test_report_schema_and_residuals(built):
    for report in _pair_reports(built):
        assert {"name", "gears", "pair", "warnings", "files", "kinematics"} <= set(report)
        for gear in report["gears"]:
            assert {"name", "pivot", "lobes", "r_min", "r_max", "perimeter", "convex"} <= set(gear)
            assert 0 < gear["r_min"] <= gear["r_max"]
        pair = report["pair"]
        assert {"center_distance", "closure_error", "rolling_residual", "ratio_min", "ratio_max"} <= set(pair)
        assert pair["closure_error"] < 1e-9 and pair["rolling_residual"] < 1e-9
        for w in report["warnings"]:
            assert w["code"] in CODES and w["message"]


def test_papers_findings_in_reports(built):
    centre = json.loads((built / "elliptic_centre" / "report.json").read_text())
    assert not centre["claim"]["holds"]
    assert {"not-closed", "not-identical"} <= {w["code"] for w in centre["warnings"]}
    assert centre["pair"]["center_distance"] < 40
    oval = json.loads((built / "oval_centre" / "report.json").read_text())
    assert oval["claim"]["holds"] and oval["pair"]["center_distance"] == pytest.approx(40, abs=1e-9)
    walker = json.loads((built / "walker" / "report.json").read_text())
    assert round(walker["walker"]["i_paper"], 6) == 3.207678
    assert walker["walker"]["i"] == pytest.approx(3.182936, abs=5e-7)
    assert {"not-closed", "slips", "blend"} <= {w["code"] for w in walker["warnings"]}
    spur = json.loads((built / "spur_pair" / "report.json").read_text())
    assert spur["pair"]["center_distance"] == pytest.approx(60, abs=1e-9)
    assert spur["pair"]["ratio_min"] == pytest.approx(0.5) and spur["pair"]["ratio_max"] == pytest.approx(0.5)


def _not_cross(polyline) -> bool:
    """A dash of a pitch curve (arcs, or more than one segment), not a stroke of the pivot's cross
    nor the assembly dot (a small diamond drawn round: four straight strokes back to its start)."""
    points = [tuple(v.dxf.location)[:2] for v in polyline.vertices]
    dot = len(points) == 5 and points[0] == points[-1] and not any(v.dxf.bulge for v in polyline.vertices)
    return not dot and (len(polyline) > 2 or any(v.dxf.bulge for v in polyline.vertices))


def test_dxf_files_read_back(built):
    for path in built.glob("*/*.dxf"):
        doc = read_dxf(path)
        assert doc.units == 4  # mm
        auditor = doc.audit()
        assert not auditor.has_errors, path
        # cut paths are closed LWPOLYLINEs; engraving open POLYLINEs (OpenSCAD skips them; dashed
        # pitch curves, so no program fills them)
        closed = [e for e in doc.modelspace().query("LWPOLYLINE POLYLINE") if e.is_closed]
        assert closed and all(e.dxf.layer == "CUT" for e in closed), path  # something to cut, nothing closed on MARK
        mark = [e for e in doc.modelspace().query("POLYLINE") if e.dxf.layer == "MARK" and _not_cross(e)]
        # a toothed gear engraves its pitch curve; a plain wheel or the walker's shoe has none
        gears = {g["name"] for g in json.loads((path.parent / "report.json").read_text()).get("gears", [])}
        if path.stem in gears and path.parent.name != "rolling_wheel":
            assert mark, path


def test_pitch_dxf_matches_the_curve(built):
    report = json.loads((built / "elliptic_focus" / "report.json").read_text())
    doc = read_dxf(built / "elliptic_focus" / "driver.dxf")
    dashes = [e for e in doc.modelspace().query("POLYLINE") if e.dxf.layer == "MARK" and _not_cross(e)]
    pts = np.array([(v.dxf.location.x, v.dxf.location.y) for e in dashes for v in e.vertices])
    r = np.hypot(pts[:, 0], pts[:, 1])
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    # the dashes' vertices on the ellipse, within the tolerance of the arcs the curve is written with
    np.testing.assert_allclose(r, 15.0**2 / (25 - 20 * np.cos(phi)), atol=2 * report["tolerance"])
    assert r.max() == pytest.approx(report["gears"][0]["r_max"], abs=2 * report["tolerance"])


def test_toothed_outlines_read_back_and_mesh(built):
    for report in _pair_reports(built):
        path = built / report["name"] / "report.json"
        assert report["pair"]["teeth"]["mesh"]["meshes"], path
        for gear in report["gears"]:
            doc = read_dxf(path.parent / f"{gear['name']}.dxf")
            cut = [e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT"]
            assert len(cut) == 1 + gear["part"]["holes"] and all(e.closed for e in cut)
            outer = max(cut, key=lambda e: abs(_area(e)))
            area = _area(outer)
            # the arcs' area exactly: the area of the cut shape within tolerance × perimeter
            assert area == pytest.approx(gear["teeth"]["area"], abs=0.001 * 2 * gear["perimeter"]) and area > 0
            assert gear["teeth"]["module"] * np.pi * gear["teeth"]["count"] == pytest.approx(
                gear["perimeter"], rel=1e-9
            )
    focus = json.loads((built / "elliptic_focus" / "report.json").read_text())
    assert [g["teeth"]["count"] for g in focus["gears"]] == [41, 41]
    assert focus["pair"]["teeth"]["identical_parts"] and focus["pair"]["teeth"]["identical_deviation"] < 1e-9
    spur = json.loads((built / "spur_pair" / "report.json").read_text())
    assert [g["teeth"]["count"] for g in spur["gears"]] == [20, 40]
    assert not any(g["teeth"]["undercut"] for g in spur["gears"])


def test_corners_cannot_take_teeth(tmp_path, capsys):
    out = tmp_path / "out"
    args = ["build", str(ROOT / "profiles" / "walker.toml"), "--out", str(out), "--set", "gear1.blend_width_deg=0"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "corners" in err and "blend" in err and not out.exists()


def test_identical_pair_rejects_a_count_that_cannot_mesh(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_text((ROOT / "profiles" / "elliptic_focus.toml").read_text().replace("module = 1.0", "count = 40"))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "teeth.count = 40" in err and "39, 41" in err


def test_set_overrides_a_value(tmp_path):
    out = tmp_path / "out"
    args = [
        "build",
        str(ROOT / "profiles" / "elliptic_focus.toml"),
        "--out",
        str(out),
        "--set",
        "gear1.b=20",
        "--set",
        "name=wider",
        *LEAN,
    ]
    assert main(args) == 0
    report = json.loads((out / "wider" / "report.json").read_text())
    assert report["gears"][0]["r_max"] == pytest.approx(25 + 15)  # a + c, c = √(25² − 20²)


def test_check_prints_without_writing(tmp_path, capsys, monkeypatch):
    # every stage checked, the band bounded by the estimate (what is printed here is the pitch
    # curves' and nothing is written either way; the walker's proven band is tests/test_fit_oracle.py's)
    monkeypatch.chdir(tmp_path)
    estimate = ["--set", 'output.certificate="estimate"']
    assert main(["check", str(ROOT / "profiles" / "walker.toml"), *COARSE, *estimate]) == 0
    text = capsys.readouterr().out
    assert "i (paper's method) = 3.207678" in text and "[slips]" in text
    assert list(tmp_path.iterdir()) == []


def test_build_without_arguments_builds_every_profile(tmp_path, monkeypatch, capsys):
    """Every profiles/*.toml of the working folder (three small ones here: the full set is built
    once for the whole suite by the ``built`` fixture)."""
    chosen = ["rolling_wheel", "spur_pair", "planetary_external"]
    (tmp_path / "profiles").mkdir()
    for name in chosen:
        shutil.copy(ROOT / "profiles" / f"{name}.toml", tmp_path / "profiles")
    monkeypatch.chdir(tmp_path)
    # the bands bounded by the estimate (what is built is under test, not their verdicts): 0.9
    # CPU-s for the three designs, not 1.6
    assert main(["build", *LEAN, "--set", 'output.certificate="estimate"']) == 0
    lines = capsys.readouterr().out.splitlines()
    heads = [ln for ln in lines[:-1] if not ln.startswith("  warning [")]
    assert [ln.split("]")[0] for ln in heads] == [f"[{n}/{len(chosen)}" for n in range(1, len(chosen) + 1)]
    # each warning in one line under its profile's, as check prints them, as many as the line counts
    wheel = lines.index(next(ln for ln in lines if "rolling_wheel:" in ln))
    assert lines[wheel + 1 : wheel + 3] == ["  warning [paper-formula] " + m for m in _messages(tmp_path)]
    assert {p.name for p in (tmp_path / "out").iterdir() if p.is_dir()} == set(chosen)


def _messages(folder: Path) -> list[str]:
    report = json.loads((folder / "out" / "rolling_wheel" / "report.json").read_text(encoding="utf-8"))
    return [w["message"] for w in report["warnings"]]


BAD = [
    ("gear1.bb=3", "gear1.bb", "unknown key"),
    ('gear1.a="big"', "gear1.a = 'big'", "a length in mm"),
    ("gear1.b=-3", "gear1.b = -3", "from 0.001 to 100000"),
    ("gear1.a=0", "gear1.a = 0", "from 0.001 to 100000"),
    ("gear1.b=30", "gear1.b = 30", "must not exceed"),
    ("pair.driver_rpm=true", "pair.driver_rpm = true", "rev/min"),
    ('pair.driver="crank"', "pair.driver = 'crank'", "one of"),
    ("gear2.lobes=0", "gear2.lobes = 0", "integer from 1 to 24"),
    ("output.tolerance=0", "output.tolerance = 0", "from 0.0001 to 0.5"),
    ("pair.center_distance=20", "pair.center_distance = 20", "largest radius"),
    ("pair.center_distance=49", "pair.center_distance = 49", "does not close"),
    ("color=1", "color", "unknown key"),
]


@pytest.mark.parametrize("override,names,allowed", BAD)
def test_bad_values_give_one_clear_line_and_write_nothing(tmp_path, capsys, override, names, allowed):
    out = tmp_path / "out"
    code = main(["build", str(ROOT / "profiles" / "elliptic_focus.toml"), "--out", str(out), "--set", override])
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert names in err[0] and allowed in err[0]
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []  # no staging folder left behind either


def test_eccentricity_at_or_above_one(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_text('[gear1]\ncurve = "ellipse"\na = 10\neccentricity = 1.0\n')
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "gear1.eccentricity = 1.0" in err and "from 0 to 0.998" in err
    assert not (tmp_path / "out").exists()


def test_ratio_law_that_cannot_close(tmp_path, capsys):
    path = tmp_path / "law.toml"
    path.write_text('[gear1]\ncurve = "ratio"\nmean = 1.2\nharmonics = [[1, 0.3, 0.0]]\n[pair]\ncenter_distance = 50\n')
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "gear1.mean = 1.2" in err and "cannot close" in err and "must be 1" in err
    path.write_text('[gear1]\ncurve = "ratio"\nharmonics = [[1, 1.5, 0.0]]\n[pair]\ncenter_distance = 50\n')
    assert main(["build", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "gear1.harmonics" in capsys.readouterr().err
    path.write_text('[gear1]\ncurve = "ratio"\nharmonics = [[1, 0.3, 0.0]]\n[pair]\ncenter_distance = 50\n')
    assert main(["build", str(path), "--out", str(tmp_path / "out"), *LEAN]) == 0


def test_several_bad_values_one_line_each(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('[gear1]\ncurve = "ellipse"\na = -1\nb = "x"\nwobble = 2\n')
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(str(path) in line for line in err)


def test_unreadable_and_invalid_files(tmp_path, capsys):
    assert main(["check", str(tmp_path / "missing.toml")]) == 2
    assert "cannot read" in capsys.readouterr().err
    broken = tmp_path / "broken.toml"
    broken.write_text("[gear1\n")
    assert main(["check", str(broken)]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_failed_build_leaves_previous_output_untouched(tmp_path, capsys):
    out = tmp_path / "out"
    good = ROOT / "profiles" / "spur_pair.toml"
    assert main(["build", str(good), "--out", str(out), *LEAN]) == 0
    before = _tree(out)
    bad = tmp_path / "bad.toml"  # valid values, but a centre distance at which it cannot close
    bad.write_text(
        'name = "spur_pair"\n[gear1]\ncurve = "circle"\nradius = 20\n[gear2]\nlobes = 2\n[pair]\ncenter_distance = 70\n'
    )
    assert main(["build", str(bad), "--out", str(out)]) == 2
    assert "does not close" in capsys.readouterr().err
    assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml", "out"]
