"""The designs a sweep visits: profile keys varied over grids, lists or samples.

``KEY=a:b:n`` is n values from a to b (whole numbers when a, b and the step are whole);
``KEY=v1,v2,…`` a list (each read as TOML); ``KEY=a:b`` a range that ``samples`` random or
Latin-hypercube draws fill.  Grids and lists multiply; the drawn points repeat for each of their
combinations.  The order of the points, and every drawn value, depends only on the inputs and
the seed — never on how many workers evaluate them.
"""

from __future__ import annotations

import itertools
import math
import re
import tomllib
import types
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Union, get_args, get_origin

import numpy as np

from ..errors import ProfileError
from ..profiles.messages import show
from ..profiles.reading import MODEL_OF, MODELS, MOST_BYTES, toml_value

__all__ = [
    "Vary",
    "SweepSpec",
    "parse_vary",
    "points",
    "read_sweep_file",
    "read_toml",
    "check_values",
    "check_key",
    "SAMPLINGS",
    "MAX_POINTS",
]

SAMPLINGS = ("random", "lhs")
MAX_POINTS = 1_000_000
"""A sweep's designs at most: the table of a million rows is ~1 GB in memory."""


@dataclass(frozen=True)
class Vary:
    """One varied key: fixed ``values`` (grid or list), or a ``span`` (lo, hi) to sample."""

    key: str
    values: tuple[Any, ...] = ()
    span: tuple[float, float] | None = None


@dataclass(frozen=True)
class SweepSpec:
    """What a sweep file (or the command line) asks for."""

    profile: str | None = None
    vary: tuple[Vary, ...] = ()
    stage: str = "teeth"
    samples: int = 0
    sampling: str = "lhs"
    seed: int = 0
    constraints: tuple[str, ...] = ()
    minimise: tuple[str, ...] = ()
    maximise: tuple[str, ...] = ()


def _number(text: str, item: str) -> float | int:
    value = toml_value(text.strip(), f"--vary {item!r}")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ProfileError(f"--vary {item!r}: {text.strip()!r} must be a number")
    return value


def parse_vary(item: str) -> Vary:
    """A ``--vary`` argument: ``KEY=a:b:n``, ``KEY=a:b`` or ``KEY=v1,v2,…``."""
    key, sep, rest = item.partition("=")
    key = key.strip()
    if not sep or not key or not rest.strip():
        raise ProfileError(f"--vary {item!r}: must be KEY=a:b:n, KEY=a:b (sampled) or KEY=v1,v2,…")
    if ":" in rest:
        parts = rest.split(":")
        if len(parts) not in (2, 3):
            raise ProfileError(f"--vary {item!r}: a range is a:b:n (n values) or a:b (sampled)")
        lo, hi = (_number(p, item) for p in parts[:2])
        if len(parts) == 2:
            if not lo < hi:
                raise ProfileError(f"--vary {item!r}: a sampled range needs a < b")
            return Vary(key, span=(float(lo), float(hi)))
        n = _number(parts[2], item)
        if not isinstance(n, int) or not 1 <= n <= MAX_POINTS:
            raise ProfileError(f"--vary {item!r}: n = {parts[2].strip()} must be a whole number from 1 to {MAX_POINTS}")
        grid = np.linspace(lo, hi, n)
        whole = all(isinstance(v, int) for v in (lo, hi)) and np.all(grid == np.round(grid))
        return Vary(key, tuple(int(v) for v in grid) if whole else tuple(float(v) for v in grid))
    values = tuple(toml_value(v.strip(), f"--vary {item!r}") for v in rest.split(","))
    return Vary(key, values)


_INT64 = 1 << 63


def _kind(value: Any) -> str | None:
    """What a varied value is: ``number``, ``boolean`` or ``text`` (None: none of these)."""
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, (int, float)):
        return "number"
    return "text" if isinstance(value, str) else None


