"""Study "throughput" (issue 35): designs an hour through ``gearcad sweep`` for the focus pair and
the walker at the pitch and teeth stages, on a local pool and on a Dask ``LocalCluster``, both of
two single-threaded worker processes.

Each figure is the sweep's wall time from its call to its table, start-up included (the pool's
processes or the cluster's scheduler and workers are started before the clock: a cluster is
started once and reused), divided into the designs it ran; designs/h per core is that over the
two workers.  Not in ``--quick``: a cluster's start takes seconds and the designs minutes.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from .commands import PROFILES

__all__ = ["bench_throughput", "throughput_lines"]

WORKERS = 2
CASES = (
    ("elliptic_focus", "pitch", ["gear1.eccentricity=0.1:0.6:2000"]),
    ("elliptic_focus", "teeth", ["gear1.eccentricity=0.1:0.6:400"]),
    ("walker", "pitch", ["gear1.b=45:55:60"]),
    ("walker", "teeth", ["gear1.b=45:55:40"]),
)
"""(profile, stage, what varies): some hundreds of designs a case, a few seconds each."""


def _rate(run: Callable[[], object]) -> tuple[float, int]:
    start = time.perf_counter()
    table = run()
    return time.perf_counter() - start, len(table)


def bench_throughput(step: Callable[[str], None] | None = None) -> list[dict]:
    """One row per (profile, stage, engine): designs, seconds, designs/h and designs/h per core."""
    import gearcad

    rows: list[dict] = []

    def add(name: str, stage: str, engine: str, seconds: float, designs: int) -> None:
        per_hour = 3600 * designs / seconds
        rows.append(
            {
                "study": "throughput",
                "method": f"{name} {stage}, {engine}",
                "n": designs,
                "seconds": seconds,
                "per_hour": per_hour,
                "per_hour_per_core": per_hour / WORKERS,
            }
        )
        if step is not None:
            step(f"throughput: {name} {stage} {engine}")

    for name, stage, vary in CASES:
        path = PROFILES / f"{name}.toml"
        seconds, n = _rate(lambda: gearcad.sweep(path, vary, stage=stage, workers=WORKERS))
        add(name, stage, "local pool", seconds, n)
    try:
        import distributed
    except ImportError:  # the sweep extra left out: the local figures only
        return rows
    with (
        distributed.LocalCluster(
            n_workers=WORKERS, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        for name, stage, vary in CASES:
            path = PROFILES / f"{name}.toml"
            gearcad.sweep(path, vary[:1], stage="pitch", client=client)  # each worker's imports, once
            seconds, n = _rate(lambda: gearcad.sweep(path, vary, stage=stage, client=client))
            add(name, stage, "LocalCluster", seconds, n)
    return rows


def throughput_lines(rows: list[dict]) -> list[str]:
    """The throughput figures as markdown table lines."""
    out = ["| profile, stage, engine | designs | seconds | designs/h | designs/h per core |", "|---|---|---|---|---|"]
    for r in rows:
        out.append(
            f"| {r['method']} | {r['n']} | {r['seconds']:.1f} | {r['per_hour']:,.0f} | {r['per_hour_per_core']:,.0f} |"
        )
    return out
