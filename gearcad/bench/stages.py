"""Designs per second per stage (issue 22), warm and in process, against the stage goals.

Each figure is CPU seconds of this process per design after one warm-up design: on a shared
machine CPU time is what a core gives, not what a neighbour takes.  The ``full`` stage cuts its
two gears on two threads, so its CPU seconds can exceed its wall time.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from ..fitting import design
from ..profiles import load_profile
from ..stages import STAGES
from .commands import PROFILES

__all__ = ["STAGE_GOALS", "bench_stages", "stages_table"]

STAGE_GOALS = {
    ("elliptic_focus", "pitch"): ("designs/s/core ≥", 1000.0),
    ("elliptic_focus", "teeth"): ("designs/s/core ≥", 30.0),
    ("elliptic_focus", "full"): ("ms ≤", 100.0),
    ("spur_pair", "full"): ("ms ≤", 30.0),
    ("walker", "full"): ("ms ≤", 500.0),
}


def _cpu_per_design(work: Callable[[], object], budget: float) -> tuple[float, int]:
    work()  # warm: imports, first-call set-up
    start, n = time.process_time(), 0
    while n == 0 or time.process_time() - start < budget:
        work()
        n += 1
    return (time.process_time() - start) / n, n


def bench_stages(quick: bool = False, step: Callable[[str], None] | None = None) -> list[dict]:
    """One row per (profile, stage): seconds per design, designs per second, the goal if any
    (``quick``: the pitch and teeth stages only, 50 ms each)."""
    rows = []
    for name in ("elliptic_focus", "spur_pair", "walker"):
        params = load_profile(PROFILES / f"{name}.toml")
        for stage in STAGES[:-1] if quick else STAGES:  # quick: no proof
            budget = 0.05 if quick else (6.0 if stage == "full" else 2.0)
            seconds, n = _cpu_per_design(lambda params=params, stage=stage: design(params, stage), budget)
            kind, goal = STAGE_GOALS.get((name, stage), ("", float("nan")))
            value = 1 / seconds if kind.startswith("designs") else 1000 * seconds
            met = (value >= goal if kind.startswith("designs") else value <= goal) if kind else None
            rows.append(
                {
                    "study": "stages",
                    "method": f"{name} {stage}",
                    "n": n,
                    "seconds": seconds,
                    "per_second": 1 / seconds,
                    "goal": f"{kind} {goal:g}" if kind else "",
                    "met": met,
                }
            )
            if step is not None:
                step(f"stages: {name} {stage}")
    return rows


def stages_table(rows: list[dict]) -> list[str]:
    """The stage figures as markdown table lines."""
    out = ["| profile, stage | ms per design | designs/s/core | goal | met |", "|---|---|---|---|---|"]
    for r in rows:
        met = "" if r["met"] is None else ("met" if r["met"] else "not met")
        out.append(f"| {r['method']} | {1000 * r['seconds']:.2f} | {r['per_second']:.1f} | {r['goal']} | {met} |")
    return out
