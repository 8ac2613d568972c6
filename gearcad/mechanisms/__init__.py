"""Mechanism designs: one module per mechanism, each a pure ``design(params) -> Design``.

No files are written here; every check a build makes is made here, so ``gearcad check`` and
``gearcad build`` refuse and accept the same profiles.
"""

from __future__ import annotations

import time
from dataclasses import replace
from importlib import import_module

from ..profiles import ProfileParams
from . import layouts
from .base import Design
from .parts import Part, Placement, cut_paths

__all__ = ["Design", "Part", "Placement", "design"]

_MODULES = {
    "gear-pair": "gear_pair",
    "roller-body": "roller_body",
    "rolling-wheel": "rolling_wheel",
    "carrier-train": "carrier_train",
}
"""Each mechanism's module, imported when a profile of it is designed (a gear pair need not
load the roller bodies', the rack drive's or the trains' numerics)."""


def design(params: ProfileParams) -> Design:
    """The checked design of any mechanism's profile parameters."""
    start = time.perf_counter()
    result = import_module(f".{_MODULES[params.mechanism]}", __name__).design(params)
    out = params.output
    parts = cut_paths(result.part_list, out)
    formats = set(out.formats)
    sheet = layouts.sheet_layout(parts, result.placements, out) if formats & {"dxf", "svg"} else ()
    plate = layouts.plate_layout(parts, result.placements, out, result.sections) if "3mf" in formats else ()
    return replace(result, part_list=parts, sheet=sheet, plate=plate, seconds=time.perf_counter() - start)
