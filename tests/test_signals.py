"""Ctrl-C and SIGTERM while one profile is designed or written: one line, exit 128 + signal,
nothing left in --out (the multi-process path is tested in test_publish.py)."""

import contextlib
import os
import select
import signal
import subprocess
import sys
import time

import pytest

from .conftest import ROOT

# the CLI's build of one profile, with the stage named on the command line held up (it says
# "ready" first) so that the signal lands inside it
CHILD = r"""
import os, sys, time
from gearcad import batch, cli
from gearcad.export import write

def held(*args, **kwargs):
    os.write(1, b"ready\n")
    time.sleep(60)

if sys.argv[3] == "design":
    batch.design = held
else:
    write.write_design = held
cli.run(["build", sys.argv[1], "--out", sys.argv[2]])
"""


def _ready(proc: subprocess.Popen, timeout: float = 30.0) -> None:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if select.select([proc.stdout], [], [], 0.05)[0]:
            assert os.read(proc.stdout.fileno(), 100).startswith(b"ready")
            return
    pytest.fail("the build never reached the stage")


@pytest.mark.parametrize("stage", ["design", "write"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_signal_during_one_profile_gives_one_line(tmp_path, stage, sig):
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    profile = str(ROOT / "profiles" / "rolling_wheel.toml")
    proc = subprocess.Popen(
        [sys.executable, "-c", CHILD, profile, str(out), stage],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
    )
    _ready(proc)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=30)
    assert (proc.returncode, err.decode().splitlines()) == (128 + sig, [f"gearcad: interrupted; {out} left as it was"])
    assert not out.exists()


def test_an_error_with_more_than_a_message_keeps_its_type_and_fields():
    """batch names the profile in an error by copying it: an error whose constructor takes more
    than a message is not made anew (which raised TypeError for Interrupted)."""
    from types import SimpleNamespace

    from gearcad.batch import _named
    from gearcad.errors import DesignError

    class Odd(DesignError):
        def __init__(self, message, extra):
            super().__init__(message)
            self.extra = extra

    def fail():
        raise Odd("too odd", 7)

    with pytest.raises(Odd, match="^gear: too odd$") as caught:
        _named(SimpleNamespace(name="gear"), fail)
    assert caught.value.extra == 7


# issue 34 items 5, 6 and 20: a sweep's and a build's pool workers, held in their first design
# (each says "ready"), and the parent ended by a signal; the property checked — the parent's one
# line and exit status, the workers gone, nothing written — holds whatever the timing
POOL_CHILD = r"""
import os, sys, time
from gearcad import batch, cli
from gearcad.sweeps import executors

def held(*args, **kwargs):
    os.write(1, b"ready\n")
    time.sleep(120)

out, what = sys.argv[1], sys.argv[2]
if what == "sweep":
    executors.evaluate_chunk = held
    cli.run(["sweep", sys.argv[3], "--vary", "gear1.eccentricity=0.2,0.3,0.4,0.5", "--stage", "pitch",
                       "--workers", "2", "--out", out])
batch.design = held
from gearcad.api import load_profile
batch.build([load_profile(p) for p in sys.argv[3:]], out, workers=2)
"""


def _children(pid: int) -> set[int]:
    """The live (not zombie) processes whose parent is ``pid``, read from /proc."""
    found = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat", encoding="ascii", errors="replace") as fh:
                    fields = fh.read().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid and fields[0] != "Z":
                found.add(int(entry))
    return found


def _alive(pids: set[int]) -> set[int]:
    alive = set()
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as fh:
                if fh.read().rsplit(")", 1)[1].split()[0] != "Z":
                    alive.add(pid)
        except OSError:
            pass
    return alive


def _pool_child(tmp_path, what: str, *args: str, session: bool = False):
    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-c", POOL_CHILD, str(out), what, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        start_new_session=session,
    )
    _ready(proc)  # a worker is in its first design: both have been forked
    workers = _children(proc.pid)
    assert len(workers) == 2, workers
    return proc, out, workers


def _gone(workers: set[int], timeout: float = 30.0) -> set[int]:
    """The workers still alive after up to ``timeout`` s (a generous bound: they end at once)."""
    end = time.monotonic() + timeout
    while _alive(workers) and time.monotonic() < end:
        time.sleep(0.05)
    left = _alive(workers)
    for pid in left:  # a failing run leaves no orphan behind either
        os.kill(pid, signal.SIGKILL)
    return left


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_build_killed_outright_takes_its_workers_with_it(tmp_path):
    """SIGKILL (the out-of-memory killer, a CI timeout) leaves the parent no moment to act."""
    profiles = [str(ROOT / "profiles" / f"{n}.toml") for n in ("elliptic_focus", "rolling_wheel")]
    proc, _, workers = _pool_child(tmp_path, "build", *profiles)
    proc.kill()
    proc.wait(timeout=30)  # not communicate(): a worker left alive holds the pipes open
    proc.stdout.close()
    proc.stderr.close()
    assert _gone(workers) == set()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["Ctrl-C", "SIGTERM"])
def test_a_sweep_ends_at_once_on_a_signal_with_one_line(tmp_path, sig):
    """Ctrl-C (to the whole process group, as a terminal sends it) or SIGTERM (to the parent):
    the queued designs are cancelled, the running ones ended — the workers are held for 120 s,
    so an exit within 30 s is not the work running out — one line, 130 / 143, nothing written."""
    proc, out, workers = _pool_child(tmp_path, "sweep", str(ROOT / "profiles" / "elliptic_focus.toml"), session=True)
    if sig == signal.SIGINT:
        os.killpg(proc.pid, sig)
    else:
        proc.send_signal(sig)
    try:
        _, err = proc.communicate(timeout=30)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
    assert (proc.returncode, err.decode().splitlines()[-1:]) == (
        128 + sig,
        [f"gearcad: interrupted; {out} left as it was"],
    )
    assert "Traceback" not in err.decode()
    assert _gone(workers) == set() and not out.exists()


def test_sigterm_before_the_build_starts_gives_its_line(tmp_path):
    """Issue 34 item 20: in the first second of a build (the arguments read, the profiles loaded:
    before the build's own guard), SIGTERM ended the process silently; the guard is now in place
    from the start of main."""
    child = (
        "import os, sys, time\nfrom gearcad import cli\n"
        "def held(*args):\n    os.write(1, b'ready\\n')\n    time.sleep(60)\n"
        "parser = cli._parser\ncli._parser = lambda: held() or parser()\n"
        "sys.exit(cli.main(['build', sys.argv[1], '--out', sys.argv[2]]))\n"
    )
    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-c", child, str(ROOT / "profiles" / "rolling_wheel.toml"), str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    _ready(proc)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert (proc.returncode, err.decode().splitlines()) == (143, ["gearcad: interrupted"])
    assert not out.exists()


def test_a_worker_stopped_before_its_initializer_ran_ends_at_once(monkeypatch):
    """A worker forked a moment before the pool is stopped still has the parent's handlers (the
    one holding signals while workers are forked): SIGTERM was taken as held, and the worker went
    on to run a queued task while the parent waited (a build's SIGTERM once hung for a minute)."""
    from gearcad import batch

    init = batch._worker_init
    monkeypatch.setattr(batch, "_worker_init", lambda *args: (time.sleep(1), init(*args)))
    start = time.monotonic()
    with batch.worker_pool(2, busy=False) as pool:
        batch.submit_all(pool, time.sleep, [(120,), (120,)])
    assert time.monotonic() - start < 60  # the tasks would hold it 120 s: not a timing budget
