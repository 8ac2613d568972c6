"""The speed goals of issue 13, measured: median whole-process time (and peak memory) against
each goal, met or not.  A benchmark, not a test: it reports, it does not fail."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .process import Measured

__all__ = ["GOALS", "Goal", "goal_rows", "goals_table"]


@dataclass(frozen=True)
class Goal:
    key: str
    """The gearcad command measured (see :func:`gearcad.bench.commands.gearcad_commands`)."""
    seconds: float
    """Median whole-process time at most, s."""
    peak_mb: float | None = None
    """Peak memory of the largest process at most, MB (None: no goal)."""


GOALS = (
    Goal("dxf", 0.6),
    Goal("all", 1.0),
    Goal("check", 0.5),
    Goal("profiles", 3.0, 150.0),
    Goal("teeth2000", 3.0),
    Goal("tol1e-4", 2.0),
    Goal("nc_square", 10.0),  # issue 38: the square set builds in 10 s and checks in 3 s
    Goal("nc_square_check", 3.0),
)


def goal_rows(measured: Mapping[str, Measured], labels: Mapping[str, str]) -> list[dict]:
    """One row per goal whose command was measured."""
    rows = []
    for goal in GOALS:
        if goal.key not in measured:
            continue
        m = measured[goal.key]
        met = m.wall <= goal.seconds and (goal.peak_mb is None or m.peak_mb <= goal.peak_mb)
        rows.append(
            {
                "study": "goals",
                "method": labels[goal.key],
                "n": len(m.runs),
                "seconds": m.wall,
                "seconds_cpu": m.cpu,
                "error": 0.0,
                "goal_seconds": goal.seconds,
                "goal_peak_mb": goal.peak_mb if goal.peak_mb is not None else float("nan"),
                "peak_mb": m.peak_mb,
                "runs": len(m.runs),
                "met": met,
            }
        )
    return rows


def goals_table(rows: list[dict]) -> list[str]:
    """The goals as markdown table lines."""
    out = [
        "| goal | median (s) | goal (s) | CPU (s) | peak (MB) | goal (MB) | runs | met |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        peak_goal = "" if r["goal_peak_mb"] != r["goal_peak_mb"] else f"≤ {r['goal_peak_mb']:.0f}"
        out.append(
            f"| {r['method']} | {r['seconds']:.2f} | ≤ {r['goal_seconds']:g} | {r['seconds_cpu']:.2f} "
            f"| {r['peak_mb']:.0f} | {peak_goal} "
            f"| {r['runs']} | {'met' if r['met'] else 'not met'} |"
        )
    return out
