"""Sweeps that search: NSGA-II (pymoo) over the ``KEY=a:b`` ranges, and the hypervolume of a front.

Each generation's population is one batch through the same chunked evaluator as a grid
(:func:`gearcad.sweeps.executors.run_chunks`), so the rows are the same on one process, a local
pool or a Dask cluster; the search itself runs here, in the client, on pymoo's own seeded random
generator (nothing else draws from it), so a seed gives the same generations everywhere.

Objectives are minimised as given (a maximised key negated); each constraint's violation amount
(:func:`gearcad.sweeps.violations`) is one of pymoo's inequality constraints (≤ 0 is met), and one
more says "not made" (a refused design, an objective without a number, or a strict bound met
only with equality) — so pymoo ranks feasible designs first and the others by how far they miss.
A range whose ends are whole numbers, over a key the profile gives as a whole number (or does not
give), is searched over whole numbers.  pymoo is the optional extra ``gearcad[optimise]``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import ProfileError

__all__ = [
    "METHODS",
    "POPULATION",
    "GENERATIONS",
    "require_pymoo",
    "budget",
    "whole_keys",
    "optimise",
    "hypervolume",
    "reference_point",
    "grid_overrides",
]

METHODS = ("grid", "nsga2")
"""``grid``: the points of the varies (grids, lists, samples); ``nsga2``: pymoo's NSGA-II."""

POPULATION = 40
GENERATIONS = 10
"""The default budget: 40 designs a generation, 10 generations (400 designs)."""

NOT_MADE = 1.0
"""The violation of a design that was refused or gives an objective no number."""


def require_pymoo(method: str) -> None:
    """One line if pymoo is not installed."""
    try:
        import pymoo  # noqa: F401
    except ImportError:
        raise ProfileError(
            f"--method {method}: needs pymoo, not installed here; pip install gearcad[optimise]"
        ) from None


