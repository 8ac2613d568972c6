"""``gearcad sweep``: the points visited, the table (refusals are rows), the front, the files read
back, and the same rows from one process, a local pool and a Dask LocalCluster."""

import os

import numpy as np
import pytest

import gearcad
from gearcad.cli import main
from gearcad.sweeps import write_sweep
from gearcad.sweeps.front import pareto
from gearcad.sweeps.space import SweepSpec, parse_vary, points

from .conftest import ROOT

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"
VARY = ["gear1.eccentricity=0.1:0.6:26", "teeth.count=21,22,41"]  # 22 teeth: an identical pair needs an odd count
GOALS = dict(
    constraints=["gears.0.teeth.undercut == false"],
    minimise=["pair.ratio_max"],
    maximise=["gears.0.teeth.min_tip_thickness"],
)


@pytest.fixture(scope="module")
def table():
    return gearcad.sweep(FOCUS, VARY, stage="teeth", workers=1, **GOALS)


def test_points():
    assert parse_vary("teeth.count=21:41:3").values == (21, 31, 41)
    assert parse_vary("gear1.a=1:2:3").values == (1.0, 1.5, 2.0)
    assert parse_vary("pair.driver='a','b'").values == ("a", "b")
    lhs = points(SweepSpec(vary=(parse_vary("gear1.a=10:20"), parse_vary("gear1.b=0:1")), samples=50, seed=3))
    a = np.array([p["gear1.a"] for p in lhs])
    # a Latin hypercube: exactly one draw in each of the 50 strata of each key
    assert sorted(np.floor((a - 10) / 10 * 50).astype(int)) == list(range(50))
    grid = points(SweepSpec(vary=(parse_vary("x=1,2"), parse_vary("y=0:1")), samples=3, sampling="random"))
    # the same draws for every combination of the listed keys
    assert [p["x"] for p in grid] == [1, 1, 1, 2, 2, 2]
    assert [p["y"] for p in grid[:3]] == [p["y"] for p in grid[3:]]


def test_pareto_by_hand():
    values = np.array([[1, 5], [2, 2], [3, 3], [5, 1], [1, 5], [0, 9]], float)
    mask = np.array([True, True, True, True, True, False])
    # (3, 3) is beaten by (2, 2); the two (1, 5) tie, and neither beats the other; (0, 9) is infeasible
    assert pareto(values, mask).tolist() == [True, True, False, True, True, False]


def test_the_table(table):
    assert len(table) == 78 and table["index"].tolist() == list(range(78))
    assert table["set.gear1.eccentricity"].iloc[::3].tolist() == pytest.approx(np.linspace(0.1, 0.6, 26).tolist())
    refused = table[table["set.teeth.count"] == 22]
    assert len(refused) == 26 and refused["refusal"].str.contains("teeth.count = 22").all()
    assert not refused["feasible"].any() and refused["pair.ratio_max"].isna().all()
    made = table[table["refusal"].isna()]
    e = made["set.gear1.eccentricity"].to_numpy()
    # closed form: the focus pair's largest ratio (1 + e)/(1 − e)
    assert made["pair.ratio_max"].to_numpy() == pytest.approx((1 + e) / (1 - e), rel=1e-12)
    front = table[table["pareto"]]
    assert len(front) >= 1 and front["feasible"].all()
    # nothing feasible beats a front row in both objectives
    ok = table[table["feasible"]]
    for _, row in front.iterrows():
        better = (ok["pair.ratio_max"] <= row["pair.ratio_max"]) & (
            ok["gears.0.teeth.min_tip_thickness"] >= row["gears.0.teeth.min_tip_thickness"]
        )
        strictly = (ok["pair.ratio_max"] < row["pair.ratio_max"]) | (
            ok["gears.0.teeth.min_tip_thickness"] > row["gears.0.teeth.min_tip_thickness"]
        )
        assert not (better & strictly).any()


def test_files_read_back(table, tmp_path):
    import pandas as pd

    from gearcad.sweeps import write_sweep

    files = write_sweep(table, tmp_path / "out")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "front.csv",
        "sweep.csv",
        "sweep.html",
        "sweep.parquet",
    ]
    back = pd.read_parquet(files["sweep.parquet"])
    assert back["refusal"].notna().sum() == 26 and back["pair.ratio_max"].equals(table["pair.ratio_max"])
    csv = pd.read_csv(files["sweep.csv"])
    assert np.allclose(csv["gears.0.teeth.min_tip_thickness"], back["gears.0.teeth.min_tip_thickness"], equal_nan=True)
    assert len(pd.read_csv(files["front.csv"])) == int(table["pareto"].sum())
    page = files["sweep.html"].read_text(encoding="utf-8")
    assert page.count('class="front"') == int(table["pareto"].sum()) and "<svg" in page
    assert "gearcad build" in page and "--set gear1.eccentricity=" in page


def test_cluster_and_pool_give_the_same_rows(table):
    """A real LocalCluster (a scheduler and a worker process started afresh, as a cluster's are:
    every chunk pickled there and back, nothing inherited from this process; one worker, since
    each imports Python, dask and gearcad anew)."""
    distributed = pytest.importorskip("distributed")

    pooled = gearcad.sweep(FOCUS, VARY, stage="teeth", workers=2, **GOALS)
    with (
        distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster,
        distributed.Client(cluster) as client,
    ):
        remote = gearcad.sweep(FOCUS, VARY, stage="teeth", client=client, **GOALS)
    assert pooled.equals(table) and remote.equals(table)


def test_cli_sweep_and_its_refusals(tmp_path, capsys):
    out = tmp_path / "sw"
    sweep_file = tmp_path / "s.toml"
    sweep_file.write_text(
        f'profile = "{FOCUS.as_posix()}"\nstage = "pitch"\nminimise = ["pair.ratio_max"]\n'
        '[vary]\n"gear1.eccentricity" = "0.2:0.6:3"\n"pair.driver_rpm" = [60, 120]\n',
        encoding="utf-8",
    )
    assert main(["sweep", "--file", str(sweep_file), "--workers", "1", "--out", str(out)]) == 0
    assert "swept 6 designs (6 made, 0 refused" in capsys.readouterr().out
    bad = tmp_path / "bad"
    for args, says in (
        (["--vary", "gear1.nope=1,2"], "gear1.nope: unknown key"),
        (["--vary", "gear1.a=1:2:x"], "must be a number"),
        (["--vary", "gear1.a=20:30"], "give --samples"),
        (["--vary", "gear1.a=20,30", "--minimise", "size"], "objective 'size'"),
        (["--vary", "gear1.a=20,30", "--samples", "-1"], "--samples -1: must be a whole number ≥ 0"),
        (["--vary", "gear1.a=20,30", "--out", str(sweep_file)], "exists and is not a folder"),
    ):
        assert main(["sweep", str(FOCUS), "--workers", "1", "--out", str(bad), *args]) == 2, args
        assert says in capsys.readouterr().err
    assert not bad.exists()


def test_sweep_writes_through_no_planted_link(table, tmp_path):
    """Issue 34 item 1: links planted under the names sweep writes are replaced, not written through."""
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "sweep"
    names = ["sweep.parquet", "sweep.csv", "front.csv", "sweep.html"]
    out.mkdir()
    for name in [f".{n}.tmp" for n in names] + names:  # the names the old code wrote through, and the final ones
        os.symlink(victim, out / name)
    write_sweep(table, out)
    assert victim.read_text() == "keep me"
    for n in names:
        assert (out / n).is_file() and not (out / n).is_symlink()
