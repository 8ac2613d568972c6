"""``gearcad sweep --method nsga2`` (pymoo) and ``--confirm full`` (issue 35 items 4 and 5): the
search's rows the same on one process, two and a Dask LocalCluster; the hypervolume against a
closed form; its refusals; and a quick-return pair the teeth stage passes, dropped by the full
stage's proof with its reason."""

import sys

import numpy as np
import pytest

import gearcad
from gearcad.cli import main
from gearcad.sweeps.optimise import hypervolume, reference_point
from gearcad.sweeps.page import sweep_page

from .conftest import ROOT

pytest.importorskip("pymoo")

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"
RANGES = ["gear1.eccentricity=0.1:0.6", "teeth.count=21:61"]
SEARCH = dict(
    stage="pitch",
    method="nsga2",
    population=6,
    generations=3,
    seed=7,
    constraints=["gears.0.convexity_margin_min >= 0.7"],
    minimise=["pair.ratio_max"],
    maximise=["gears.0.min_curvature_radius"],
)


def test_nsga2_rows_are_the_same_on_one_two_workers_and_a_cluster():
    """The search runs in the client on pymoo's seeded generator; each generation is one batch
    through the grid's chunked evaluator: 1 process, a pool of 2 and a LocalCluster (threads: the
    grid's test proves a cluster of processes gives a grid's rows) give the same table."""
    distributed = pytest.importorskip("distributed")

    one = gearcad.sweep(FOCUS, RANGES, workers=1, **SEARCH)
    two = gearcad.sweep(FOCUS, RANGES, workers=2, **SEARCH)
    with (
        distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster,
        distributed.Client(cluster) as client,
    ):
        remote = gearcad.sweep(FOCUS, RANGES, client=client, **SEARCH)
    assert one.equals(two) and one.equals(remote)
    assert list(one["generation"]) == [g for g in range(3) for _ in range(6)]
    assert list(one["index"]) == list(range(18))
    counts = one["set.teeth.count"]
    assert all(isinstance(c, (int, np.integer)) and 21 <= c <= 61 for c in counts)  # whole numbers, in range
    assert one["set.gear1.eccentricity"].between(0.1, 0.6).all()
    # the violation amounts fed to the search, by closed form: about a focus, an ellipse's
    # u = 1/r = (1 + e·cos θ)/p has u + u'' = 1/p, so (r² + 2r'² − r·r'')/r² = r/p, least at
    # r_min = p/(1 + e): the margin is 1/(1 + e), and ≥ 0.7 exactly where e ≤ 3/7
    e = one["set.gear1.eccentricity"].to_numpy(float)
    amount = one["violation.gears.0.convexity_margin_min >= 0.7"].to_numpy(float)
    assert np.allclose(amount, np.maximum(0.0, 0.7 - 1 / (1 + e)), atol=1e-9)
    assert (one["feasible"].to_numpy(bool) == (e <= 3 / 7)).all() and 0 < one["feasible"].sum() < 18
    volumes = one.attrs["hypervolumes"]
    assert len(volumes) == 3 and all(b >= a for a, b in zip(volumes, volumes[1:]))  # a front only grows
    page = sweep_page(one)
    assert "<h2>The search (NSGA2, population 6, seed 7)</h2>" in page and page.count("<tr><td>") >= 3
    other = gearcad.sweep(FOCUS, RANGES, workers=1, **{**SEARCH, "seed": 8})
    assert not other["set.gear1.eccentricity"].equals(one["set.gear1.eccentricity"])


def test_hypervolume_and_its_reference_point():
    """Two points (1, 2), (2, 1): the nadir (2, 2) plus 10 % of the span 1 gives (2.1, 2.1); the
    area they dominate up to it is 1.1·0.1 + 0.1·1.1 − 0.1·0.1 = 0.21 (by hand)."""
    front = np.array([[1.0, 2.0], [2.0, 1.0]])
    ref = reference_point(front)
    assert ref.tolist() == pytest.approx([2.1, 2.1])
    assert hypervolume(front, ref) == pytest.approx(0.21)
    assert hypervolume(front[:0], ref) == 0.0