def check_values(vary: Vary) -> None:
    """Refuse, before any design, a varied value that no table column could hold: not a finite
    number, true/false or text; a whole number past 64 bits; numbers mixed with text in one key."""
    kinds = set()
    for value in vary.values:
        kind = _kind(value)
        if kind is None:
            raise ProfileError(f"--vary {vary.key}: {show(value)} must be a number, true/false or text")
        if kind == "number" and not (math.isfinite(value) and -_INT64 <= value < _INT64):
            raise ProfileError(f"--vary {vary.key}: {show(value)} must be a finite number (within ±2⁶³)")
        kinds.add(kind)
    if len(kinds) > 1:
        shown = ", ".join(show(v) for v in vary.values[:6])
        raise ProfileError(
            f"--vary {vary.key}: {shown}: the values mix {' and '.join(sorted(kinds))}; give values of one kind "
            "(an empty item between commas is text)"
        )


_PART = re.compile(r"[A-Za-z0-9_]+")


def admits(annotation: Any) -> tuple[list[type], bool]:
    """The tables (profile models) a field's type admits, and whether it admits a plain value
    (a number, text, a list); TOML has no null, so ``None`` admits neither."""
    origin = get_origin(annotation)
    if origin is Annotated:
        return admits(get_args(annotation)[0])
    if origin is Union or origin is types.UnionType:
        tables, plain = [], False
        for arg in get_args(annotation):
            t, p = admits(arg)
            tables += t
            plain |= p
        return tables, plain
    if annotation is type(None):
        return [], False
    if isinstance(annotation, type) and hasattr(annotation, "model_fields"):
        return [annotation], False
    return [], True


def check_key(data: dict, key: str) -> None:
    """Refuse a varied key that names no value of the profile's schema: dotted names, each a
    table's key, the last one a value (not a table, not a list's item)."""
    parts = key.split(".")
    if not all(_PART.fullmatch(p) for p in parts):
        raise ProfileError(f"--vary {show(key)}: the key must be dotted names, e.g. gear1.eccentricity")
    mechanism = data.get("mechanism", "gear-pair")
    tables: list[type] = [MODEL_OF[mechanism]] if isinstance(mechanism, str) and mechanism in MODEL_OF else [*MODELS]
    plain = False
    for depth, part in enumerate(parts):
        where = ".".join(parts[:depth])
        fields = [m.model_fields[part] for m in tables if part in m.model_fields]
        if not fields:
            if not tables:
                raise ProfileError(f"--vary {key}: {where} is a value, not a table")
            known = sorted({f for m in tables for f in m.model_fields})
            raise ProfileError(
                f"--vary {key}: unknown key (allowed{f' in {where}' if where else ''}: {', '.join(known)})"
            )
        tables, plain = [], False
        for f in fields:
            t, p = admits(f.annotation)
            tables += t
            plain |= p
    if not plain:
        known = sorted({f for m in tables for f in m.model_fields})
        raise ProfileError(
            f"--vary {key}: a table; vary one of its keys ({', '.join(f'{key}.{k}' for k in known[:6])}, …)"
        )


def read_toml(path: str | Path, what: str) -> dict:
    """A TOML file's data, read as ``build`` reads a profile: at most MOST_BYTES (``/dev/zero``
    has no end), UTF-8 (a byte-order mark accepted); any failure one :class:`ProfileError` line."""
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MOST_BYTES + 1)
    except OSError as exc:
        raise ProfileError(f"{path}: cannot read the {what} ({exc.strerror or exc})") from None
    if len(raw) > MOST_BYTES:
        raise ProfileError(f"{path}: more than {MOST_BYTES >> 20} MiB, too large for a {what}")
    try:
        return tomllib.loads(raw.decode("utf-8-sig"))
    except UnicodeDecodeError as exc:
        raise ProfileError(f"{path}: the {what} is not UTF-8 text (byte at offset {exc.start})") from None
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"{path}: the {what} is not valid TOML ({exc})") from None
    except (ValueError, RecursionError):
        raise ProfileError(f"{path}: the {what} is not valid TOML (a huge integer, or nesting hundreds deep)") from None


def _draws(spans: list[tuple[float, float]], samples: int, sampling: str, seed: int) -> np.ndarray:
    """(samples, len(spans)) values: uniform draws, or a Latin hypercube (one draw in each of
    ``samples`` equal strata of every key, the strata paired at random)."""
    rng = np.random.default_rng(seed)
    if sampling == "random":
        u = rng.random((samples, len(spans)))
    else:
        u = (np.argsort(rng.random((samples, len(spans))), axis=0) + rng.random((samples, len(spans)))) / samples
    lo = np.array([s[0] for s in spans])
    hi = np.array([s[1] for s in spans])
    return lo + u * (hi - lo)


