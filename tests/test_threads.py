"""gearcad.threads: a design's two jobs side by side in threads, or in line where every core is
busy — the same design either way; ``GEARCAD_THREADS`` read as OpenMP reads its variable."""

import json

import numpy as np
import pytest

import gearcad
from gearcad.cli import main
from gearcad.threads import VARIABLE, set_threads, side_by_side, threads

from .conftest import COARSE, EXAMPLES, profile


def _same(a, b) -> None:
    """Two designs alike: every part's written paths (vertices and bulges) and the report."""
    assert [p.name for p in a.parts()] == [p.name for p in b.parts()]
    for pa, pb in zip(a.parts(), b.parts(), strict=True):
        assert len(pa.cut) == len(pb.cut), pa.name
        for ra, rb in zip(pa.cut, pb.cut, strict=True):
            np.testing.assert_array_equal(ra.vertices, rb.vertices, err_msg=pa.name)
            np.testing.assert_array_equal(ra.bulges, rb.bulges, err_msg=pa.name)
    assert json.dumps(a.report(), sort_keys=True, default=str) == json.dumps(b.report(), sort_keys=True, default=str)


@pytest.mark.parametrize(
    "name, overrides",
    [
        # two gears cut side by side, the mesh proof beside the play, a laser's three band cases
        ("spur_pair", {"process.kind": "laser"}),
        # a train's mesh bands (the tight and wide cases side by side)
        ("planetary_external", {"process.kind": "laser"}),
    ],
    ids=["pair", "train"],
)
def test_threads_or_none_give_the_same_design(monkeypatch, name, overrides):
    designs = []
    for count in ("2", "1"):
        monkeypatch.setenv(VARIABLE, count)
        assert threads() == int(count)
        designs.append(gearcad.design(profile(name, {**COARSE, **overrides})))
    _same(*designs)


def test_the_environment_comes_first_then_the_process_then_the_cores(monkeypatch):
    monkeypatch.delenv(VARIABLE, raising=False)
    try:
        set_threads(1)
        assert threads() == 1
        monkeypatch.setenv(VARIABLE, "8")
        assert threads() == 2  # two jobs at most: more threads would wait
        monkeypatch.delenv(VARIABLE)
        set_threads(None)
        assert threads() in (1, 2)
    finally:
        set_threads(None)


def test_in_line_jobs_keep_their_errors_as_threads_do(monkeypatch):
    monkeypatch.setenv(VARIABLE, "1")
    order = []
    with side_by_side() as pool:
        first = pool.submit(lambda: 1 / 0)
        second = pool.submit(order.append, "ran")
    assert isinstance(first.exception(), ZeroDivisionError) and second.result() is None and order == ["ran"]
    with pytest.raises(KeyboardInterrupt), side_by_side() as pool:  # an interrupt ends the design at once
        pool.submit(lambda: (_ for _ in ()).throw(KeyboardInterrupt))
        pytest.fail("ran on after an interrupt")


@pytest.mark.parametrize("value", ["0", "two", "-1"])
def test_a_bad_thread_count_is_one_line(monkeypatch, capsys, tmp_path, value):
    monkeypatch.setenv(VARIABLE, value)
    assert main(["check", str(EXAMPLES / "elliptic_focus.toml"), "--set", "output.tolerance=0.01"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and VARIABLE in err[0] and repr(value) in err[0], err
