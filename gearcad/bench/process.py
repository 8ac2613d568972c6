"""Whole-process measurements: a fresh Python per run, timed from outside, measured inside.

A child is ``python -c <code> <spec json>``.  The parent times it from start to exit (the wall
time a user waits for); the child reports how long its imports took, each call of its work, and
its peak memory: the larger of its own high-water mark (``VmHWM``) and that of any process it
waited for (a build's worker pool), i.e. the largest single process.
"""

from __future__ import annotations

import compileall
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Command", "Measured", "ProcessRun", "cli_command", "measure", "run_child"]

_PROLOGUE = """
import json, resource, sys, time
start = time.perf_counter()
from pathlib import Path
spec = json.loads(sys.argv[1])
extra = {}
"""

_EPILOGUE = """
try:  # this process's own high-water mark (ru_maxrss of SELF would keep a parent's across exec)
    own = next(int(l.split()[1]) for l in open("/proc/self/status") if l.startswith("VmHWM"))
except (OSError, StopIteration):
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
Path(spec["measure"]).write_text(json.dumps(
    {"imports": imported - start, "calls": calls, "peak_kb": max(own, children), "extra": extra}))
"""

_CLI_BODY = """
from gearcad.cli import main
imported = time.perf_counter()
calls = []
for _ in range(spec["calls"]):
    t = time.perf_counter()
    code = main(spec["argv"])
    calls.append(time.perf_counter() - t)
    if code:
        sys.exit(code)
"""


@dataclass(frozen=True)
class ProcessRun:
    wall: float
    """s from start to exit, seen from outside."""
    imports: float
    """s the child spent importing before its work (as the child counts it)."""
    calls: tuple[float, ...]
    """s per call of the work, in the child (the first includes anything imported on use)."""
    peak_mb: float
    """Largest resident set of the child or of any process it waited for, MB."""
    extra: dict
    cpu: float = float("nan")
    """s of CPU (user + system) of the child and every process it waited for: what a loaded
    machine inflates least (with a worker pool it can exceed the wall time)."""


@dataclass(frozen=True)
class Command:
    """A child to run: its body (Python that sets ``imported``, ``calls`` and ``extra``) and spec."""

    label: str
    body: str
    spec: dict
    folder: Path
    """Where the child writes (emptied by the child's own tool or overwritten each run)."""


@dataclass(frozen=True)
class Measured:
    label: str
    runs: tuple[ProcessRun, ...]
    warm: tuple[float, ...] = field(default=())
    """s per call of the same work repeated in one process after its first call."""

    @property
    def wall(self) -> float:
        return statistics.median(r.wall for r in self.runs)

    @property
    def in_process(self) -> float:
        """Median first call after the imports (lazy imports inside the work included)."""
        return statistics.median(r.calls[0] for r in self.runs)

    @property
    def imports(self) -> float:
        return statistics.median(r.imports for r in self.runs)

    @property
    def cpu(self) -> float:
        return statistics.median(r.cpu for r in self.runs)

    @property
    def peak_mb(self) -> float:
        return max(r.peak_mb for r in self.runs)

    @property
    def warm_median(self) -> float:
        return statistics.median(self.warm) if self.warm else float("nan")


def _environment() -> dict[str, str]:
    """The child imports the gearcad being measured (a worktree's, not whichever is installed),
    from bytecode as an installed package does: compiled here once, and read (not recompiled)
    by every child even where the shell asks Python not to write bytecode."""
    root = Path(__file__).resolve().parents[2]
    compileall.compile_dir(root / "gearcad", quiet=1)
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPATH"] = os.pathsep.join([str(root), *filter(None, [env.get("PYTHONPATH")])])
    return env


def run_child(command: Command, *, calls: int = 1) -> ProcessRun:
    """Run ``command`` once in a fresh interpreter."""
    command.folder.mkdir(parents=True, exist_ok=True)
    measure = command.folder / f".measure-{os.getpid()}.json"
    measure.unlink(missing_ok=True)
    spec = {**command.spec, "calls": calls, "measure": str(measure)}
    code = _PROLOGUE + command.body + _EPILOGUE
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", code, json.dumps(spec)],
        capture_output=True,
        text=True,
        env=_environment(),
        cwd=command.folder,
    )
    wall = time.perf_counter() - start
    now = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (now.ru_utime + now.ru_stime) - (used.ru_utime + used.ru_stime)
    if done.returncode != 0 or not measure.exists():
        tail = (done.stderr or done.stdout).strip().splitlines()[-5:]
        raise RuntimeError(f"{command.label}: the child failed ({done.returncode}): " + " | ".join(tail))
    data = json.loads(measure.read_text())
    measure.unlink()
    return ProcessRun(wall, data["imports"], tuple(data["calls"]), data["peak_kb"] / 1024, data["extra"], cpu)


def cli_command(label: str, argv: list[str], folder: Path) -> Command:
    """``gearcad <argv>`` as a child (``main(argv)``, what ``python -m gearcad`` runs)."""
    return Command(label, _CLI_BODY, {"argv": argv}, folder)


def measure(
    commands: Mapping[str, Command],
    *,
    runs: int,
    warm_calls: Mapping[str, int] | None = None,
    long_run: float = 5.0,
    step: Callable[[str], None] | None = None,
) -> dict[str, Measured]:
    """Run every command ``runs`` times, interleaved (one run of each per round, so a burst of
    load elsewhere slows all alike); a command whose first run took over ``long_run`` seconds
    runs at most three times.  ``warm_calls[label]`` extra calls in one more process give the
    warm in-process time (after the first call)."""
    done: dict[str, list[ProcessRun]] = {label: [] for label in commands}
    for round_ in range(runs):
        for label, command in commands.items():
            if round_ >= 3 and done[label][0].wall > long_run:
                continue
            done[label].append(run_child(command))
            if step:
                step(f"{label} ({round_ + 1}/{runs})")
    warm: dict[str, tuple[float, ...]] = {}
    for label, extra in (warm_calls or {}).items():
        if extra > 0:
            warm[label] = run_child(commands[label], calls=1 + extra).calls[1:]
            if step:
                step(f"{label} (in process)")
    return {label: Measured(label, tuple(r), warm.get(label, ())) for label, r in done.items()}