def points(spec: SweepSpec) -> list[dict[str, Any]]:
    """Every design's overrides {key: value}, in the sweep's order."""
    keys = [v.key for v in spec.vary]
    if len(set(keys)) != len(keys):
        twice = next(k for k in keys if keys.count(k) > 1)
        raise ProfileError(f"--vary {twice}: the key is varied twice")
    if spec.sampling not in SAMPLINGS:
        raise ProfileError(f"sampling = {spec.sampling!r}: must be one of {', '.join(SAMPLINGS)}")
    fixed = [v for v in spec.vary if v.span is None]
    spanned = [v for v in spec.vary if v.span is not None]
    if spanned and spec.samples < 1:
        raise ProfileError(f"--vary {spanned[0].key}: a range a:b is sampled; give --samples N (N ≥ 1) or a:b:n")
    count = math.prod(len(v.values) for v in fixed) * (spec.samples if spanned else 1)
    if count > MAX_POINTS:
        raise ProfileError(f"the sweep has {count} designs: at most {MAX_POINTS}")
    draws = _draws([v.span for v in spanned], spec.samples, spec.sampling, spec.seed) if spanned else [()]
    out = []
    for combo in itertools.product(*(v.values for v in fixed)):
        for row in draws:
            out.append({**dict(zip((v.key for v in fixed), combo)), **{v.key: float(x) for v, x in zip(spanned, row)}})
    return out


def _strings(data: dict, key: str) -> tuple[str, ...]:
    value = data.get(key, [])
    value = [value] if isinstance(value, str) else value
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ProfileError(f"{key} = {show(value)}: must be a list of strings")
    return tuple(value)


def read_sweep_file(path: Path) -> SweepSpec:
    """A sweep TOML: profile, stage, samples, sampling, seed, constraints, minimise, maximise and a
    ``[vary]`` table whose values are "a:b:n" / "a:b" strings or lists of values."""
    data = read_toml(path, "sweep file")
    known = {"profile", "vary", "stage", "samples", "sampling", "seed", "constraints", "minimise", "maximise"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ProfileError(f"{path}: {unknown[0]}: unknown key (allowed: {', '.join(sorted(known))})")
    vary = []
    table = data.get("vary", {})
    if not isinstance(table, dict):
        raise ProfileError(f'{path}: vary must be a table of KEY = "a:b:n" or [values]')
    for key, value in table.items():
        if isinstance(value, list):
            if not value:
                raise ProfileError(f"{path}: vary.{key} = []: give at least one value")
            vary.append(Vary(key, tuple(value)))
        elif isinstance(value, str):
            vary.append(parse_vary(f"{key}={value}"))
        else:
            raise ProfileError(f'{path}: vary.{key} = {show(value)}: must be "a:b:n", "a:b" or a list of values')
    for key in ("samples", "seed"):
        value = data.get(key, 0)
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise ProfileError(f"{path}: {key} = {show(value)}: must be a whole number ≥ 0")
    for key in ("stage", "sampling"):
        if key in data and not isinstance(data[key], str):
            raise ProfileError(f"{path}: {key} = {show(data[key])}: must be text")
    profile = data.get("profile")
    if profile is not None and (not isinstance(profile, str) or not profile.strip()):
        raise ProfileError(f'{path}: profile = {show(profile)}: must be a file\'s path, e.g. "my.toml"')
    if profile is not None:
        profile = str((Path(path).parent / profile) if not Path(profile).is_absolute() else profile)
    return SweepSpec(
        profile=profile,
        vary=tuple(vary),
        stage=data.get("stage", "teeth"),
        samples=data.get("samples", 0),
        sampling=data.get("sampling", "lhs"),
        seed=data.get("seed", 0),
        constraints=_strings(data, "constraints"),
        minimise=_strings(data, "minimise"),
        maximise=_strings(data, "maximise"),
    )
