"""One chunk of a sweep, evaluated wherever a worker runs: plain data in, plain rows out.

A worker gets the profile as the dict its TOML reads to (no file needs to be on the worker) and a
list of (index, overrides); it returns one row per design — a refused design is a row with its
reason, never an exception.  Nothing here depends on the worker, so rows are the same anywhere.
"""

from __future__ import annotations

import logging
from typing import Any

from ..errors import GearcadError
from ..fitting import design
from ..profiles.reading import apply_overrides, parse_profile

__all__ = ["evaluate_chunk", "flatten"]

_SKIP = {"schema", "name", "title", "summary", "units", "mechanism", "warnings", "stage"}


def flatten(report: dict, prefix: str = "") -> dict[str, Any]:
    """The report's scalars under dotted keys (``gears.0.teeth.min_tip_thickness``); lists of
    numbers (pivots, intervals) are left out, lists of tables numbered."""
    out: dict[str, Any] = {}
    for key, value in report.items():
        if not prefix and key in _SKIP:
            continue
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(flatten(value, f"{name}."))
        elif isinstance(value, list):
            for i, item in enumerate(value):
                if isinstance(item, dict):
                    out.update(flatten(item, f"{name}.{i}."))
        elif value is None or isinstance(value, (bool, int, float, str)):
            out[name] = value
    return out


def evaluate_chunk(data: dict, name: str, stage: str, chunk: list[tuple[int, dict]]) -> list[dict[str, Any]]:
    """Rows ``{"index", "refusal", "warnings", <report keys>…}`` for the chunk's designs."""
    logging.getLogger("gearcad").setLevel(logging.ERROR)  # warnings are counted in the row
    rows = []
    for index, overrides in chunk:
        row: dict[str, Any] = {"index": index, "refusal": None}
        try:
            d = design(parse_profile(apply_overrides(data, overrides), default_name=name), stage)
            report = d.report()
            row["warnings"] = len(report["warnings"])
            row.update(flatten(report))
        except GearcadError as exc:
            row["refusal"] = " ".join(str(exc).split())
        except Exception as exc:  # noqa: BLE001 - a sweep reports a design that breaks gearcad, and goes on
            row["refusal"] = f"internal error ({type(exc).__name__}: {' '.join(str(exc).split())}); please report"
        rows.append(row)
    return rows
