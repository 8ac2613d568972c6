"""The mechanisms gearcad designs: one line each, the profile's ``mechanism`` value, the module
under :mod:`gearcad.mechanisms` whose ``design(params) -> Draft`` draws it, and its params model.

A new mechanism is its params model (``gearcad.profiles``), its module here, and its line below.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..profiles import CarrierTrainParams, GearPairParams, RollerBodyParams, RollingWheelParams

__all__ = ["Mechanism", "MECHANISMS"]


@dataclass(frozen=True)
class Mechanism:
    name: str
    """The profile's ``mechanism`` value."""
    module: str
    """Its module under gearcad.mechanisms, imported only when a profile of it is designed (a
    gear pair need not load the roller bodies', the rack drive's or the trains' numerics)."""
    params: type
    """Its profile model."""


MECHANISMS: dict[str, Mechanism] = {
    m.name: m
    for m in (
        Mechanism("gear-pair", "gear_pair", GearPairParams),
        Mechanism("roller-body", "roller_body", RollerBodyParams),
        Mechanism("rolling-wheel", "rolling_wheel", RollingWheelParams),
        Mechanism("carrier-train", "carrier_train", CarrierTrainParams),
    )
}