def test_the_optimiser_refuses_bad_input(tmp_path, capsys, monkeypatch):
    out = tmp_path / "bad"
    base = [
        "sweep",
        str(FOCUS),
        "--stage",
        "pitch",
        "--workers",
        "1",
        "--minimise",
        "pair.ratio_max",
        "--out",
        str(out),
    ]
    for args, says in (
        (
            ["--method", "nsga2", "--vary", "gear1.eccentricity=0.1:0.6:5"],
            "--method nsga2 searches a range; give KEY=a:b",
        ),
        (["--method", "nsga2", "--vary", "teeth.count=21,41"], "give KEY=a:b"),
        (["--method", "nsga2", "--vary", RANGES[0], "--population", "2"], "population = 2: must be at least 4"),
        (["--method", "nsga2", "--vary", RANGES[0], "--generations", "2", "--evaluations", "9"], "not both"),
        (["--method", "nsga2", "--vary", RANGES[0], "--samples", "9"], "a search chooses its own points"),
        (["--vary", "gear1.eccentricity=0.1:0.6:3", "--generations", "2"], "only for a search"),
        (["--vary", "gear1.eccentricity=0.1:0.6:3", "--confirm", "full", "--stage", "full"], "already at the full"),
    ):
        assert main([*base, *args]) == 2, args
        err = capsys.readouterr().err
        assert says in err and len(err.strip().splitlines()) == 1, err
    monkeypatch.setitem(sys.modules, "pymoo", None)  # as if not installed: its import fails
    assert main([*base, "--method", "nsga2", "--vary", RANGES[0]]) == 2
    err = capsys.readouterr().err.strip()
    assert "pip install gearcad[optimise]" in err and len(err.splitlines()) == 1
    assert not out.exists()


def test_confirm_full_drops_what_the_teeth_stage_cannot_see():
    """A centred ellipse of eccentricity 0.95 with 40 teeth: its follower is concave, the teeth
    stage passes it and says it is blind there (``stage_blind``), the full stage's mesh proof
    finds the teeth overlapping and the play below zero.  The issue's quick-return motion pair
    fails the same way, at 2.9 CPU-s a full design against this one's 1.3 (see the report)."""
    centre = ROOT / "profiles" / "elliptic_centre.toml"
    vary = ["gear1.eccentricity=0.95", "teeth.count=40", "output.tolerance=0.01"]
    table = gearcad.sweep(centre, vary, stage="teeth", workers=1, confirm="full", maximise=["pair.ratio_max"])
    row = table.iloc[0]
    assert row["ok"] and row["feasible"] and row["stage_blind.0.code"] == "interference"
    assert row["stage_blind.1.code"] == "jams" and "concave" in row["stage_blind.0.why"]
    assert row["confirmed"] is False or row["confirmed"] == False  # noqa: E712 - pandas' boolean
    assert row["confirm_refusal"] == "failed: interference, jams"
    assert not table["pareto"].any()  # the front re-computed from the survivors: none
    assert "<li>#0: fails — failed: interference, jams</li>" in sweep_page(table)


def test_the_teeth_stage_says_it_is_blind_to_the_quick_return_pairs_failures():
    """Issue 35's quick-return law (ratio 0.5 for 240° of the driver, 2 for 120°, smoothed; E =
    150 mm): the teeth stage passes it and names what it cannot see; a convex focus pair's teeth
    stage is blind to nothing.  (Its full design, which fails with interference and jams, is in
    ``gearcad bench``: 2.6 CPU-s.)"""
    from gearcad.bench.optimise import quick_return

    report = gearcad.design(quick_return(), stage="teeth").report()
    assert report["ok"] and report["motion"]["error_deg"] <= 0.01
    assert [b["code"] for b in report["stage_blind"]] == ["interference", "jams"]
    assert "required motion" in report["stage_blind"][0]["why"]
    assert gearcad.design(FOCUS, stage="teeth").report()["stage_blind"] == []
