"""``gearcad sweep`` as trustworthy as ``build`` (issue 34, items 4, 7, 10, 12–15, 18): every
mistake in what a sweep is given is one line and exit 2 before the first design (the tests count
the designs run: none), nothing is written, and a Dask scheduler that has no worker, or a port
that accepts and never answers, ends the sweep within its ``--scheduler-timeout``."""

import socket

import numpy as np
import pytest

import gearcad
from gearcad.cli import main
from gearcad.errors import GearcadError, ProfileError
from gearcad.sweeps import evaluate, write_sweep

from .conftest import ROOT

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"
E = "gear1.eccentricity=0.2,0.3"


@pytest.fixture
def designs(monkeypatch):
    """How many designs the sweeps in the test started (in this process: ``--workers 1``)."""
    count = [0]
    real = evaluate.design

    def counted(*args, **kwargs):
        count[0] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(evaluate, "design", counted)
    return count


def _refused(capsys, tmp_path, args, says):
    out = tmp_path / "out"
    code = main(["sweep", "--workers", "1", "--stage", "pitch", "--out", str(out), *args])
    err = capsys.readouterr().err.splitlines()
    assert (code, len(err)) == (2, 1), (args, err)
    assert says in err[0], (args, err)
    assert not out.exists()


@pytest.mark.parametrize(
    "args, says",
    [
        # item 4: non-finite values (they were written into sweep.csv and sweep.parquet)
        (["--vary", "gear1.eccentricity=nan,0.3"], "nan must be a finite number"),
        (["--vary", "gear1.eccentricity=0.2,inf"], "inf must be a finite number"),
        (["--vary", "teeth.count=21,-inf"], "-inf must be a finite number"),
        (["--vary", "teeth.count=21,99999999999999999999"], "within ±2⁶³"),
        # item 13: numbers mixed with text (pyarrow refused the column after the sweep)
        (["--vary", "teeth.count=25,,30"], "mix number and text"),
        (["--vary", "teeth.count=25,true"], "mix boolean and number"),
        # item 18: keys that name no value of the schema (each design was refused, exit 0)
        (["--vary", "gear1=1,2"], "--vary gear1: a table"),
        (["--vary", "..=1"], "must be dotted names"),
        (["--vary", "gear1..a=1"], "must be dotted names"),
        (["--vary", "output.formats.0=1"], "output.formats is a value, not a table"),
        (["--vary", "gear1.nope=1,2"], "gear1.nope: unknown key"),
        # item 12: a constraint's value that is not a number (a TypeError after the sweep)
        (["--vary", E, "--constraint", "pair.ratio_max <= abc"], "'abc' must be a finite number"),
        (["--vary", E, "--constraint", "pair.ratio_max <= [1, 2]"], "must be a finite number"),
        (["--vary", E, "--constraint", "pair.ratio_max <= 2026-01-01"], "must be a finite number"),
        (["--vary", E, "--constraint", 'pair.ratio_max <= "50"'], "'50' must be a finite number"),
        (["--vary", E, "--constraint", "pair.ratio_max <= nan"], "nan must be a finite number"),
        (["--vary", E, "--minimise", "pair.ratio_max", "--maximise", "pair.ratio_max"], "both minimised and"),
        # issue 35 item 3: report keys and their kind, from one design at the stage, before the sweep
        (["--vary", E, "--constraint", "pair.ratio_mx <= 3"], "the pitch stage reports no such key (did you mean"),
        (["--vary", E, "--minimise", "size"], "objective 'size': the pitch stage reports no such key"),
        (["--vary", E, "--minimise", "pair.method"], "the report gives text"),
        (["--vary", E, "--constraint", "pair.method < 3"], "the report gives text"),
        (["--vary", E, "--constraint", "pair.ratio_max >= 3", "--constraint", "pair.ratio_max < 2"], "meets both"),
        (["--vary", E, "--constraint", "pair.ratio_max > 2", "--constraint", "pair.ratio_max <= 2"], "meets both"),
        # item 14: scheduler addresses other than tcp://HOST:PORT (ValueError, TypeError, 3 EiB)
        *(
            (["--vary", E, "--scheduler", address], "must be tcp://HOST:PORT")
            for address in (
                "garbage",
                "tcp://",
                "inproc://",
                "ucx://10.0.0.5:8786",
                "tls://10.0.0.5:8786",
                "file:///tmp/x",
                "tcp://10.0.0.5",
                "tcp://10.0.0.5:0",
                "tcp://10.0.0.5:99999999999999999999",
                "tcp://a b:8786",
            )
        ),
        (["--vary", E, "--scheduler-timeout", "nan"], "--scheduler-timeout nan"),
        (["--vary", E, "--scheduler-timeout", "0"], "--scheduler-timeout 0"),
    ],
)
def test_mistakes_are_refused_before_the_first_design(capsys, tmp_path, designs, args, says):
    _refused(capsys, tmp_path, [str(FOCUS), *args], says)
    assert designs[0] == 0


