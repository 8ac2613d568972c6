"""Mechanism designs: one module per mechanism, each a pure ``design(params) -> Design``.

No files are written here; every check a build makes is made here, so ``gearcad check`` and
``gearcad build`` refuse and accept the same profiles.
"""

from __future__ import annotations

import time
from dataclasses import replace

from ..profiles import CarrierTrainParams, GearPairParams, ProfileParams, RollerBodyParams, RollingWheelParams
from . import carrier_train, gear_pair, roller_body, rolling_wheel
from .base import Design
from .parts import Part, Placement, cut_paths

__all__ = ["Design", "Part", "Placement", "design"]

_DESIGNERS = {
    GearPairParams: gear_pair.design,
    RollerBodyParams: roller_body.design,
    RollingWheelParams: rolling_wheel.design,
    CarrierTrainParams: carrier_train.design,
}


def design(params: ProfileParams) -> Design:
    """The checked design of any mechanism's profile parameters."""
    start = time.perf_counter()
    result = _DESIGNERS[type(params)](params)
    parts = cut_paths(result.part_list, params.output)
    return replace(result, part_list=parts, seconds=time.perf_counter() - start)
