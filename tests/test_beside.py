"""Pictures drawn in a forked process beside the other files: the same files, byte for byte, as
drawn in line; the child's errors come back as errors; nothing outlives the build."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from gearcad import load_profile
from gearcad.errors import DesignError, GearcadError
from gearcad.export.beside import Beside, can_fork
from gearcad.export.write import write_design
from gearcad.fitting import design

from .conftest import ROOT


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


@pytest.fixture(scope="module")
def spur():
    """The spur pair as written by the suite's build (every output): designed once, drawn by both
    tests (a design is frozen: writing it changes nothing)."""
    return design(load_profile(ROOT / "profiles" / "spur_pair.toml"))


def test_same_files_whether_drawn_beside_or_in_line(tmp_path, monkeypatch, built, spur):
    """Drawn beside (charts and animation forked), the files are those the suite's own build
    wrote (``built``: in line, or beside on another machine), byte for byte."""
    d = spur
    assert can_fork()  # else the build would draw in line and the test would prove nothing
    started = []
    monkeypatch.setattr("gearcad.export.write.Beside", lambda work: started.append(1) or Beside(work))
    files = write_design(d, tmp_path, beside=True)
    assert len(started) == 2  # the charts and the animation, each in a process of its own
    inline = built / "spur_pair"
    listed = json.loads((inline / "report.json").read_text(encoding="utf-8"))["files"]
    assert list(files) == list(listed)  # the report lists them in the same order
    assert {"animation.gif", "pitch_curves.png", "mesh.png"} <= set(files)
    for name in files:
        if name != "index.html":  # written by the build after the files (it links the index)
            assert (inline / name).read_bytes() == (tmp_path / name).read_bytes(), name


def test_the_value_comes_back():
    assert Beside(lambda: {"a": [1, 2.5]}).result() == {"a": [1, 2.5]}


def test_the_childs_error_is_raised_in_the_parent():
    def fail():
        raise DesignError("mesh.png: no room for the legend")

    with pytest.raises(DesignError, match="no room for the legend"):
        Beside(fail).result()


def test_an_error_that_cannot_be_pickled_comes_back_as_its_text():
    class Local(Exception):  # a local class cannot be pickled
        pass

    def fail():
        raise Local("drawn wrong")

    with pytest.raises(GearcadError, match="Local: drawn wrong"):
        Beside(fail).result()


def test_the_childs_traceback_comes_with_its_error():
    def fail():
        raise ValueError("no room")

    with pytest.raises(ValueError, match="no room") as caught:
        Beside(fail).result()
    assert any("in the process drawing beside the build" in note and "fail" in note for note in caught.value.__notes__)


def test_a_child_killed_outright_is_one_clear_error():
    """The OOM killer's SIGKILL: no result, and the message says so (no traceback for the CLI)."""

    def killed():
        os.kill(os.getpid(), signal.SIGKILL)

    with pytest.raises(GearcadError, match="ended killed by signal 9"):
        Beside(killed).result()


def test_no_process_to_spare_draws_in_line(tmp_path, monkeypatch, spur):
    """A second fork that fails (EAGAIN) leaves the first child to finish and draws the rest
    here: the same files, and no child left running."""
    d = spur
    real_fork, forks, children = os.fork, [], []

    def fork():
        if forks:
            raise BlockingIOError(11, "Resource temporarily unavailable")
        forks.append(1)
        pid = real_fork()
        if pid:
            children.append(pid)
        return pid

    monkeypatch.setattr(os, "fork", fork)
    files = write_design(d, tmp_path, beside=True)
    assert len(children) == 1 and not _alive(children[0])
    assert {"animation.gif", "pitch_curves.png", "mesh.png"} <= set(files)
    assert all((tmp_path / name).stat().st_size == entry["bytes"] for name, entry in files.items() if "bytes" in entry)


def test_cancel_ends_the_child():
    job = Beside(lambda: time.sleep(30))
    pid = job._pid
    job.cancel()
    assert not _alive(pid)  # killed and reaped: not even a zombie
    job.cancel()  # a second cancel does nothing


def test_the_child_dies_with_its_parent(tmp_path):
    """A parent killed outright (SIGKILL: no finally runs) takes its picture process with it."""
    script = textwrap.dedent(
        """
        import os, signal, sys, time
        from gearcad.export.beside import Beside
        job = Beside(lambda: time.sleep(30))
        print(job._pid, flush=True)
        time.sleep(0.3)
        os.kill(os.getpid(), signal.SIGKILL)
        """
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=20)
    assert run.returncode == -signal.SIGKILL
    child = int(run.stdout.split()[0])
    deadline = time.monotonic() + 60  # a hang guard, a generous multiple: it returns once the child is gone
    while _alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _alive(child)
