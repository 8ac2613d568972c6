"""The sweep's Pareto front at scale (issue 35): CPU seconds for 10⁴…10⁶ random rows.

Uniform random rows (a front of a few tens of rows), rows on one falling line or plane (every
row on the front: the worst case for the sweep and Kung's merges — though of a million random
rows on a line a few hundred lie within the tolerance of a neighbour in one objective, and one
of each such pair then dominates), two objectives with rounding noise (pairs that differ by
1e-15: the ties the front's tolerance merges), and the running front merged chunk by chunk.
The goal: a million two-objective rows in ≤ 10 s.
"""

from __future__ import annotations

import time

import numpy as np

from ..sweeps.front import RunningFront, pareto

__all__ = ["FRONT_GOAL", "bench_front", "front_lines", "front_summary"]

CHUNK = 400
"""Rows a chunk brings back to the running front (a pitch-stage task's designs)."""

FRONT_GOAL = (2, 1_000_000, 10.0)
"""(objectives, rows, CPU seconds at most): issue 35's goal."""


def _cases(rows: int, rng: np.random.Generator):
    uniform = rng.random((rows, 2))
    yield "2 objectives, uniform", uniform
    line = rng.random(rows)
    yield "2 objectives, all on the front", np.column_stack([line, 1 - line])
    noisy = np.repeat(rng.random((rows // 2, 2)), 2, axis=0)
    noisy[1::2] *= 1 + 1e-15 * rng.standard_normal((rows // 2, 2))
    yield "2 objectives, rounding noise", noisy
    yield "3 objectives, uniform", rng.random((rows, 3))
    plane = rng.random((rows, 3))
    plane[:, 2] = 2 - plane[:, 0] - plane[:, 1]
    yield "3 objectives, all on the front", plane


def bench_front(quick: bool = False) -> list[dict]:
    """One row per (case, rows): CPU seconds of :func:`~gearcad.sweeps.front.pareto`, the rows
    on the front, and for the goal's case whether it is met (``quick``: 10⁴ rows)."""
    rng = np.random.default_rng(35)
    out = []
    for rows in (10_000,) if quick else (10_000, 100_000, 1_000_000):
        for method, values in _cases(rows, rng):
            mask = np.ones(rows, dtype=bool)
            start = time.process_time()
            front = pareto(values, mask)
            seconds = time.process_time() - start
            objectives = values.shape[1]
            goal = (objectives, rows) == FRONT_GOAL[:2] and method.endswith("uniform")
            out.append(
                {
                    "study": "front",
                    "method": method,
                    "n": rows,
                    "seconds": max(seconds, 1e-6),
                    "error": 0.0,
                    "front_rows": int(front.sum()),
                    "goal": f"s ≤ {FRONT_GOAL[2]:g}" if goal else "",
                    "met": seconds <= FRONT_GOAL[2] if goal else None,
                }
            )
        uniform = np.random.default_rng(rows).random((rows, 2))
        start = time.process_time()
        running = RunningFront(2)
        for first in range(0, rows, CHUNK):  # as a pitch-stage sweep's chunks return
            running.add(np.arange(first, min(first + CHUNK, rows)), uniform[first : first + CHUNK])
        seconds = time.process_time() - start
        out.append(
            {
                "study": "front",
                "method": f"2 objectives, uniform, merged {CHUNK} rows at a time",
                "n": rows,
                "seconds": max(seconds, 1e-6),
                "error": 0.0,
                "front_rows": len(running.rows()),
                "goal": "",
                "met": None,
            }
        )
    return out


def front_lines(rows: list[dict]) -> list[str]:
    """The front's timings as markdown table lines."""
    out = ["| case | rows | CPU (s) | on the front | goal | met |", "|---|---|---|---|---|---|"]
    for r in rows:
        if r["study"] != "front":
            continue
        met = "" if r["met"] is None else ("met" if r["met"] else "not met")
        out.append(f"| {r['method']} | {r['n']:,} | {r['seconds']:.3f} | {r['front_rows']:,} | {r['goal']} | {met} |")
    return out


def front_summary(rows: list[dict]) -> list[str]:
    """One line for the bench's summary: the largest uniform two-objective case, and the goal."""
    two = [r for r in rows if r["study"] == "front" and r["method"] == "2 objectives, uniform"]
    if not two:
        return []
    r = max(two, key=lambda r: r["n"])
    met = "met" if r["met"] else "not met"
    verdict = "" if r["met"] is None else f" (goal ≤ {FRONT_GOAL[2]:g} s for {FRONT_GOAL[1]:,}: {met})"
    return [f"Pareto front: {r['n']:,} random two-objective rows in {r['seconds']:.2f} s of CPU{verdict}"]
