"""``gearcad compare A B``: two designs' key numbers and findings side by side.

The numbers are the report's own (``report.json``), flattened to dotted keys; lists of
gears are keyed by their place from 0 (``gears.0.name``), as ``sweep`` and report.json's lists number
them, so two designs line up row by row.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

from .batch import design_all
from .profiles import load_profile

__all__ = ["KEY_BLOCKS", "key_numbers", "compare_lines"]

KEY_BLOCKS = ("pair", "gears", "kinematics", "body", "drive", "geometry", "motion", "train", "compound", "assembly")
"""The report's blocks compared (``parts``, ``files`` and ``output`` say how, not what)."""


def _flat(value: Any, key: str) -> Iterator[tuple[str, Any]]:
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _flat(v, f"{key}.{k}")
    elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for n, v in enumerate(value):  # by place from 0, as sweep keys them: two designs' gears line up
            yield from _flat(v, f"{key}.{n}")
    elif isinstance(value, bool | int | float | str) and not isinstance(value, list):
        yield key, value


def key_numbers(report: dict) -> dict[str, Any]:
    """``{dotted key: value}`` of every scalar in the report's :data:`KEY_BLOCKS`."""
    return {k: v for block in KEY_BLOCKS if block in report for k, v in _flat(report[block], block)}


def _show(value: Any) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{value:.6g}" if math.isfinite(value) else str(value)
    return str(value)


def _differ(a: Any, b: Any) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    return a != b


def compare_lines(a: Path, b: Path, overrides: Sequence[str] = (), unset: Sequence[str] = ()) -> list[str]:
    """Profiles ``a`` and ``b`` (``overrides``, ``unset`` applied to ``b`` only, so that a profile can
    be compared with a variant of itself) as lines of text: summaries, a table of key numbers
    (``*`` where they differ), then each design's findings."""
    (first,) = design_all([load_profile(a)])
    (second,) = design_all([load_profile(b, overrides, unset=unset)])
    a, b = key_numbers(first.report()), key_numbers(second.report())
    keys = list(dict.fromkeys([*a, *b]))
    names = (first.name, second.name) if first.name != second.name else ("A", "B")
    width = max([len(k) for k in keys] + [3])
    col = max([len(_show(v)) for v in (*a.values(), *b.values())] + [len(n) for n in names])
    lines = [f"{names[0]}: {first.summary}", f"{names[1]}: {second.summary}", ""]
    lines.append(f"  {'key':<{width}}  {names[0]:>{col}}  {names[1]:>{col}}")
    for key in keys:
        mark = "*" if _differ(a.get(key), b.get(key)) else " "
        lines.append(f"{mark} {key:<{width}}  {_show(a.get(key)):>{col}}  {_show(b.get(key)):>{col}}")
    for name, d in zip(names, (first, second)):
        lines.append("")
        lines.append(f"{name}: {len(d.findings)} finding(s)")
        lines += [f"  [{f.code}] {f.message}" for f in d.findings]
    return lines
