"""A sweep's cost per design beyond the design itself (issue 35 item 6), at the pitch stage.

For the focus pair (a closed form: the design is cheap, so what surrounds it shows) and the
walker (a synthesis: 250 times dearer), a chunk of designs over ``gear1`` is timed three ways,
in interleaved rounds, CPU seconds per design, the fastest round of each (load only adds):

- ``design``: ``design(params, "pitch")`` alone, the parameters made beforehand — the work;
- ``row``: :func:`~gearcad.sweeps.evaluate.evaluate_chunk`, what a sweep's worker runs: each
  design's parameters from the profile validated once, the design, its row;
- ``row before``: the loop as it was before issue 35 — the whole overridden profile validated for
  every design, the report built and walked — for comparison.

The overhead is ``row − design``; the goal: at most 20 % of the design's own time.
"""

from __future__ import annotations

import time
from collections.abc import Callable

__all__ = ["OVERHEAD_GOAL", "bench_overhead", "overhead_lines", "overhead_summary"]

OVERHEAD_GOAL = 0.20
"""A pitch-stage design's overhead in a sweep, at most, as a share of the design's own time."""

CASES = {
    "elliptic_focus": ("gear1.eccentricity", 0.1, 0.6, 400),
    "walker": ("gear1.b", 45.0, 55.0, 6),
}
"""Profile → the key varied, its range and the designs of the chunk (a sweep's pitch chunk is 400)."""


def _before(data: dict, name: str, chunk: list[tuple[int, dict]]) -> list[dict]:
    """The rows as a worker made them before issue 35 (for comparison only)."""
    from ..fitting import design
    from ..profiles.reading import apply_overrides, parse_profile
    from ..sweeps.evaluate import flatten

    rows = []
    for index, overrides in chunk:
        row = {"index": index, "refusal": None}
        d = design(parse_profile(apply_overrides(data, overrides), default_name=name), "pitch")
        report = d.report()
        row["warnings"] = len(report["warnings"])
        row.update(flatten(report))
        rows.append(row)
    return rows


def _fastest(funcs: dict[str, Callable[[], object]], rounds: int) -> dict[str, float]:
    """CPU seconds of each function's fastest round, the functions interleaved round by round."""
    best = dict.fromkeys(funcs, float("inf"))
    for _ in range(rounds):
        for key, func in funcs.items():
            start = time.process_time()
            func()
            best[key] = min(best[key], time.process_time() - start)
    return best


def bench_overhead(quick: bool = False, step: Callable[[str], None] | None = None) -> list[dict]:
    """One row per profile: CPU seconds per design of the design, the row, the row as it was,
    and the overhead's share of the design (``quick``: the focus pair only, fewer rounds)."""
    import logging

    from ..fitting import design
    from ..profiles.reading import apply_overrides, parse_profile
    from ..sweeps.evaluate import evaluate_chunk
    from ..sweeps.space import read_toml
    from .commands import PROFILES

    rows = []
    for name, (key, low, high, count) in CASES.items():
        if quick and name != "elliptic_focus":
            continue
        data = read_toml(PROFILES / f"{name}.toml", "profile")
        count = min(count, 60) if quick else count
        chunk = [(i, {key: low + (high - low) * i / max(count - 1, 1)}) for i in range(count)]
        params = [parse_profile(apply_overrides(data, o), default_name=name) for _, o in chunk]
        made = evaluate_chunk(data, name, "pitch", chunk)
        if any(r["refusal"] for r in made) or made != _before(data, name, chunk):
            raise AssertionError(f"{name}: a sweep's rows differ from the report's, or a design is refused")
        level = logging.getLogger("gearcad").level
        try:
            best = _fastest(
                {
                    "design": lambda: [design(p, "pitch") for p in params],
                    "row": lambda: evaluate_chunk(data, name, "pitch", chunk),
                    "row before": lambda: _before(data, name, chunk),
                },
                rounds=2 if quick else 3 if count < 100 else 7,
            )
        finally:
            logging.getLogger("gearcad").setLevel(level)
        work, row, before = (best[k] / count for k in ("design", "row", "row before"))
        share = (row - work) / work
        rows.append(
            {
                "study": "overhead",
                "method": f"{name} pitch",
                "n": count,
                "seconds": row,
                "design_seconds": work,
                "before_seconds": before,
                "overhead_share": share,
                "before_share": (before - work) / work,
                "goal": f"overhead ≤ {OVERHEAD_GOAL:.0%} of the design",
                "met": share <= OVERHEAD_GOAL,
            }
        )
        if step is not None:
            step(f"overhead: {name} pitch")
    return rows


def overhead_lines(rows: list[dict]) -> list[str]:
    """The overhead rows as markdown table lines."""
    out = [
        "| profile, stage | design (ms) | row (ms) | overhead | row before (ms) | overhead before "
        "| designs/h/core | goal | met |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["study"] != "overhead":
            continue
        out.append(
            f"| {r['method']} | {1000 * r['design_seconds']:.3f} | {1000 * r['seconds']:.3f} "
            f"| {r['overhead_share']:.0%} | {1000 * r['before_seconds']:.3f} | {r['before_share']:.0%} "
            f"| {3600 / r['seconds']:,.0f} | {r['goal']} | {'met' if r['met'] else 'not met'} |"
        )
    return out


def overhead_summary(rows: list[dict]) -> list[str]:
    """One line per profile for the bench's summary."""
    return [
        f"sweep overhead, {r['method']}: {r['overhead_share']:.0%} of the design's "
        f"{1000 * r['design_seconds']:.3f} ms (before issue 35: {r['before_share']:.0%}); "
        f"{3600 / r['seconds']:,.0f} designs/h per core (before: {3600 / r['before_seconds']:,.0f}) "
        f"(goal ≤ {OVERHEAD_GOAL:.0%}: {'met' if r['met'] else 'not met'})"
        for r in rows
        if r["study"] == "overhead"
    ]
