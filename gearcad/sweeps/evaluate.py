"""One chunk of a sweep, evaluated wherever a worker runs: plain data in, plain rows out.

A worker gets the profile as the dict its TOML reads to (no file needs to be on the worker) and a
list of (index, overrides); it returns one row per design — a refused design is a row with its
reason, never an exception.  Nothing here depends on the worker, so rows are the same anywhere.
"""

from __future__ import annotations

import logging
from typing import Any

from ..errors import GearcadError, ProfileError
from ..fitting import design
from ..profiles.reading import EXCLUSIVE_KEYS, parse_profile

__all__ = ["evaluate_chunk", "flatten", "overridden"]

_PARTNER = {a: b for pair in EXCLUSIVE_KEYS for a, b in (pair, pair[::-1])}

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


def overridden(data: dict, overrides: dict[str, Any]) -> dict:
    """What ``apply_overrides(data, overrides)`` gives for a sweep's point, without copying the
    whole profile for every design: only the tables on an override's path are copied (a profile
    of 100,000 sampled radii is not), and ``data`` is not walked again (it was, once, as the
    sweep began).  The values are plain numbers, true/false or text, checked as the sweep began.
    """
    result = dict(data)
    fresh = {id(result)}  # the tables copied for this design: set into freely

    def table(node: dict, part: str, make: bool) -> Any:
        child = node.get(part)
        if child is None and make:
            child = node[part] = {}
            fresh.add(id(child))
        elif isinstance(child, dict) and id(child) not in fresh:
            child = node[part] = dict(child)
            fresh.add(id(child))
        return child

    for key, value in overrides.items():
        parts = key.split(".")
        node: Any = result
        for depth, part in enumerate(parts[:-1], 1):
            node = table(node, part, make=True)
            if not isinstance(node, dict):
                raise ProfileError(f"override {key!r}: {'.'.join(parts[:depth])} is not a table")
        node[parts[-1]] = value
        partner = _PARTNER.get(key)
        if partner is not None:
            *path, last = partner.split(".")
            node = result
            for part in path:
                node = table(node, part, make=False) if isinstance(node, dict) else None
            if isinstance(node, dict):
                node.pop(last, None)
    name, title = result.get("name"), result.get("title")
    if "name" in overrides and "title" not in overrides and isinstance(name, str) and isinstance(title, str) and title:
        result["title"] = f"{title} ({name})"  # as apply_overrides: a variant must not look like the original
    return result


def evaluate_chunk(data: dict, name: str, stage: str, chunk: list[tuple[int, dict]]) -> list[dict[str, Any]]:
    """Rows ``{"index", "refusal", "warnings", <report keys>…}`` for the chunk's designs (at the
    full stage also ``failures``: the codes of the findings that fail a check, space-separated)."""
    logging.getLogger("gearcad").setLevel(logging.ERROR)  # warnings are counted in the row
    rows = []
    for index, overrides in chunk:
        row: dict[str, Any] = {"index": index, "refusal": None}
        try:
            d = design(parse_profile(overridden(data, overrides), default_name=name), stage)
            report = d.report()
            row["warnings"] = len(report["warnings"])
            row.update(flatten(report))
            if stage == "full":  # what a full design fails, by code (a cheaper stage proves no check)
                row["failures"] = " ".join(f.code for f in d.failures())
        except GearcadError as exc:
            row["refusal"] = " ".join(str(exc).split())
        except Exception as exc:  # noqa: BLE001 - a sweep reports a design that breaks gearcad, and goes on
            row["refusal"] = f"internal error ({type(exc).__name__}: {' '.join(str(exc).split())}); please report"
        rows.append(row)
    return rows
