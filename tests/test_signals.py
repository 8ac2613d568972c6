"""Ctrl-C and SIGTERM while one profile is designed or written: one line, exit 128 + signal,
nothing left in --out (the multi-process path is tested in test_publish.py)."""

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
sys.exit(cli.main(["build", sys.argv[1], "--out", sys.argv[2]]))
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
