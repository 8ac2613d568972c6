"""Where a sweep's chunks run: in this process, on a local process pool, or on a Dask cluster.

Chunks are sized so that a worker's start-up and each task's round trip are small next to its
work (hundreds of pitch-stage designs, tens at the teeth stage, one or two full designs); the
rows come back in the sweep's order whichever finishes first.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any

from ..threads import cores, set_threads
from .evaluate import evaluate_chunk

__all__ = ["chunks", "run_chunks"]

CHUNK = {"pitch": 400, "teeth": 40, "full": 2}
"""Designs per task at most, by stage: ~0.1–1 s of work each, so a task's overhead (a few ms
locally, ~10 ms on a cluster) stays a few per cent."""

RETRIES = 3
"""A Dask task whose worker is lost is run again up to this many times."""


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
    progress: Callable[[int, int], None] | None = None,
) -> list[dict]:
    """Every point's row, in ``points``' order: on ``client`` (a ``distributed.Client``) if
    given, else on ``workers`` local processes (all cores by default; 1 runs here)."""
    total, done, rows = len(points), 0, []

    def collect(part: list[dict]) -> None:
        nonlocal done
        rows.extend(part)
        done += len(part)
        if progress is not None:
            progress(done, total)

    if client is not None:
        tasks = chunks(points, stage, max(1, len(client.scheduler_info().get("workers", {}))))
        futures = client.map(
            evaluate_chunk,
            [data] * len(tasks),
            [name] * len(tasks),
            [stage] * len(tasks),
            tasks,
            retries=RETRIES,
            pure=False,
        )
        from distributed import as_completed as dask_completed

        for future in dask_completed(futures):
            collect(future.result())
    else:
        count = _worker_count(workers)
        tasks = chunks(points, stage, count)
        if count == 1 or len(tasks) == 1:
            for task in tasks:
                collect(evaluate_chunk(data, name, stage, task))
        else:
            busy = min(count, len(tasks)) >= cores()  # a process on every core: no threads beside its designs
            with ProcessPoolExecutor(
                min(count, len(tasks)), initializer=set_threads, initargs=(1 if busy else None,)
            ) as pool:
                for job in as_completed([pool.submit(evaluate_chunk, data, name, stage, t) for t in tasks]):
                    collect(job.result())
    return sorted(rows, key=lambda r: r["index"])
