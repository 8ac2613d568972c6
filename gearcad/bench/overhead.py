"""A sweep's cost per design beyond the design itself (issue 35 item 6), at the pitch stage.

For the focus pair (a closed form: the design is cheap, so what surrounds it shows) and the
walker (a synthesis: 250 times dearer), a chunk of designs over ``gear1`` is timed, in
interleaved rounds, CPU seconds per design, the fastest round of each (load only adds):

- ``design``: ``design(params, "pitch")`` alone, the parameters made beforehand — the work;
- ``overhead``: what a sweep's worker does for a design besides it — its parameters from the
  profile validated once (:class:`~gearcad.sweeps.variants.Variants`) and its row from the design
  (:func:`~gearcad.sweeps.evaluate.scalars`) — and ``overhead before``: the same as it was before
  issue 35, the whole overridden profile validated and the report built and walked;
- ``row``: :func:`~gearcad.sweeps.evaluate.evaluate_chunk` whole, what the worker runs (its
  designs/h); the loop costs a little more than its parts timed apart (the caches are shared).

The goal: the overhead at most 20 % of the design's own time.
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

    return [
        _row_before(design(p, "pitch")) | {"index": i}
        for i, p in zip((i for i, _ in chunk), _params_before(data, name, chunk))
    ]


def _params_before(data: dict, name: str, chunk: list[tuple[int, dict]]) -> list:
    from ..profiles.reading import apply_overrides, parse_profile

    return [parse_profile(apply_overrides(data, overrides), default_name=name) for _, overrides in chunk]


def _params_now(variants, chunk: list[tuple[int, dict]]) -> list:
    return [variants.params(overrides) for _, overrides in chunk]


def _row_before(d) -> dict:
    from ..sweeps.evaluate import flatten

    report = d.report()
    return {"index": None, "refusal": None, "warnings": len(report["warnings"]), **flatten(report)}


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
    from ..sweeps.evaluate import evaluate_chunk, scalars
    from ..sweeps.space import read_toml
    from ..sweeps.variants import Variants
    from .commands import PROFILES

    rows = []
    for name, (key, low, high, count) in CASES.items():
        if quick and name != "elliptic_focus":
            continue
        data = read_toml(PROFILES / f"{name}.toml", "profile")
        count = min(count, 60) if quick else count
        chunk = [(i, {key: low + (high - low) * i / max(count - 1, 1)}) for i in range(count)]
        params = _params_before(data, name, chunk)
        made = evaluate_chunk(data, name, "pitch", chunk)
        if any(r["refusal"] for r in made) or [[*r.items()] for r in made] != [
            [*r.items()] for r in _before(data, name, chunk)
        ]:
            raise AssertionError(f"{name}: a sweep's rows differ from the report's, or a design is refused")
        designs = [design(p, "pitch") for p in params]
        level = logging.getLogger("gearcad").level
        try:
            best = _fastest(
                {
                    "design": lambda: [design(p, "pitch") for p in params],
                    "params": lambda: _params_now(Variants(data, name), chunk),
                    "rows": lambda: [scalars(d, {"index": 0, "refusal": None}) for d in designs],
                    "params before": lambda: _params_before(data, name, chunk),
                    "rows before": lambda: [_row_before(d) for d in designs],
                    "row": lambda: evaluate_chunk(data, name, "pitch", chunk),
                    "row before": lambda: _before(data, name, chunk),
                },
                rounds=2 if quick else 3 if count < 100 else 7,
            )
        finally:
            logging.getLogger("gearcad").setLevel(level)
        per = {k: v / count for k, v in best.items()}
        work = per["design"]
        overhead, before = per["params"] + per["rows"], per["params before"] + per["rows before"]
        rows.append(
            {
                "study": "overhead",
                "method": f"{name} pitch",
                "n": count,
                "seconds": per["row"],
                "design_seconds": work,
                "overhead_seconds": overhead,
                "before_seconds": before,
                "row_before_seconds": per["row before"],
                "overhead_share": overhead / work,
                "before_share": before / work,
                "goal": f"overhead ≤ {OVERHEAD_GOAL:.0%} of the design",
                "met": overhead / work <= OVERHEAD_GOAL,
            }
        )
        if step is not None:
            step(f"overhead: {name} pitch")
    return rows


def overhead_lines(rows: list[dict]) -> list[str]:
    """The overhead rows as markdown table lines."""
    out = [
        "| profile, stage | design (ms) | overhead (ms) | share | before (ms) | share before | row in the loop (ms) "
        "| designs/h/core | goal | met |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["study"] != "overhead":
            continue
        out.append(
            f"| {r['method']} | {1000 * r['design_seconds']:.3f} | {1000 * r['overhead_seconds']:.4f} "
            f"| {r['overhead_share']:.1%} | {1000 * r['before_seconds']:.4f} | {r['before_share']:.1%} "
            f"| {1000 * r['seconds']:.3f} | {3600 / r['seconds']:,.0f} | {r['goal']} "
            f"| {'met' if r['met'] else 'not met'} |"
        )
    return out


def overhead_summary(rows: list[dict]) -> list[str]:
    """One line per profile for the bench's summary."""
    return [
        f"sweep overhead, {r['method']}: {r['overhead_share']:.1%} of the design's {1000 * r['design_seconds']:.3f} ms "
        f"(before issue 35: {r['before_share']:.1%}; goal ≤ {OVERHEAD_GOAL:.0%}: {'met' if r['met'] else 'not met'}); "
        f"a worker's loop {3600 / r['seconds']:,.0f} designs/h per core (before: {3600 / r['row_before_seconds']:,.0f})"
        for r in rows
        if r["study"] == "overhead"
    ]
