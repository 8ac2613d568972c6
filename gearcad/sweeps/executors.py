"""Where a sweep's chunks run: in this process, on a local process pool, or on a Dask cluster.

Chunks are sized so that a worker's start-up and each task's round trip are small next to its
work (hundreds of pitch-stage designs, tens at the teeth stage, one or two full designs); the
rows come back in the sweep's order whichever finishes first.
"""

from __future__ import annotations

import math
import re
import socket
import time
from collections.abc import Callable
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from ..batch import finished, submit_all, worker_pool
from ..errors import GearcadError, ProfileError
from ..interrupts import held_signals
from ..profiles.messages import show
from ..threads import cores
from .evaluate import evaluate_chunk

__all__ = ["chunks", "run_chunks", "connect", "scheduler_address", "SCHEDULER_TIMEOUT"]

CHUNK = {"pitch": 400, "teeth": 40, "full": 2}
"""Designs per task at most, by stage: ~0.1–1 s of work each, so a task's overhead (a few ms
locally, ~10 ms on a cluster) stays a few per cent."""

RETRIES = 3
"""A Dask task whose worker is lost is run again up to this many times."""

SCHEDULER_TIMEOUT = 60.0
"""Seconds a sweep waits on a Dask scheduler that has no worker (and to connect to it)."""

POLL = 0.25
"""Seconds between looks at a cluster's workers while no chunk comes back."""


_ADDRESS = re.compile(r"tcp://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9](?:[A-Za-z0-9.-]{0,252}[A-Za-z0-9])?):([0-9]{1,5})")


def scheduler_address(address: Any) -> tuple[str, int]:
    """``tcp://HOST:PORT`` (HOST a name, an IPv4 address or a bracketed IPv6 one) as (host,
    port); anything else — another protocol, no port, a stray character — is refused."""
    match = _ADDRESS.fullmatch(address) if isinstance(address, str) else None
    if match is None or not 1 <= int(match[2]) <= 65535:
        raise ProfileError(
            f"--scheduler {show(address)}: must be tcp://HOST:PORT with PORT 1–65535, e.g. tcp://10.0.0.5:8786"
        )
    return match[1].strip("[]"), int(match[2])


def connect(address: str, timeout: float = SCHEDULER_TIMEOUT):
    """A ``distributed.Client`` on the scheduler at ``address``, within ``timeout`` seconds.

    A Dask scheduler greets a new connection first; distributed waits for that greeting with no
    time limit, so a port that accepts and never answers would hang the client.  The greeting is
    awaited here first, on a plain socket, within the timeout.
    """
    host, port = scheduler_address(address)
    end = time.monotonic() + timeout
    try:
        with socket.create_connection((host, port), timeout=timeout) as probe:
            probe.settimeout(max(end - time.monotonic(), 0.01))
            if not probe.recv(1):
                raise ConnectionError("it closed the connection")
    except TimeoutError:
        raise GearcadError(f"--scheduler {address}: no answer within {timeout:g} s (is it a Dask scheduler?)") from None
    except OSError as exc:
        raise GearcadError(f"--scheduler {address}: cannot reach it ({exc.strerror or exc})") from None
    from distributed import Client

    try:
        return Client(address, timeout=max(end - time.monotonic(), 1.0))
    except (OSError, TimeoutError) as exc:
        raise GearcadError(f"--scheduler {address}: cannot connect ({exc})") from None


def chunks(items: list, stage: str, workers: int) -> list[list]:
    """The points cut into tasks: at most ``CHUNK[stage]`` each, at least 4 tasks per worker
    where there are enough points (so that a slow task does not hold up the end)."""
    size = max(1, min(CHUNK.get(stage, 2), math.ceil(len(items) / (4 * max(workers, 1)))))
    return [items[i : i + size] for i in range(0, len(items), size)]


def _worker_count(workers: int | None) -> int:
    return workers if workers else cores()


def run_chunks(
    data: dict,
    name: str,
    stage: str,
    points: list[tuple[int, dict]],
    *,
    workers: int | None = None,
    client: Any = None,
    scheduler_timeout: float = SCHEDULER_TIMEOUT,
    progress: Callable[[int, int], None] | None = None,
) -> list[dict]:
    """Every point's row, in ``points``' order: on ``client`` (a ``distributed.Client``) if
    given, else on ``workers`` local processes (all cores by default; 1 runs here).

    Whatever ends the run early (an error, Ctrl-C, SIGTERM) cancels the work not yet done and
    ends the local workers at once; a local worker never outlives this process.  On a cluster,
    a run that has had no worker for ``scheduler_timeout`` seconds is given up with one line.
    """
    total, done, rows = len(points), 0, []

    def collect(part: list[dict]) -> None:
        nonlocal done
        rows.extend(part)
        done += len(part)
        if progress is not None:
            progress(done, total)

    if client is not None:
        _on_cluster(client, data, name, stage, points, scheduler_timeout, collect)
    else:
        count = _worker_count(workers)
        tasks = chunks(points, stage, count)
        if count == 1 or len(tasks) == 1:
            for task in tasks:
                collect(evaluate_chunk(data, name, stage, task))
        else:
            count = min(count, len(tasks))
            # a process on every core: no threads beside its designs
            with worker_pool(count, busy=count >= cores()) as pool:
                for job in finished(submit_all(pool, evaluate_chunk, [(data, name, stage, t) for t in tasks])):
                    try:
                        part = job.result()
                    except BrokenProcessPool:
                        raise GearcadError(
                            f"a sweep's worker process ended abruptly (killed, e.g. by the out-of-memory killer?) "
                            f"with {total - done} of {total} designs left; nothing was written"
                        ) from None
                    collect(part)
    return sorted(rows, key=lambda r: r["index"])


def _on_cluster(client, data, name, stage, points, timeout: float, collect) -> None:
    """The chunks on a Dask cluster; cancelled if anything ends the run early.  Every ``POLL``
    seconds the scheduler is asked for its workers: none for ``timeout`` seconds (none came, or
    the last one died) gives up with one line naming the scheduler and the designs left."""
    from distributed import wait

    info = client.scheduler_info()
    tasks = chunks(points, stage, max(1, len(info.get("workers", {}))))
    futures = client.map(
        evaluate_chunk,
        [data] * len(tasks),
        [name] * len(tasks),
        [stage] * len(tasks),
        tasks,
        retries=RETRIES,
        pure=False,
    )
    pending, left = set(futures), len(points)
    alone_since = None  # when the scheduler was first seen with no worker, since the last chunk
    try:
        while pending:
            with held_signals():  # delivered between waits, never inside distributed's locks
                try:
                    done, pending = wait(pending, timeout=POLL, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    done = set()
                parts = [future.result() for future in done]
                staffed = bool(done) or bool(client.scheduler_info(n_workers=1).get("workers"))
            for part in parts:
                left -= len(part)
                collect(part)
            if staffed:
                alone_since = None
                continue
            now = time.monotonic()
            alone_since = now if alone_since is None else alone_since
            if now - alone_since >= timeout:
                address = client.scheduler.address
                raise GearcadError(
                    f"--scheduler {address}: no worker for {timeout:g} s, {left} of {len(points)} designs left "
                    f"undone (start one: dask worker {address}; --scheduler-timeout sets the wait)"
                )
    except BaseException:
        client.cancel(list(pending))
        raise