def test_files_of_no_end_are_refused_at_the_cap(capsys, tmp_path, designs):
    """Item 10: the profile and --file are read as build reads a profile, at most 16 MiB."""
    _refused(capsys, tmp_path, ["/dev/zero", "--vary", E], "more than 16 MiB")
    _refused(capsys, tmp_path, ["--file", "/dev/zero"], "more than 16 MiB")
    assert designs[0] == 0


@pytest.mark.parametrize(
    "text, says",
    [
        ('[vary]\n"gear1.eccentricity" = []\n', "give at least one value"),
        ('samples = true\n[vary]\n"gear1.eccentricity" = "0.2:0.3"\n', "samples = true: must be a whole number"),
        ('[vary]\n"gear1.eccentricity" = 0.3\n', '"a:b:n", "a:b" or a list'),
        ('[vary]\n"gear1.eccentricity" = [0.2, nan]\n', "nan must be a finite number"),
        ('stage = 5\n[vary]\n"gear1.eccentricity" = [0.2]\n', "stage = 5: must be text"),
    ],
)
def test_sweep_file_mistakes(capsys, tmp_path, designs, text, says):
    """Item 15: a sweep file's values each refused with one line."""
    sweep_file = tmp_path / "s.toml"
    sweep_file.write_text(f'profile = "{FOCUS.as_posix()}"\n{text}', encoding="utf-8")
    _refused(capsys, tmp_path, ["--file", str(sweep_file)], says)
    for profile in ("5", "[1, 2]"):
        sweep_file.write_text(f'profile = {profile}\n[vary]\n"gear1.eccentricity" = [0.2]\n', encoding="utf-8")
        _refused(capsys, tmp_path, ["--file", str(sweep_file)], f"profile = {profile}: must be a file's path")
    assert designs[0] == 0


@pytest.mark.parametrize(
    "kwargs, says",
    [
        (dict(workers=-3), "workers = -3: must be a whole number ≥ 1"),
        (dict(workers=True), "workers = true"),
        (dict(seed=1.5), "seed = 1.5: must be a whole number ≥ 0"),
        (dict(samples=-1), "samples = -1"),
        (dict(client="tcp://x"), "--scheduler 'tcp://x': must be tcp://HOST:PORT"),
        (dict(client=42), "client = 42: must be a distributed.Client"),
        (dict(minimise=[None]), "minimise = [None]: must be a list of report keys"),
        (dict(stage="fast"), "stage = 'fast': must be one of pitch, teeth, full"),
        (dict(scheduler_timeout=float("inf")), "scheduler_timeout = inf"),
        (dict(profile=5), "profile = 5: must be a profile's path"),
        (dict(vary={"gear1.eccentricity": []}), "give at least one value"),
    ],
)
def test_api_mistakes(designs, kwargs, says):
    """Item 15: the API's arguments, one ProfileError each, before any design."""
    kwargs = {"profile": FOCUS, "vary": [E], "stage": "pitch", "workers": 1, **kwargs}
    with pytest.raises(ProfileError) as caught:
        gearcad.sweep(kwargs.pop("profile"), kwargs.pop("vary"), **kwargs)
    assert says in str(caught.value) and len(str(caught.value).splitlines()) == 1
    assert designs[0] == 0


