"""Sweeps: many designs of one profile, with keys varied, at a stage, as one table.

:func:`sweep` returns a pandas DataFrame, one row per design: ``index``, the varied keys as
``set.<key>``, ``refusal`` (None for a made design), ``warnings``, every scalar of the stage's
report under its dotted key, ``feasible`` (made, and meets every constraint) and ``pareto`` (on
the front of the objectives among the feasible rows).  :func:`write_sweep` writes it as Parquet
and CSV with the front and an HTML page.  pandas, pyarrow and dask are imported only here
(``pip install gearcad[sweep]``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from ..errors import ProfileError
from ..profiles.messages import show
from ..stages import STAGES

__all__ = ["sweep", "write_sweep", "violations"]


def _profile_data(profile) -> tuple[dict, str, str | None]:
    """The profile as TOML data, its default name and its path (if a file)."""
    from .space import read_toml

    if isinstance(profile, Mapping):
        return dict(profile), str(profile.get("name", "profile")), None
    if not isinstance(profile, (str, Path)) or not str(profile).strip():
        raise ProfileError(f"profile = {show(profile)}: must be a profile's path or its data (a dict)")
    path = Path(profile)
    return read_toml(path, "profile"), path.stem, str(path)


def _varies(vary) -> tuple:
    from .space import Vary, parse_vary

    if isinstance(vary, str):
        vary = [vary]
    if isinstance(vary, Mapping):
        out = []
        for k, v in vary.items():
            if isinstance(v, (list, tuple)):
                if not v:
                    raise ProfileError(f"vary {show(k)} = []: give at least one value")
                out.append(Vary(str(k), tuple(v)))
            else:
                out.append(parse_vary(f"{k}={v}"))
        return tuple(out)
    if not isinstance(vary, (list, tuple)) or not all(isinstance(v, (str, Vary)) for v in vary):
        raise ProfileError(f"vary = {show(vary)}: must be KEY=… strings (or a dict of key: values)")
    return tuple(v if isinstance(v, Vary) else parse_vary(v) for v in vary)  # Vary: from a sweep file


def _check_keys_exist(data: dict, name: str, first: dict) -> None:
    """A key that the profile does not have is a mistake in the sweep, not a refused design."""
    from ..profiles.reading import apply_overrides, parse_profile

    for key, value in first.items():
        try:
            parse_profile(apply_overrides(data, {key: value}), default_name=name)
        except ProfileError as exc:
            lines = [ln for ln in str(exc).splitlines() if "unknown key" in ln or "is not a table" in ln]
            if lines:
                raise ProfileError(f"--vary {key}: {lines[0]}") from None


def _keys(value, what: str) -> list[str]:
    """Constraints or objectives: one string, or a list of strings."""
    items = [value] if isinstance(value, str) else value
    if not isinstance(items, (list, tuple)) or not all(isinstance(k, str) and k.strip() for k in items):
        raise ProfileError(f"{what} = {show(value)}: must be a list of report keys (text)")
    return list(items)


def _whole(value, what: str, least: int, *, none: bool = False) -> None:
    if value is None and none:
        return
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise ProfileError(f"{what} = {show(value)}: must be a whole number ≥ {least}")


def _check_arguments(stage, samples, sampling, seed, workers, client, scheduler_timeout, objectives) -> None:
    """The API's arguments, each refused with one line before any work."""
    from .space import SAMPLINGS

    if stage not in STAGES:
        raise ProfileError(f"stage = {show(stage)}: must be one of {', '.join(STAGES)}")
    if sampling not in SAMPLINGS:
        raise ProfileError(f"sampling = {show(sampling)}: must be one of {', '.join(SAMPLINGS)}")
    _whole(samples, "samples", 0)
    _whole(seed, "seed", 0)
    _whole(workers, "workers", 1, none=True)
    if isinstance(scheduler_timeout, bool) or not isinstance(scheduler_timeout, (int, float)):
        raise ProfileError(f"scheduler_timeout = {show(scheduler_timeout)}: must be a number of seconds")
    if not 0 < scheduler_timeout <= 86400:
        raise ProfileError(f"scheduler_timeout = {show(scheduler_timeout)}: must be from 0 to 86400 s (excluded 0)")
    if client is not None and not isinstance(client, str) and not hasattr(client, "submit"):
        raise ProfileError(f"client = {show(client)}: must be a distributed.Client or its tcp://HOST:PORT")
    if isinstance(client, str):
        from .executors import scheduler_address

        scheduler_address(client)
    minimise, maximise = objectives
    for key in {*minimise} & {*maximise}:
        raise ProfileError(f"objective {key!r}: both minimised and maximised; give it once")
    for group in objectives:
        twice = [k for k in group if group.count(k) > 1]
        if twice:
            raise ProfileError(f"objective {twice[0]!r}: given twice")


