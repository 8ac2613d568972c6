"""One chunk of a sweep, evaluated wherever a worker runs: plain data in, plain rows out.

A worker gets the profile as the dict its TOML reads to (no file needs to be on the worker) and a
list of (index, overrides); it returns one row per design — a refused design is a row with its
reason, never an exception.  Nothing here depends on the worker, so rows are the same anywhere.
"""

from __future__ import annotations

import logging
import math
from typing import Any

import numpy as np

from ..errors import GearcadError
from ..fitting import design
from .overrides import overridden

__all__ = ["evaluate_chunk", "flatten", "overridden", "scalars"]

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


def scalars(d, out: dict[str, Any] | None = None) -> dict[str, Any]:
    """``flatten(d.report())`` without building the report (into ``out`` if given): for a design
    before the full stage (no parts, no assembly, no files), its report blocks walked once, numpy
    scalars made plain and NaN or infinity None as the report makes them (issue 35: the report
    and its walk were a fifth of a pitch-stage design's time)."""
    out = {} if out is None else out
    data = d.data
    if d.stage == "full" or d.part_list or not all(isinstance(g, dict) for g in data.get("gears", ())):
        out.update(flatten(d.report()))
    elif data.keys().isdisjoint(_TOP):  # the report: tolerance, the blocks, ok
        out["tolerance"] = d.params.output.tolerance
        _walk(data, "", out)
        out["ok"] = d.ok
    else:  # a block named as one of the report's own keys: built as the report builds it
        top = {"tolerance": d.params.output.tolerance, **data, "warnings": None, "ok": d.ok}
        _walk({k: v for k, v in top.items() if k not in _SKIP_EARLY}, "", out)
    return out


_SKIP_EARLY = (*_SKIP, "parts", "assembly", "output", "files")
"""The report's top-level keys no row holds, and those a stage before "full" does not report."""
_TOP = {*_SKIP_EARLY, "tolerance", "ok"}
"""Keys of the report that a block of the same name would replace or be replaced by."""
_F64 = np.float64
_FINITE = math.isfinite


def _walk(node: dict, prefix: str, out: dict[str, Any]) -> None:
    """``flatten(finite(node), prefix)`` into ``out``, in one walk (plain numbers, text, tables
    and lists of tables, the common cases, first)."""
    for key, value in node.items():
        kind = type(value)
        if kind is float or kind is _F64:
            out[f"{prefix}{key}"] = float(value) if _FINITE(value) else None
        elif kind is str or kind is int or kind is bool or value is None:
            out[f"{prefix}{key}"] = value
        elif kind is dict:
            _walk(value, f"{prefix}{key}.", out)
        elif kind is list or kind is tuple:
            for i, item in enumerate(value):
                if type(item) is dict:
                    _walk(item, f"{prefix}{key}.{i}.", out)
                elif isinstance(item, dict):
                    _walk(item, f"{prefix}{key}.{i}.", out)
        else:
            _put(value, f"{prefix}{key}", out)


def _put(value: Any, name: str, out: dict[str, Any]) -> None:
    """``flatten`` of ``finite(value)`` under ``name``."""
    if isinstance(value, (float, np.floating)):
        out[name] = float(value) if math.isfinite(value) else None
    elif isinstance(value, dict):
        _walk(value, f"{name}.", out)
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            if isinstance(item, dict):
                _walk(item, f"{name}.{i}.", out)
    elif isinstance(value, np.integer):
        out[name] = int(value)
    elif isinstance(value, np.bool_):
        out[name] = bool(value)
    elif value is None or isinstance(value, (bool, int, str)):
        out[name] = value


def _refusal(exc: Exception) -> str:
    if isinstance(exc, GearcadError):
        return " ".join(str(exc).split())
    # a sweep reports a design that breaks gearcad, and goes on
    return f"internal error ({type(exc).__name__}: {' '.join(str(exc).split())}); please report"


def evaluate_chunk(data: dict, name: str, stage: str, chunk: list[tuple[int, dict]]) -> list[dict[str, Any]]:
    """Rows ``{"index", "refusal", "warnings", <report keys>…}`` for the chunk's designs (at the
    full stage also ``failures``: the codes of the findings that fail a check, space-separated);
    a refused design is a row with its reason.

    The profile is validated once for the chunk and each design's overrides alone
    (:class:`~gearcad.sweeps.variants.Variants`), and the row is taken from the design without
    building its report (:func:`scalars`): the same rows, and the same refusals, as
    ``parse_profile`` on the overridden data and ``flatten(design.report())``.  The chunk goes
    through in three passes — every design's parameters, then every design, then every row —
    each a short loop over the same code: interleaved, the three took a quarter longer on a
    busy machine (measured at the pitch stage, issue 35)."""
    from .variants import Variants

    logging.getLogger("gearcad").setLevel(logging.ERROR)  # warnings are counted in the row
    variants = Variants(data, name)
    rows = [{"index": index, "refusal": None} for index, _ in chunk]
    made: list[Any] = [None] * len(chunk)
    for k, (_, overrides) in enumerate(chunk):
        try:
            made[k] = variants.params(overrides)
        except Exception as exc:  # noqa: BLE001 - the design's row says why
            rows[k]["refusal"] = _refusal(exc)
    for k, params in enumerate(made):
        if params is not None:
            try:
                made[k] = design(params, stage)
            except Exception as exc:  # noqa: BLE001 - the design's row says why
                made[k] = None
                rows[k]["refusal"] = _refusal(exc)
    for row, d in zip(rows, made):
        if d is None:
            continue
        row["warnings"] = len(d.findings)
        try:
            scalars(d, row)
            if stage == "full":  # what a full design fails, by code (a cheaper stage proves no check)
                row["failures"] = " ".join(f.code for f in d.failures())
        except Exception as exc:  # noqa: BLE001 - the design's row says why, and holds nothing else
            index = row["index"]
            row.clear()
            row.update(index=index, refusal=_refusal(exc))
    return rows
