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

from . import batch as _batch
from . import profiles as _profiles
from .batch import BuildResult
from .errors import OutputError, ProfileError
from .fitting import design as _design
from .mechanisms import Design
from .profiles import ProfileParams
from .publish import check_out
from .stages import STAGES

__all__ = [
    "load_profile",
    "parse_profile",
    "profile_schema",
    "design",
    "design_all",
    "check",
    "build",
    "check_out",
    "sweep",
    "coupon",
]


def load_profile(
    path: str | Path, overrides: Mapping[str, Any] | Sequence[str] = (), *, unset: Sequence[str] = ()
) -> ProfileParams:
    """Read and validate a TOML profile; ``overrides`` map dotted keys to values (None unsets a
    key; one of two exclusive keys replaces the other, e.g. teeth.count for teeth.module), or are
    ``KEY=VALUE`` strings with TOML values; ``unset`` names keys to remove.
    Raises :class:`~gearcad.errors.ProfileError` with one line per bad value."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"load_profile: path must be a str or pathlib.Path, got {type(path).__name__}")
    return _profiles.load_profile(path, () if overrides is None else overrides, unset=unset)


def profile_schema() -> dict:
    """The JSON Schema of profiles (for TOML editors)."""
    return _profiles.profile_schema()


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
    if not isinstance(profile, tuple(_profiles.MODEL_OF.values())):
        raise TypeError(
            "a profile is a path, a dict of the TOML's tables or loaded parameters (gearcad.load_profile), "
            f"got {type(profile).__name__}"
        )
    return profile


def design(profile: ProfileParams | str | Path | Mapping[str, Any], stage: str = "full") -> Design:
    """The checked design of a profile (params, a path or a dict): parts, findings, report.
    ``stage``: "pitch" (the pitch curves and their checks only), "teeth" (and the teeth judged by
    closed form) or "full" (parts, mesh proof, everything a build writes); gear pairs only stop early.
    Raises :class:`~gearcad.errors.DesignError` for a design that cannot be made."""
    if stage not in STAGES:
        raise ProfileError(f"stage = {stage!r}: must be one of {', '.join(STAGES)}")
    return _design(_params(profile), stage)


def design_all(profiles: Sequence[ProfileParams | str | Path | Mapping[str, Any]], stage: str = "full") -> list[Design]:
    """:func:`design` of several profiles, an error naming the profile it came from; two profiles
    of one name are refused (they would build into one folder)."""
    if stage not in STAGES:
        raise ProfileError(f"stage = {stage!r}: must be one of {', '.join(STAGES)}")
    return _batch.design_all([_params(p) for p in profiles], stage)


def check(
    profile: ProfileParams | str | Path | Mapping[str, Any],
    stage: str = "full",
    *,
    strict: bool = False,
    allow: Sequence[str] = (),
) -> Design:
    """Everything ``build`` checks (or a stage's part of it), without writing a file: :func:`design`,
    and with ``strict`` :class:`~gearcad.errors.ChecksFailed` when a finding fails
    (``Design.failures``) whose code is not in ``allow`` — what ``gearcad check`` exits 3 for."""
    d = design(profile, stage)
    return d.raise_failures(allow) if strict else d


def build(
    profiles: Sequence[ProfileParams | str | Path | Mapping[str, Any]],
    out: str | Path,
    progress: Callable[[int, int, BuildResult], None] | None = None,
) -> list[BuildResult]:
    """Build profiles into ``out/<name>/`` (all or nothing); returns each build's result.
    Raises :class:`~gearcad.errors.OutputError` when a file cannot be written or published;
    :func:`check_out` finds a bad ``out`` before any work."""
    if isinstance(profiles, (str, Path, Mapping, *_profiles.MODEL_OF.values())) or not isinstance(profiles, Iterable):
        kind = type(profiles).__name__
        raise TypeError(f"build: profiles must be a list of profiles, got a {kind} (for one: build([p], out))")
    if progress is not None and not callable(progress):
        raise TypeError(f"build: progress must be a function (n, total, result) or None, got {type(progress).__name__}")
    return _batch.build([_params(p) for p in profiles], out, progress)


def sweep(profile: str | Path | Mapping[str, Any], vary: Sequence[str] | Mapping[str, Any] = (), **options):
    """Design a profile over varied keys at a stage; the table as a pandas DataFrame, one row per
    design (refused ones too). See :func:`gearcad.sweeps.sweep` for the options (stage, samples,
    sampling, seed, constraints, minimise, maximise, workers, client, progress)."""
    from .sweeps import sweep as _sweep

    return _sweep(profile, vary, **options)


def coupon(profile: ProfileParams | Design | str | Path | Mapping[str, Any], out: str | Path) -> Path:
    """Write a gear pair's calibration coupon into ``out/<name>-coupon/`` (published atomically):
    ``coupon.dxf``, ``coupon.svg``, ``coupon.3mf`` and ``coupon.txt`` naming the key to set after
    measuring (see :mod:`gearcad.fitting.coupon`); ``profile`` may be its design already.
    Returns the folder.  Raises
    :class:`~gearcad.errors.ProfileError` for a profile that is not a gear pair or names no
    process (``process.kind`` "none")."""
    from .export.coupon import write_coupon
    from .fitting.coupon import check_coupon, coupon_data
    from .interrupts import interrupt_guard
    from .publish import Publisher, check_out

    made = profile if isinstance(profile, Design) else None
    params = made.params if made is not None else _params(profile)
    check_coupon(params)
    check_out(out)
    data = coupon_data(made if made is not None else _design(params))
    output = params.output
    with interrupt_guard(out), Publisher(out) as publisher:
        folder = publisher.folder(f"{params.name}-coupon")
        try:
            write_coupon(data, folder, cut_layer=output.cut_layer, mark_layer=output.mark_layer, flavour=output.dxf)
        except OSError as exc:  # a full disk, a failing filesystem: one line, nothing published
            if isinstance(exc, BrokenPipeError):
                raise
            why = exc.strerror or exc
            raise OutputError(f"{params.name}-coupon: cannot write ({why}); nothing was published") from None
        publisher.commit()
    return publisher.path / f"{params.name}-coupon"