def _check_constraint(condition) -> None:
    """A constraint's value is a number or true/false; an order (< <= > >=) needs a finite number."""
    key, op, value = condition
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    if op in ("==", "!=") and isinstance(value, bool):
        return
    if not number or not math.isfinite(value):
        allowed = "a finite number" if op not in ("==", "!=") else "a finite number or true/false"
        raise ProfileError(f"--constraint {condition}: {show(value)} must be {allowed}")


def _probe(data: dict, name: str, stage: str, first: dict) -> dict[str, Any] | None:
    """The report's scalars of the sweep's first point, designed here once, at the sweep's stage
    (at ``teeth`` for ``full``: a full design can take half a minute); None if it is refused."""
    from ..fitting import design
    from ..profiles.reading import apply_overrides, parse_profile
    from .evaluate import flatten

    try:
        params = parse_profile(apply_overrides(data, first), default_name=name)
        return flatten(design(params, "teeth" if stage == "full" else stage).report())
    except Exception:  # noqa: BLE001 - a refused first point says nothing of the keys; its row will say why
        return None


def _check_goals(report: dict, stage: str, conditions: list, objectives: list[str], inputs: list[str]) -> None:
    """Every constraint and objective names a key the stage reports, of a kind it can be judged
    by (an order or an objective needs a number, not text); one line each, before the first design.
    At ``full`` a key the teeth stage does not report is left to the table (a full design reports
    more than its probe)."""
    import difflib

    known = {"index", "refusal", "warnings", *inputs, *report}
    for what, key, needs_number in [
        *(("--constraint", c[0], c[1] not in ("==", "!=")) for c in conditions),
        *(("objective", k, True) for k in objectives),
    ]:
        if key not in known:
            if stage == "full":
                continue
            near = difflib.get_close_matches(key, sorted(known), n=3, cutoff=0.6)
            hint = f"did you mean {', '.join(near)}?" if near else "any report key of the stage, dotted"
            raise ProfileError(f"{what} {key!r}: the {stage} stage reports no such key ({hint})")
        value = report.get(key)
        if needs_number and isinstance(value, str):
            raise ProfileError(f"{what} {key!r}: the report gives text ({value!r}), not a number to order by")


def _check_bounds(conditions: list) -> None:
    """Constraints on one key that no value can meet together (``x >= 2`` and ``x <= 1``)."""
    bounds: dict[str, list] = {}
    for key, op, value in conditions:
        if isinstance(value, bool):
            continue
        lo, hi = bounds.setdefault(key, [(-math.inf, False, None), (math.inf, False, None)])
        if op in (">=", ">", "==") and (value > lo[0] or (value == lo[0] and op == ">")):
            bounds[key][0] = (value, op == ">", f"{key} {op} {value}")
        if op in ("<=", "<", "==") and (value < hi[0] or (value == hi[0] and op == "<")):
            bounds[key][1] = (value, op == "<", f"{key} {op} {value}")
    for key, (lo, hi) in bounds.items():
        if lo[0] > hi[0] or (lo[0] == hi[0] and (lo[1] or hi[1])):
            raise ProfileError(f"--constraint {lo[2]} and --constraint {hi[2]}: no value of {key} meets both")


def violations(table, conditions: list) -> dict[str, Any]:
    """How far each row is from meeting each constraint, as columns ``violation.<constraint>``:
    0 where it is met; for an order the distance to the bound (``x <= 4`` at x = 4.5: 0.5; a
    strict ``x < 4`` at x = 4: 0, though not met); for ``==``/``!=`` on numbers the distance
    |x − v| or 1; on true/false 1; empty (null) for a refused design or a missing value."""
    import pandas as pd

    out = {}
    for key, op, value in conditions:
        amounts = []
        for x in table[key]:
            if x is None or x != x or isinstance(x, str):
                amounts.append(None)
            elif isinstance(value, bool) or isinstance(x, bool):
                amounts.append(0.0 if (x == value) == (op == "==") else 1.0)
            elif op in ("<=", "<"):
                amounts.append(max(0.0, float(x) - value))
            elif op in (">=", ">"):
                amounts.append(max(0.0, value - float(x)))
            elif op == "==":
                amounts.append(abs(float(x) - value))
            else:
                amounts.append(0.0 if x != value else 1.0)
        out[f"violation.{key} {op} {show(value)}"] = pd.array(amounts, dtype="Float64")
    return out


