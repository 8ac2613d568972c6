"""Sweeps: many designs of one profile, with keys varied, at a stage, as one table.

:func:`sweep` returns a pandas DataFrame, one row per design: ``index``, the varied keys as
``set.<key>``, ``refusal`` (None for a made design), ``warnings``, every scalar of the stage's
report under its dotted key, ``feasible`` (made, and meets every constraint) and ``pareto`` (on
the front of the objectives among the feasible rows).  :func:`write_sweep` writes it as Parquet
and CSV with the front and an HTML page.  pandas, pyarrow and dask are imported only here
(``pip install gearcad[sweep]``).
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from ..errors import ProfileError
from ..stages import STAGES

__all__ = ["sweep", "write_sweep"]


def _profile_data(profile) -> tuple[dict, str, str | None]:
    """The profile as TOML data, its default name and its path (if a file)."""
    if isinstance(profile, Mapping):
        return dict(profile), str(profile.get("name", "profile")), None
    path = Path(profile)
    try:
        return tomllib.loads(path.read_text(encoding="utf-8-sig")), path.stem, str(path)
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ProfileError(f"{path}: cannot read the profile ({exc})") from None


def _varies(vary) -> tuple:
    from .space import Vary, parse_vary

    if isinstance(vary, Mapping):
        return tuple(
            Vary(k, tuple(v)) if isinstance(v, (list, tuple)) else parse_vary(f"{k}={v}") for k, v in vary.items()
        )
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
    progress: Callable[[int, int], None] | None = None,
):
    """Design every point of the sweep and return the table (a pandas DataFrame).

    >>> import gearcad
    >>> t = gearcad.sweep("profiles/elliptic_focus.toml", ["gear1.eccentricity=0.2:0.6:3"], stage="pitch",
    ...                   minimise=["pair.ratio_max"], workers=1)
    >>> [round(x, 3) for x in t["pair.ratio_max"]]
    [1.5, 2.333, 4.0]
    """
    import numpy as np
    import pandas as pd

    from .front import check_keys, feasible, pareto, parse_constraint
    from .space import SweepSpec, points

    if stage not in STAGES:
        raise ProfileError(f"stage = {stage!r}: must be one of {', '.join(STAGES)}")
    data, name, path = _profile_data(profile)
    spec = SweepSpec(vary=_varies(vary), stage=stage, samples=samples, sampling=sampling, seed=seed)
    overrides = points(spec)
    conditions = [parse_constraint(c) for c in constraints]
    if overrides:
        _check_keys_exist(data, name, overrides[0])
    rows = _run(data, name, stage, overrides, workers=workers, client=client, progress=progress)
    table = pd.DataFrame(rows)
    table = table.rename(columns={k: f"set.{k}" for k in (v.key for v in spec.vary)})
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
    table.attrs.update(
        profile=path,
        name=name,
        stage=stage,
        minimise=list(minimise),
        maximise=list(maximise),
        constraints=[str(c) for c in conditions],
        inputs=list(inputs.columns),
    )
    return table


def _run(data, name, stage, overrides, **kwargs) -> list[dict]:
    from .executors import run_chunks

    return run_chunks(data, name, stage, list(enumerate(overrides)), **kwargs)


def write_sweep(table, out: str | Path) -> dict[str, Path]:
    """``sweep.parquet``, ``sweep.csv``, ``front.csv`` and ``sweep.html`` in ``out``, each
    written whole under a random name and renamed into place (:func:`gearcad.publish.write_files`:
    never through a link planted in ``out``, no half-written file left)."""
    from ..publish import check_out, write_files
    from .page import sweep_page

    check_out(out)
    plain = table.copy()
    plain.attrs = {}
    contents = {
        "sweep.parquet": plain.to_parquet(index=False),
        "sweep.csv": plain.to_csv(index=False).encode("utf-8"),
        "front.csv": plain[plain["pareto"]].to_csv(index=False).encode("utf-8"),
        "sweep.html": sweep_page(table).encode("utf-8"),
    }
    return write_files(out, contents)
