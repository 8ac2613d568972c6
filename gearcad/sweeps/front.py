"""Constraints and objectives over a sweep's table, and its Pareto front.

A constraint is ``KEY OP VALUE`` with OP one of ``<= >= < > == !=`` and VALUE read as TOML
(``gears.0.teeth.undercut == false``, ``gears.0.teeth.min_tip_thickness >= 0.4``); an objective
is a report key to minimise or maximise.  A refused design meets no constraint.
"""

from __future__ import annotations

import operator
import re

import numpy as np

from ..errors import ProfileError
from ..profiles.reading import toml_value

__all__ = ["Constraint", "parse_constraint", "feasible", "pareto"]

_OPS = {"<=": operator.le, ">=": operator.ge, "==": operator.eq, "!=": operator.ne, "<": operator.lt, ">": operator.gt}
_PATTERN = re.compile(r"^\s*([A-Za-z0-9_.]+)\s*(<=|>=|==|!=|<|>)\s*(.+?)\s*$")


class Constraint(tuple):
    """(key, op, value)."""

    def __str__(self) -> str:
        return f"{self[0]} {self[1]} {self[2]}"


def parse_constraint(text: str) -> Constraint:
    match = _PATTERN.match(text)
    if not match:
        raise ProfileError(f"--constraint {text!r}: must be KEY OP VALUE with OP one of {' '.join(_OPS)}")
    key, op, raw = match.groups()
    return Constraint((key, op, toml_value(raw, f"--constraint {text!r}")))


def check_keys(columns, keys: list[str], what: str) -> None:
    """Refuse a constraint or objective naming no column of the table."""
    for key in keys:
        if key not in columns:
            near = sorted(c for c in columns if c.split(".")[-1] == key.split(".")[-1])[:4]
            hint = f" (did you mean {', '.join(near)}?)" if near else " (any report key of the stage, dotted)"
            raise ProfileError(f"{what} {key!r}: no design of the sweep reports it{hint}")


def feasible(table, constraints: list[Constraint]) -> np.ndarray:
    """A bool per row: the design was made and meets every constraint."""
    ok = table["refusal"].isna().to_numpy().copy()
    for key, op, value in constraints:
        column = table[key]
        held = np.array([v is not None and v == v and bool(_OPS[op](v, value)) for v in column], dtype=bool)
        ok &= held
    return ok


def pareto(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Rows of ``values`` (rows, objectives; all to be minimised) on the front among ``mask``:
    no other masked row is as good in every objective and better in one."""
    front = np.zeros(len(values), dtype=bool)
    index = np.flatnonzero(mask & np.all(np.isfinite(values), axis=1))
    pts = values[index]
    for j, p in zip(index, pts):
        dominated = np.any(np.all(pts <= p, axis=1) & np.any(pts < p, axis=1))
        front[j] = not dominated
    return front