def sweep(
    profile: str | Path | Mapping[str, Any],
    vary: Sequence[str] | Mapping[str, Any] = (),
    *,
    stage: str = "teeth",
    samples: int = 0,
    sampling: str = "lhs",
    seed: int = 0,
    constraints: Sequence[str] = (),
    minimise: Sequence[str] = (),
    maximise: Sequence[str] = (),
    workers: int | None = None,
    client: Any = None,
    scheduler_timeout: float = 60.0,
    progress: Callable[[int, int], None] | None = None,
    method: str = "grid",
    population: int | None = None,
    generations: int | None = None,
    evaluations: int | None = None,
    against_grid: bool = False,
    confirm: str | None = None,
):
    """Design every point of the sweep and return the table (a pandas DataFrame).

    ``method="nsga2"`` searches the ``KEY=a:b`` ranges with pymoo's NSGA-II instead
    (``population`` × ``generations`` designs, or ``evaluations``; ``seed``), the table gaining a
    ``generation`` column; ``against_grid`` also designs a grid of the same budget for the page's
    hypervolume comparison (:mod:`gearcad.sweeps.optimise`).  ``confirm="full"`` re-designs the
    front's rows at the full stage and keeps on the front only those that pass
    (:mod:`gearcad.sweeps.confirm`).

    Everything the sweep is given — keys, values, constraints, objectives, arguments — is
    checked before the first design (a :class:`ProfileError`, one line).  ``client`` is a
    ``distributed.Client`` or a scheduler's ``tcp://HOST:PORT`` (connected, then closed); a
    cluster with no worker for ``scheduler_timeout`` seconds ends the sweep with an error.

    >>> import gearcad
    >>> t = gearcad.sweep("profiles/elliptic_focus.toml", ["gear1.eccentricity=0.2:0.6:3"], stage="pitch",
    ...                   minimise=["pair.ratio_max"], workers=1)
    >>> [round(x, 3) for x in t["pair.ratio_max"]]
    [1.5, 2.333, 4.0]
    """
    from .space import SweepSpec

    constraints, minimise, maximise = (_keys(constraints, "constraints"), _keys(minimise, "minimise"),
                                       _keys(maximise, "maximise"))  # fmt: skip
    _check_arguments(stage, samples, sampling, seed, workers, client, scheduler_timeout, (minimise, maximise))
    conditions, (data, name, path), varies = _checked_inputs(profile, vary, constraints)
    searched = (method, population, generations, evaluations, against_grid)
    spec = SweepSpec(vary=varies, stage=stage, samples=samples, sampling=sampling, seed=seed)
    overrides = _first_points(data, name, stage, varies, conditions, (minimise, maximise), searched, confirm, spec)
    running = dict(workers=workers, client=client, scheduler_timeout=scheduler_timeout, progress=progress)
    if method != "grid":
        from .optimise import search

        rows, overrides, extra = search(data, name, stage, varies, conditions, minimise, maximise, **running,
                                        method=method, seed=seed, population=population, generations=generations,
                                        evaluations=evaluations, against_grid=against_grid)  # fmt: skip
    else:
        rows, extra = _run(data, name, stage, overrides, **running), {}
    table, inputs = _table(rows, overrides, conditions, minimise, maximise, extra)
    table.attrs.update(
        profile=path,
        name=name,
        stage=stage,
        minimise=list(minimise),
        maximise=list(maximise),
        constraints=[str(c) for c in conditions],
        inputs=list(inputs.columns),
        method=method,
        **extra,
    )
    if confirm is not None:
        from .confirm import confirm_front

        table = confirm_front(table, data, name, conditions, _run, **running)
    return table


def _checked_inputs(profile, vary, constraints):
    """The constraints parsed, the profile read and the varied keys and values checked against
    it: (conditions, (data, name, path), varies), or a one-line refusal."""
    from .front import parse_constraint
    from .space import check_key, check_values

    conditions = [parse_constraint(c) for c in constraints]
    for condition in conditions:
        _check_constraint(condition)
    data, name, path = _profile_data(profile)
    varies = _varies(vary)
    for v in varies:
        check_key(data, v.key)
        check_values(v)
    _check_bounds(conditions)
    return conditions, (data, name, path), varies


