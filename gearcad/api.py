"""gearcad's Python API: the same stages the command line runs.

>>> import gearcad
>>> params = gearcad.load_profile("profiles/spur_pair.toml", overrides={"teeth.module": 2.0})
>>> d = gearcad.check(params)
>>> d.report()["pair"]["teeth"]["mesh"]["meshes"]
True
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from . import profiles as _profiles
from .batch import BuildResult
from .batch import build as _build
from .mechanisms import Design
from .mechanisms import design as _design
from .profiles import ProfileParams

__all__ = ["load_profile", "parse_profile", "design", "check", "build"]


def load_profile(path: str | Path, overrides: Mapping[str, Any] | Sequence[str] = ()) -> ProfileParams:
    """Read and validate a TOML profile; ``overrides`` map dotted keys to values (None unsets a
    key; one of two exclusive keys replaces the other, e.g. teeth.count for teeth.module).
    Raises :class:`~gearcad.errors.ProfileError` with one line per bad value."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"load_profile: path must be a str or pathlib.Path, got {type(path).__name__}")
    return _profiles.load_profile(path, () if overrides is None else overrides)


def parse_profile(data: Mapping[str, Any], *, name: str = "profile") -> ProfileParams:
    """Validate a profile given as a dict (the TOML's tables as nested dicts)."""
    if not isinstance(data, Mapping):
        raise TypeError(f"parse_profile: data must be a dict of the TOML's tables, got {type(data).__name__}")
    return _profiles.parse_profile(dict(data), default_name=name)


def _params(profile: ProfileParams | str | Path | Mapping[str, Any]) -> ProfileParams:
    if isinstance(profile, (str, Path)):
        return load_profile(profile)
    if isinstance(profile, Mapping):
        return parse_profile(profile)
    if not isinstance(profile, ProfileParams):
        raise TypeError(
            "a profile is a path, a dict of the TOML's tables or loaded parameters (gearcad.load_profile), "
            f"got {type(profile).__name__}"
        )
    return profile


def design(profile: ProfileParams | str | Path | Mapping[str, Any]) -> Design:
    """The checked design of a profile (params, a path or a dict): parts, findings, report.
    Raises :class:`~gearcad.errors.DesignError` for a design that cannot be made."""
    return _design(_params(profile))


def check(profile: ProfileParams | str | Path | Mapping[str, Any]) -> Design:
    """Everything ``build`` checks, without writing a file; the same as :func:`design`."""
    return design(profile)


def build(
    profiles: Sequence[ProfileParams | str | Path | Mapping[str, Any]],
    out: str | Path,
    progress: Callable[[int, int, BuildResult], None] | None = None,
) -> list[BuildResult]:
    """Build profiles into ``out/<name>/`` (all or nothing); returns each build's result."""
    if isinstance(profiles, (str, Path, Mapping, *ProfileParams.__args__)) or not isinstance(profiles, Iterable):
        kind = type(profiles).__name__
        raise TypeError(f"build: profiles must be a list of profiles, got a {kind} (for one: build([p], out))")
    if progress is not None and not callable(progress):
        raise TypeError(f"build: progress must be a function (n, total, result) or None, got {type(progress).__name__}")
    return _build([_params(p) for p in profiles], out, progress)