def budget(population: int | None, generations: int | None, evaluations: int | None) -> tuple[int, int]:
    """(population, generations): ``evaluations`` with a population gives ⌈N / P⌉ generations."""
    for what, value in (("population", population), ("generations", generations), ("evaluations", evaluations)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
            raise ProfileError(f"{what} = {value!r}: must be a whole number ≥ 1")
    if population is not None and population < 4:
        raise ProfileError(f"population = {population}: must be at least 4 (NSGA-II mates pairs)")
    if evaluations is not None and generations is not None:
        raise ProfileError("give --generations or --evaluations, not both")
    size = population or POPULATION
    if evaluations is not None:
        return size, max(1, math.ceil(evaluations / size))
    if size * (generations or GENERATIONS) > 1_000_000:
        raise ProfileError(f"population × generations = {size * (generations or GENERATIONS)}: at most 1000000")
    return size, generations or GENERATIONS


def _value(data: dict, key: str) -> Any:
    node: Any = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def whole_keys(data: dict, varies) -> list[bool]:
    """Per varied key: searched over whole numbers (both ends whole, the profile's value whole or absent)."""
    out = []
    for v in varies:
        base = _value(data, v.key)
        whole_base = base is None or (isinstance(base, int) and not isinstance(base, bool))
        out.append(whole_base and all(float(e).is_integer() for e in v.span))
    return out


def _check_spans(varies, method: str) -> None:
    if not varies:
        raise ProfileError(f"--method {method}: vary at least one key as a range, KEY=a:b")
    for v in varies:
        if v.span is None:
            raise ProfileError(
                f"--vary {v.key}: --method {method} searches a range; give KEY=a:b (not a grid a:b:n or a list)"
            )


def first_point(data: dict, varies) -> dict[str, Any]:
    """The middle of every range: the point the sweep's keys are checked on before the search."""
    out = {}
    for v, whole in zip(varies, whole_keys(data, varies)):
        mid = (v.span[0] + v.span[1]) / 2
        out[v.key] = int(math.floor(mid)) if whole else float(mid)
    return out


def _overrides(keys: list[str], whole: list[bool], x: np.ndarray) -> dict[str, Any]:
    return {k: (int(round(float(v))) if w else float(v)) for k, w, v in zip(keys, whole, x)}


def _targets(rows: list[dict], conditions, minimise, maximise) -> tuple[np.ndarray, np.ndarray]:
    """(F, G) for pymoo: objectives to minimise and violation amounts (≤ 0 met)."""
    import pandas as pd

    from . import violations
    from .front import feasible

    keys = [*minimise, *maximise]
    table = pd.DataFrame(rows)
    for key in {*keys, *(c[0] for c in conditions)} - set(table.columns):
        table[key] = None
    if "refusal" not in table:
        table["refusal"] = None
    F = np.column_stack(
        [pd.to_numeric(table[k], errors="coerce").to_numpy(float) * (1 if k in minimise else -1) for k in keys]
    )
    amounts = [a.to_numpy(dtype=float, na_value=NOT_MADE) for a in violations(table, conditions).values()]
    missing = ~np.isfinite(F).all(axis=1) | table["refusal"].notna().to_numpy()
    met = feasible(table, conditions)
    unmet = np.where(missing, NOT_MADE, 0.0)
    # a strict bound met with equality has violation 0 but is not feasible: a little more than 0
    short = ~missing & ~met & (np.sum(amounts, axis=0) <= 0 if amounts else True)
    unmet = np.where(short, 1e-9, unmet)
    G = np.column_stack([*amounts, unmet]) if amounts else unmet[:, None]
    return np.where(np.isfinite(F), F, 0.0), G


def _nsga2(varies, columns, objectives: int, constraints: int, *, population: int, generations: int, seed: int):
    """pymoo's problem over the varied keys' spans and its NSGA-II, set up (whole-number keys,
    at ``columns``, rounded before they are designed)."""
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem
    from pymoo.core.repair import Repair

    keys = [v.key for v in varies]

    class _Whole(Repair):  # whole-number keys rounded before they are designed
        def _do(self, problem, X, **kwargs):
            X = np.array(X, dtype=float)
            X[:, columns] = np.round(X[:, columns])
            return X

    problem = Problem(
        n_var=len(keys),
        n_obj=objectives,
        n_ieq_constr=constraints + 1,
        xl=np.array([v.span[0] for v in varies], float),
        xu=np.array([v.span[1] for v in varies], float),
    )
    algorithm = NSGA2(pop_size=population, repair=_Whole(), eliminate_duplicates=True)
    algorithm.setup(problem, termination=("n_gen", generations), seed=seed, verbose=False)
    return problem, algorithm


def optimise(
    data: dict,
    name: str,
    stage: str,
    varies,
    conditions,
    minimise: list[str],
    maximise: list[str],
    *,
    method: str = "nsga2",
    population: int,
    generations: int,
    seed: int = 0,
    run: Callable[[list[tuple[int, dict]]], list[dict]],
    progress: Callable[[int, int], None] | None = None,
) -> tuple[list[dict], list[dict], list[int]]:
    """The search: (rows, overrides, generation of each row), rows in the order designed.
    ``run`` designs a batch of (index, overrides) and returns its rows in order (the sweep's
    :func:`run_chunks` on its workers or cluster)."""
    _check_spans(varies, method)
    if not minimise and not maximise:
        raise ProfileError(f"--method {method}: give at least one objective (--minimise or --maximise)")
    require_pymoo(method)
    from pymoo.core.evaluator import Evaluator
    from pymoo.problems.static import StaticProblem

    keys = [v.key for v in varies]
    whole = whole_keys(data, varies)
    problem, algorithm = _nsga2(varies, np.flatnonzero(whole), len(minimise) + len(maximise), len(conditions),
                                population=population, generations=generations, seed=seed)  # fmt: skip
    rows: list[dict] = []
    overrides: list[dict] = []
    born: list[int] = []
    total = population * generations
    for generation in range(generations):
        pop = algorithm.ask()
        if pop is None or len(pop) == 0:  # nothing new left to try (a tiny whole-number space)
            break
        batch = [_overrides(keys, whole, x) for x in pop.get("X")]
        start = len(rows)
        made = run([(start + i, o) for i, o in enumerate(batch)])
        F, G = _targets(made, conditions, minimise, maximise)
        Evaluator().eval(StaticProblem(problem, F=F, G=G), pop)
        algorithm.tell(infills=pop)
        rows += made
        overrides += batch
        born += [generation] * len(batch)
        if progress is not None:
            progress(len(rows), max(total, len(rows)))
    return rows, overrides, born


def grid_overrides(data: dict, varies, evaluations: int) -> list[dict[str, Any]]:
    """A grid over the ranges with at most ``evaluations`` points: ⌊N^(1/k)⌋ values a key (fewer
    where a whole-number range has fewer), the budget's share of a grid sweep."""
    import itertools

    per = max(1, int(math.floor(evaluations ** (1 / len(varies)) + 1e-9)))
    axes = []
    for v, whole in zip(varies, whole_keys(data, varies)):
        if whole:
            values = sorted({int(round(x)) for x in np.linspace(v.span[0], v.span[1], per)})
        else:
            values = [float(x) for x in np.linspace(v.span[0], v.span[1], per)]
        axes.append(values)
    keys = [v.key for v in varies]
    return [dict(zip(keys, combo)) for combo in itertools.product(*axes)]


def reference_point(*fronts: np.ndarray) -> np.ndarray:
    """The hypervolume's reference point: the nadir (worst value of each objective, minimised)
    of the fronts together, plus 10 % of their span in it (1 % of its size, or 1, where the span is 0)."""
    points = np.vstack([f for f in fronts if len(f)])
    worst, best = points.max(axis=0), points.min(axis=0)
    span = worst - best
    fallback = np.where(worst != 0, 0.01 * np.abs(worst), 1.0)
    return worst + np.where(span > 0, 0.1 * span, fallback)


def hypervolume(front: np.ndarray, reference: np.ndarray) -> float:
    """The volume the (minimised) front dominates up to ``reference``: pymoo's indicator."""
    from pymoo.indicators.hv import HV

    front = np.asarray(front, float)
    inside = front[(front < reference).all(axis=1)] if len(front) else front
    return float(HV(ref_point=np.asarray(reference, float))(inside)) if len(inside) else 0.0


def check_method(
    method, varies, minimise, maximise, population, generations, evaluations, against_grid, samples=0
) -> None:
    """A search's arguments, refused with one line before the first design."""
    if method not in METHODS:
        raise ProfileError(f"method = {method!r}: must be one of {', '.join(METHODS)}")
    if not isinstance(against_grid, bool):
        raise ProfileError(f"against_grid = {against_grid!r}: must be true or false")
    if method == "grid":
        for what, value in (("population", population), ("generations", generations), ("evaluations", evaluations)):
            if value is not None:
                raise ProfileError(f"--{what} {value}: only for a search (--method nsga2)")
        if against_grid:
            raise ProfileError("--against-grid: only for a search (--method nsga2)")
        return
    if samples:
        raise ProfileError(f"--samples {samples}: a search chooses its own points; give --population and --generations")
    budget(population, generations, evaluations)
    _check_spans(varies, method)
    keys = [v.key for v in varies]
    twice = [k for k in keys if keys.count(k) > 1]
    if twice:
        raise ProfileError(f"--vary {twice[0]}: the key is varied twice")
    if not minimise and not maximise:
        raise ProfileError(f"--method {method}: give at least one objective (--minimise or --maximise)")
    require_pymoo(method)


def _front_points(F: np.ndarray, G: np.ndarray) -> np.ndarray:
    from .front import pareto

    ok = (G <= 0).all(axis=1)
    return F[pareto(F, ok)] if ok.any() else F[:0]


def search(
    data, name, stage, varies, conditions, minimise, maximise, *, workers, client, scheduler_timeout, progress,
    method, seed, population, generations, evaluations, against_grid,
) -> tuple[list[dict], list[dict], dict[str, Any]]:  # fmt: skip
    """The sweep's search on its workers or cluster (``run`` is the sweep's batch runner): rows,
    overrides and the table's extras — ``generation`` per row, and for the page the hypervolume
    after each generation, the reference point, and with ``against_grid`` the grid's front and
    hypervolume for the same budget."""
    from .executors import connect, run_chunks

    size, gens = budget(population, generations, evaluations)

    def body(connected):
        def batch(points):
            return run_chunks(data, name, stage, points, workers=workers, client=connected,
                              scheduler_timeout=scheduler_timeout)  # fmt: skip

        found = optimise(data, name, stage, varies, conditions, minimise, maximise, method=method,
                         population=size, generations=gens, seed=seed, run=batch, progress=progress)  # fmt: skip
        grid = None
        if against_grid:
            points = list(enumerate(grid_overrides(data, varies, len(found[0]))))
            grid = run_chunks(data, name, stage, points, workers=workers, client=connected,
                              scheduler_timeout=scheduler_timeout)  # fmt: skip
        return found, grid

    if isinstance(client, str):
        with connect(client, scheduler_timeout) as connected:
            (rows, overrides, born), grid = body(connected)
    else:
        (rows, overrides, born), grid = body(client)
    F, G = _targets(rows, conditions, minimise, maximise)
    born_array = np.array(born)
    fronts = [_front_points(F[born_array <= g], G[born_array <= g]) for g in range(max(born, default=-1) + 1)]
    extra: dict[str, Any] = dict(generation=born, population=size, generations=gens, seed=seed)
    grid_front = None
    if grid is not None:
        grid_front = _front_points(*_targets(grid, conditions, minimise, maximise))
        extra.update(grid_evaluations=len(grid), grid_front=grid_front.tolist())
    if fronts and (len(fronts[-1]) or (grid_front is not None and len(grid_front))):
        reference = reference_point(fronts[-1], *([grid_front] if grid_front is not None else []))
        extra.update(
            reference_point=reference.tolist(),
            hypervolumes=[hypervolume(f, reference) for f in fronts],
            front_sizes=[len(f) for f in fronts],
        )
        if grid_front is not None:
            extra["grid_hypervolume"] = hypervolume(grid_front, reference)
    return rows, overrides, {"generation": born, **{k: v for k, v in extra.items() if k != "generation"}}