def _first_points(data, name, stage, varies, conditions, goals, searched, confirm, spec) -> list[dict]:
    """The grid's points (or a search's first), checked before the first design: the method and
    its budget, the confirmation, the keys, and the goals on a probe design."""
    from .confirm import check_confirm
    from .optimise import check_method, first_point
    from .space import points

    minimise, maximise = goals
    method, population, generations, evaluations, against_grid = searched
    check_method(method, varies, minimise, maximise, population, generations, evaluations, against_grid, spec.samples)
    check_confirm(confirm, stage)
    overrides = points(spec) if method == "grid" else [first_point(data, varies)]
    if overrides:
        _check_keys_exist(data, name, overrides[0])
        report = _probe(data, name, stage, overrides[0]) if conditions or minimise or maximise else None
        if report is not None:
            _check_goals(report, stage, conditions, [*minimise, *maximise], [f"set.{k}" for k in overrides[0]])
    return overrides


def _table(rows, overrides, conditions, minimise, maximise, extra: dict):
    """The sweep's table: each row's inputs after its index, then whether it is feasible and on
    the front and by how much it violates each constraint (a search's generation second)."""
    import numpy as np
    import pandas as pd  # once the designs are made: a sweep stopped early never needs it

    from .front import check_keys, feasible, pareto

    table = pd.DataFrame(rows)
    inputs = pd.DataFrame([{f"set.{k}": v for k, v in o.items()} for o in overrides], index=table.index)
    table = pd.concat([table[["index"]], inputs, table.drop(columns=["index"])], axis=1)
    objectives = [*minimise, *maximise]
    check_keys(table.columns, [c[0] for c in conditions], "constraint")
    check_keys(table.columns, objectives, "objective")
    ok = feasible(table, conditions)
    values = [
        pd.to_numeric(table[k], errors="coerce").to_numpy(float) * (1 if k in minimise else -1) for k in objectives
    ]
    front = pareto(np.column_stack(values), ok) if values else np.zeros(len(table), dtype=bool)
    table.insert(len(inputs.columns) + 1, "feasible", ok)
    table.insert(len(inputs.columns) + 2, "pareto", front)
    for n, (column, amounts) in enumerate(violations(table, conditions).items()):
        table.insert(len(inputs.columns) + 3 + n, column, amounts)
    if "generation" in extra:  # an optimiser's: which generation designed the row
        table.insert(1, "generation", extra.pop("generation"))
    return table, inputs


def _run(data, name, stage, overrides, *, client, scheduler_timeout, **kwargs) -> list[dict]:
    from .executors import connect, run_chunks

    if not isinstance(client, str):
        return run_chunks(data, name, stage, list(enumerate(overrides)), client=client, **kwargs)
    with connect(client, scheduler_timeout) as connected:
        return run_chunks(
            data,
            name,
            stage,
            list(enumerate(overrides)),
            client=connected,
            scheduler_timeout=scheduler_timeout,
            **kwargs,
        )


def write_sweep(table, out: str | Path) -> dict[str, Path]:
    """``sweep.parquet``, ``sweep.csv``, ``front.csv`` and ``sweep.html`` in ``out``, each
    written whole under a random name and renamed into place (:func:`gearcad.publish.write_files`:
    never through a link planted in ``out``, no half-written file left).  The four are written
    with Ctrl-C and SIGTERM held off (a moment), so that ``out`` holds one sweep's files, not two."""
    from ..interrupts import held_signals
    from ..publish import check_out, write_files
    from .page import sweep_page

    missing = [c for c in ("index", "refusal", "feasible", "pareto") if c not in getattr(table, "columns", ())]
    why = "not a table" if not hasattr(table, "to_parquet") else f"no {missing[0]!r} column" if missing else None
    if why or len(table) == 0:
        raise ProfileError(f"write_sweep: {why or 'no rows'}; give the table gearcad.sweep returns")
    check_out(out)
    plain = table.copy()
    plain.attrs = {}
    contents = {
        "sweep.parquet": plain.to_parquet(index=False),
        "sweep.csv": plain.to_csv(index=False).encode("utf-8"),
        "front.csv": plain[plain["pareto"]].to_csv(index=False).encode("utf-8"),
        "sweep.html": sweep_page(table).encode("utf-8"),
    }
    with held_signals():
        return write_files(out, contents)