def test_write_sweep_of_no_table(tmp_path):
    import pandas as pd

    empty = gearcad.sweep(FOCUS, [E], stage="pitch", workers=1).iloc[:0]
    for table, says in ((pd.DataFrame(), "no 'index' column"), ([], "not a table"), (empty, "no rows")):
        with pytest.raises(ProfileError, match=says):
            write_sweep(table, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_center_distance_can_be_varied():
    """Issue 35 item 4: a report key named as a varied key (pair.center_distance) is a column
    of its own, not a second ``set.`` column ("Duplicate column names" after the sweep)."""
    t = gearcad.sweep(FOCUS, ["pair.center_distance=50", "gear1.a=25,26"], stage="pitch", workers=1)
    assert t.columns.is_unique and t["set.pair.center_distance"].tolist() == [50, 50]
    # a focus pair closes at 2a only: the first is made with 50, the second refused
    assert t["pair.center_distance"].tolist()[:1] == [50] and t["refusal"].isna().tolist() == [True, False]


# item 7: a real scheduler with no worker, and a port that accepts and never answers


@pytest.fixture(scope="module")
def lonely_scheduler():
    """A Dask scheduler on 127.0.0.1, in this process, with no worker at all."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=0, processes=False, protocol="tcp://", host="127.0.0.1", dashboard_address=":0"
    ) as cluster:
        yield cluster.scheduler_address


def test_a_scheduler_with_no_worker_times_out_with_one_line(lonely_scheduler, capsys, tmp_path):
    with pytest.raises(GearcadError, match=r"no worker for 0\.5 s, 2 of 2 designs left undone"):
        gearcad.sweep(FOCUS, [E], stage="pitch", client=lonely_scheduler, scheduler_timeout=0.5)
    out = tmp_path / "out"
    args = ["sweep", str(FOCUS), "--vary", E, "--scheduler", lonely_scheduler, "--scheduler-timeout", "0.5"]
    assert main([*args, "--stage", "pitch", "--out", str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and f"--scheduler {lonely_scheduler}: no worker for 0.5 s, 2 of 2 designs" in err[0]
    assert not out.exists()


def test_a_port_that_never_answers_times_out(capsys, tmp_path):
    """distributed itself waits for the scheduler's greeting with no limit: this hung for ever."""
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        address = f"tcp://127.0.0.1:{listener.getsockname()[1]}"
        out = tmp_path / "out"
        args = ["sweep", str(FOCUS), "--vary", E, "--scheduler", address, "--scheduler-timeout", "0.5"]
        assert main([*args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err == [f"gearcad: error: --scheduler {address}: no answer within 0.5 s (is it a Dask scheduler?)"]
    assert not out.exists()


def test_violations_the_feasible_count_and_the_exit_status_of_none_feasible(capsys, tmp_path):
    """Issue 35 Deliver 3: how far each design is from each constraint, in the table; the
    feasible count on stdout; no feasible design is exit 3 (the files written all the same)."""
    import pandas as pd

    out = tmp_path / "out"
    args = ["sweep", str(FOCUS), "--vary", "gear1.eccentricity=0.2,0.3,0.5", "--stage", "pitch", "--workers", "1"]
    limits = ["--constraint", "pair.ratio_max <= 2", "--constraint", "pair.ratio_min >= 0.6"]
    assert main([*args, *limits, "--out", str(out)]) == 0
    assert "(3 made, 0 refused, 1 feasible, " in capsys.readouterr().out
    table = pd.read_parquet(out / "sweep.parquet")
    e = table["set.gear1.eccentricity"].to_numpy()
    # closed form: the focus pair's ratio runs from (1 − e)/(1 + e) to (1 + e)/(1 − e)
    assert table["violation.pair.ratio_max <= 2"].to_numpy() == pytest.approx(np.maximum(0, (1 + e) / (1 - e) - 2))
    assert table["violation.pair.ratio_min >= 0.6"].to_numpy() == pytest.approx(np.maximum(0, 0.6 - (1 - e) / (1 + e)))
    assert table["feasible"].tolist() == [True, False, False]
    assert main([*args, "--constraint", "pair.ratio_max <= 1", "--out", str(out)]) == 3
    captured = capsys.readouterr()
    assert "(3 made, 0 refused, 0 feasible, " in captured.out
    assert captured.err.splitlines()[-1] == (
        "gearcad: no feasible design: none of the 3 meets every constraint (the violation.* columns say by how "
        "much each missed)"
    )  # after the progress bar
    assert (out / "sweep.csv").is_file()


def test_overrides_as_apply_overrides_gives_them_without_copying_the_profile():
    """Issue 35 Deliver 6: a design's overrides copy only the tables on their paths, and give
    what ``apply_overrides`` gives (an exclusive key's partner removed, a new name in the title,
    a missing table made); the profile itself is left as it was."""
    import copy
    import tomllib

    from gearcad.profiles.reading import apply_overrides
    from gearcad.sweeps.evaluate import overridden

    data = tomllib.loads(FOCUS.read_text(encoding="utf-8"))
    before = copy.deepcopy(data)
    for overrides in (
        {"gear1.eccentricity": 0.3},  # removes gear1.b
        {"teeth.count": 31, "pair.driver_rpm": 60},  # removes teeth.module
        {"name": "wide", "gear1.a": 30},
        {"process.kerf": 0.1, "bore.diameter": 3},  # tables the profile does not give
        {},
    ):
        got = overridden(data, overrides)
        assert got == apply_overrides(data, overrides), overrides
        assert data == before
        # the tables off the overrides' paths are shared, not copied
        assert got["output"] is data["output"] or "output" in {k.split(".")[0] for k in overrides}
