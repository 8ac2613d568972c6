"""gearcad: noncircular gears and the mechanisms around them, from TOML profiles to parts.

The pipeline runs one way: ``profiles`` (TOML → validated parameters) → ``mechanisms`` (a pure
``design(params)`` per mechanism: curves, teeth, parts, checks) → ``export`` (files).

The API (see README, "Python"): :func:`load_profile`, :func:`parse_profile`, :func:`design`,
:func:`check`, :func:`build`.  Imported on first use, so ``import gearcad`` stays cheap.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING

__version__ = "0.2.0"
__all__ = [
    "__version__",
    "load_profile",
    "parse_profile",
    "design",
    "design_all",
    "check",
    "build",
    "sweep",
    "coupon",
    "profile_schema",
    "Design",
    "Part",
    "Finding",
    "GearcadError",
    "ProfileError",
    "DesignError",
    "OutputError",
    "ChecksFailed",
]

_WHERE = {
    "load_profile": "api",
    "parse_profile": "api",
    "design": "api",
    "design_all": "api",
    "check": "api",
    "build": "api",
    "sweep": "api",
    "coupon": "api",
    "profile_schema": "api",
    "Design": "mechanisms",
    "Part": "mechanisms",
    "Finding": "findings",
    "GearcadError": "errors",
    "ProfileError": "errors",
    "DesignError": "errors",
    "OutputError": "errors",
    "ChecksFailed": "errors",
}

if TYPE_CHECKING:
    from .api import build, check, coupon, design, design_all, load_profile, parse_profile, profile_schema, sweep
    from .errors import ChecksFailed, DesignError, GearcadError, OutputError, ProfileError
    from .findings import Finding
    from .mechanisms import Design, Part


def __getattr__(name: str):
    if name in _WHERE:
        return getattr(import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module 'gearcad' has no attribute {name!r}")
