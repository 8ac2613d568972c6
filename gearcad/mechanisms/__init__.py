"""Mechanism designs: one module per mechanism, each a pure ``design(params) -> Design``.

No files are written here; every check a build makes is made here, so ``gearcad check`` and
``gearcad build`` refuse and accept the same profiles.
"""

from __future__ import annotations

import time
from dataclasses import replace
from importlib import import_module

from ..profiles import ProfileParams
from . import fit, layouts
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
    mechanism = import_module(f".{_MODULES[params.mechanism]}", __name__)
    given, params = params, fit.made(params)  # the process's kerf and the backlash it needs
    result = mechanism.design(params)
    bands = fit.pair_bands(result)
    extra = 0.0
    for _ in range(2):  # the closed form falls short on a noncircular pair: add what the band lacks
        if not bands or bands[0].fits or not fit.chose_backlash(given):
            break
        extra += 1.25 * bands[0].needed_backlash
        retry = fit.made(given, extra)
        if not fit.backlash_takes(retry):  # the tips reach the roots: no backlash frees them
            break
        params, result = retry, mechanism.design(retry)
        bands = fit.pair_bands(result)
    result = fit.with_bands(result, bands)
    out = params.output
    parts = fit.assembly_marks(result, cut_paths(result.part_list, out))
    formats = set(out.formats)
    sheet = layouts.sheet_layout(parts, result.placements, out) if formats & {"dxf", "svg"} else ()
    plate = layouts.plate_layout(parts, result.placements, out) if "3mf" in formats else ()
    return replace(result, part_list=parts, sheet=sheet, plate=plate, seconds=time.perf_counter() - start)
