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

__all__ = [
    "Constraint",
    "parse_constraint",
    "feasible",
    "pareto",
    "snap",
    "RunningFront",
    "row_values",
    "BITS",
    "FLOOR",
]

_OPS = {"<=": operator.le, ">=": operator.ge, "==": operator.eq, "!=": operator.ne, "<": operator.lt, ">": operator.gt}
_PATTERN = re.compile(r"^\s*([A-Za-z0-9_.]+)\s*(<=|>=|==|!=|<|>)\s*(.+?)\s*$")


class Constraint(tuple):
    """(key, op, value)."""

    def __str__(self) -> str:
        """As it would be written (TOML values: ``== false``, ``== "x"``), so that
        :func:`parse_constraint` reads it back."""
        value = self[2]
        if isinstance(value, bool):
            text = "true" if value else "false"
        elif isinstance(value, str):
            text = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
        else:
            text = str(value)
        return f"{self[0]} {self[1]} {text}"


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


BITS = 30
"""Objective values are compared after rounding to this many significant bits (a relative step
of 2⁻³¹…2⁻³⁰, at most 9.3e-10): values that differ only in rounding noise (9.000000000000009
against 9.000000000000007) compare equal, so the noise makes no front point."""

FLOOR = -40
"""…and never finer than 2⁻⁴⁰ ≈ 9.1e-13 in the key's own unit (mm, rad…): noise about zero
(a closure error of 1e-17 against 3e-17) compares equal too."""


def snap(values: np.ndarray) -> np.ndarray:
    """``values`` rounded to :data:`BITS` significant bits (and to a multiple of 2^:data:`FLOOR`),
    exactly (powers of two only) and monotonically: ``a <= b`` gives ``snap(a) <= snap(b)``.

    Each value is rounded on its own, so the comparison does not depend on which other rows
    are in the table: a front merged chunk by chunk is the front of the whole table.  Two
    values within 1e-9 of each other compare equal unless a rounding step falls between them
    (for rounding noise of 1e-15, about one pair in 10⁷); values more than 2⁻²⁹ ≈ 1.9e-9 apart
    (relative) never compare equal."""
    values = np.asarray(values, dtype=float)
    _, exponent = np.frexp(values)
    step = np.maximum(exponent - BITS, FLOOR)
    return np.ldexp(np.rint(np.ldexp(values, -step)), step) + 0.0  # + 0.0: no -0.0


