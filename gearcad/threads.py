"""Two jobs of one design side by side in threads, where a core is free for the second.

Shapely's vectorised GEOS calls and numpy's work on large arrays release the GIL, so two
independent jobs of a design (the two gears' teeth, the mesh proof beside the play, the cases
of a backlash band) can share two cores.  Measured on the example profiles on an idle two-core
machine, the threads take up to a fifth off a design's time (0.48 → 0.38 s for the oval pair)
and about 10 % more CPU time in all, since the GIL is held through the Python between the calls.
Where every core already has a process of its own — the workers of a build of several
profiles or of a sweep, a test run under pytest-xdist — that extra CPU is all they bring.

:func:`side_by_side` gives an executor: two threads, or one that runs each job as it is
submitted.  The number of threads is ``GEARCAD_THREADS`` from the environment (``1``: none
beside; read as OpenMP reads ``OMP_NUM_THREADS``), else what :func:`set_threads` set for this
process, else two where the process may use two cores or more.
"""

from __future__ import annotations

import os
from concurrent.futures import Executor, Future, ThreadPoolExecutor

from .errors import ProfileError

__all__ = ["side_by_side", "set_threads", "threads", "cores"]

VARIABLE = "GEARCAD_THREADS"

_set: int | None = None


def cores() -> int:
    """The cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def set_threads(count: int | None) -> None:
    """This process's threads per design (``None``: back to the default); the environment's
    ``GEARCAD_THREADS`` still comes first."""
    global _set
    _set = count


def threads() -> int:
    """How many jobs of one design run at once here: 1 or 2."""
    value = os.environ.get(VARIABLE, "").strip()
    if value:
        try:
            count = int(value)
        except ValueError:
            count = 0
        if count < 1:
            raise ProfileError(f"{VARIABLE} = {value!r} (environment): must be a whole number, 1 (no threads) or more")
        return min(count, 2)
    return _set if _set is not None else min(2, cores())


class _InLine(Executor):
    """An executor that runs each job as it is submitted, in this thread."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        future: Future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as exc:  # noqa: BLE001 - kept in the future, as a thread's would be
            future.set_exception(exc)  # (an interrupt is not: it ends the design here and now)
        return future


def side_by_side() -> Executor:
    """An executor for two jobs of one design: two threads, or in line (see the module)."""
    return ThreadPoolExecutor(max_workers=2) if threads() > 1 else _InLine()
