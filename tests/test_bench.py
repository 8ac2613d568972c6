"""The stability map (hard designs end in ok, a warning code or one clear error) and a smoke
run of ``gearcad bench --quick``.  Benchmarks measure; they are not timed tests."""

import csv
import math
from pathlib import Path

import pytest

from gearcad.bench import stability_map
from gearcad.cli import main
from gearcad.findings import CODES


@pytest.fixture(scope="module")
def stability():
    return {(r["case"], r["value"]): r["outcome"] for r in stability_map(quick=True)}


def test_every_hard_design_ends_clearly(stability):
    for (case, value), outcome in stability.items():
        kind, _, detail = outcome.partition(":")
        assert kind in {"ok", "warning", "error"}, (case, value, outcome)
        if kind == "warning":
            assert {c.strip() for c in detail.split(",")} <= set(CODES)
        if kind == "error":
            assert "nan" not in detail.lower() and detail.strip()


def test_stability_outcomes_are_the_expected_ones(stability):
    assert stability[("ellipse (centre) eccentricity, 40 teeth", 0.5)] == "ok"
    assert "smaller teeth.module" in stability[("ellipse (centre) eccentricity, 40 teeth", 0.99)]
    assert "undercut" in stability[("spur pair 1:1, tooth count", 6)]
    assert stability[("spur pair 1:1, tooth count", 400)] == "ok"
    assert "corners" in stability[("walker blend width (deg)", 0.0)]
    assert stability[("ratio law mean (1 closes)", 1.0)] == "ok"
    assert "cannot close" in stability[("ratio law mean (1 closes)", 1.2)]
    assert stability[("roller body amplitude, m = 3", 0.1)] == "ok"
    assert stability[("roller body amplitude, m = 3", 0.2)] == "warning: concave"
    assert "crosses itself" in stability[("roller body amplitude, m = 3", 0.3)]


def test_bench_quick_smoke_run(tmp_path: Path, capsys, monkeypatch, stability):
    # the stability map is measured (and tested) above: the smoke run reuses it
    rows = [{"case": c, "value": v, "outcome": o, "seconds": 0.01} for (c, v), o in stability.items()]
    monkeypatch.setattr("gearcad.bench.stability_map", lambda quick=False: rows)
    out = tmp_path / "bench"
    assert main(["bench", "--quick", "--out", str(out)]) == 0
    for name in (
        "speed_accuracy.png",
        "output_size.png",
        "builds.png",
        "stability.png",
        "results.csv",
        "results.md",
        "stability.csv",
    ):
        assert (out / name).stat().st_size > 0, name
    with (out / "results.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    studies = {r["study"] for r in rows}
    assert {"quadrature", "walker-i", "output", "build", "teeth-scaling"} <= studies
    assert any(s.startswith("envelope") for s in studies)
    for r in rows:
        assert math.isfinite(float(r["seconds"])) and float(r["seconds"]) > 0
    # the paper's walker method misses the rolling i by its known 0.0247
    walker = next(r for r in rows if r["method"].startswith("paper: trapezoid"))
    assert float(walker["error"]) == pytest.approx(3.207678 - 3.182936, abs=1e-5)
    # peak memory of a whole build stays under 250 MB
    assert all(float(r["peak_mb"]) < 250 for r in rows if r["study"] == "build")
    assert "measurements written" in capsys.readouterr().out