def pareto(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Rows of ``values`` (rows, objectives; all to be minimised) on the front among ``mask``:
    no other masked row is as good in every objective and better in one, values compared after
    :func:`snap`.  A row with a NaN or infinite objective (refused, or not reporting it) is on
    no front.  Rows that tie in every objective are all on the front (equally good designs).

    Two objectives: sorted by the first, swept along the second, O(n log n).  More: Kung's
    divide and conquer on the rows sorted lexicographically (a row can only be dominated by one
    before it); for three objectives each merge is a sorted 2-D query (O(n log² n) in all), for
    four or more a vectorised comparison of the two halves' fronts (O(n · front) at worst)."""
    values = np.asarray(values, dtype=float)
    if values.ndim != 2:
        raise ValueError(f"values: must be (rows, objectives), not of shape {values.shape}")
    front = np.zeros(len(values), dtype=bool)
    if values.shape[1] == 0:
        return front
    index = np.flatnonzero(np.asarray(mask, dtype=bool) & np.all(np.isfinite(values), axis=1))
    if len(index):
        front[index[_front_of(snap(values[index]))]] = True
    return front


def _front_of(points: np.ndarray) -> np.ndarray:
    """Positions of the non-dominated rows of ``points`` (finite, to be minimised), sorted."""
    order = np.lexsort(points.T[::-1])  # by the first objective, then the second, …
    ranked = points[order]
    starts = np.ones(len(ranked), dtype=bool)
    starts[1:] = np.any(ranked[1:] != ranked[:-1], axis=1)  # the first of each run of equal rows
    unique = ranked[starts]
    if unique.shape[1] == 1:
        keep = np.zeros(len(unique), dtype=bool)
        keep[0] = True
    elif unique.shape[1] == 2:
        keep = _front_2d(unique)
    else:
        keep = np.zeros(len(unique), dtype=bool)
        keep[_kung(unique, np.arange(len(unique)))] = True
    chosen = np.zeros(len(points), dtype=bool)
    chosen[order] = keep[np.cumsum(starts) - 1]  # every row of a run as its first
    return np.flatnonzero(chosen)


def _front_2d(unique: np.ndarray) -> np.ndarray:
    """Distinct points sorted by (first, second): a point is on the front when its second value
    is below every second value before it (ties in the first come later with larger seconds)."""
    second = unique[:, 1]
    best_before = np.minimum.accumulate(np.concatenate([[np.inf], second[:-1]]))
    return second < best_before


MERGE_CELLS = 1 << 22
"""Comparisons per vectorised block in Kung's merge (bounds its memory to ~ 4 M × objectives)."""


LEAF = 64
"""Rows below which Kung's recursion compares every pair at once."""


def _kung(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Kung, Luccio & Preparata (1975): the front of ``points[rows]`` (distinct, sorted
    lexicographically), as positions into ``points``, in order."""
    if len(rows) <= LEAF:
        p = points[rows]
        covers = np.all(p[:, None, :] <= p[None, :, :], axis=2)  # [i, j]: row i is nowhere worse than j
        np.fill_diagonal(covers, False)  # distinct rows: covering another is dominating it
        return rows[~covers.any(axis=0)]
    half = len(rows) // 2
    top = _kung(points, rows[:half])
    bottom = _kung(points, rows[half:])
    return _merge(points, top, bottom)


def _merge(points: np.ndarray, top: np.ndarray, bottom: np.ndarray) -> np.ndarray:
    """``top`` (a front, before ``bottom`` in order: no row of ``bottom`` can dominate one of
    it) and the rows of the front ``bottom`` that no row of ``top`` dominates."""
    if len(top) == 0 or len(bottom) == 0:
        return np.concatenate([top, bottom])
    if points.shape[1] == 3:  # every row of top is nowhere worse in the first: a 2-D query on the others
        a = points[top]
        by_second = np.argsort(a[:, 1], kind="stable")
        least_third = np.minimum.accumulate(a[by_second, 2])
        b = points[bottom]
        reach = np.searchsorted(a[by_second, 1], b[:, 1], side="right")  # rows of top with second <= b's
        covered = (reach > 0) & (least_third[np.maximum(reach - 1, 0)] <= b[:, 2])
        return np.concatenate([top, bottom[~covered]])
    a = points[top]
    keep = np.ones(len(bottom), dtype=bool)
    block = max(1, MERGE_CELLS // len(top))
    for start in range(0, len(bottom), block):
        b = points[bottom[start : start + block]]
        keep[start : start + block] = ~np.any(np.all(a[None, :, :] <= b[:, None, :], axis=2), axis=1)
    return np.concatenate([top, bottom[keep]])


class RunningFront:
    """The front merged chunk by chunk as a sweep's chunks return, in any order: after every
    chunk has been added, :meth:`rows` is ``np.flatnonzero(pareto(values, mask))`` of the whole
    table (each value is rounded on its own, and a row dominated by any row is dominated by a
    row of the front).  Memory: the front so far, not the table.

    :func:`gearcad.sweep` does not use it: it takes the front once from the finished table, which
    costs a third of the CPU that reading every returned row and merging would spend in the client
    (docs/sweep.md, measured on 10⁵ rows); it is here for a caller that wants the front while its
    designs run.

    >>> f = RunningFront(2)
    >>> f.add([2, 3], [[1.0, 5.0], [2.0, 2.0]])
    >>> f.add([0, 1], [[3.0, 3.0], [0.5, 9.0]], mask=[True, False])
    >>> f.rows().tolist()
    [2, 3]
    """

    def __init__(self, objectives: int) -> None:
        self._index = np.zeros(0, dtype=np.int64)
        self._points = np.zeros((0, objectives))

    def add(self, index, values, mask=None) -> None:
        """Merge rows ``index`` (their numbers in the table) with ``values`` (rows, objectives;
        to be minimised) and ``mask`` (True where feasible; default all) into the front."""
        index = np.asarray(index, dtype=np.int64).reshape(-1)
        values = np.asarray(values, dtype=float).reshape(len(index), self._points.shape[1])
        ok = np.ones(len(index), dtype=bool) if mask is None else np.asarray(mask, dtype=bool).reshape(-1)
        ok &= np.all(np.isfinite(values), axis=1)
        points = snap(values[ok])
        both = np.concatenate([self._points, points])
        rows = np.concatenate([self._index, index[ok]])
        kept = _front_of(both) if len(both) else np.zeros(0, dtype=int)
        self._points, self._index = both[kept], rows[kept]

    def rows(self) -> np.ndarray:
        """The table's rows on the front, in order."""
        return np.sort(self._index)


def row_values(
    rows: list[dict], minimise: list[str], maximise: list[str], constraints: list[Constraint]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(index, values, feasible)`` of rows as a chunk returns them (``{"index", "refusal",
    <report keys>…}``), for :meth:`RunningFront.add`: what :func:`feasible` and the table's
    objective columns give, row by row (maximised keys negated; a missing, text or None value
    is NaN, so the row is on no front)."""
    keys = [*minimise, *maximise]
    index = np.array([r["index"] for r in rows], dtype=np.int64)
    values = np.array(
        [[_number(r.get(k)) * (1 if k in minimise else -1) for k in keys] for r in rows], dtype=float
    ).reshape(len(rows), len(keys))
    ok = np.array(
        [
            r.get("refusal") is None
            and all(
                (v := r.get(key)) is not None and v == v and bool(_OPS[op](v, value)) for key, op, value in constraints
            )
            for r in rows
        ],
        dtype=bool,
    )
    return index, values, ok


def _number(value) -> float:
    if isinstance(value, (bool, int, float, np.integer, np.floating)):
        return float(value)
    return float("nan")
