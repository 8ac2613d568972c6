"""The mechanisms gearcad designs: one line each, the profile's ``mechanism`` value, the module
under :mod:`gearcad.mechanisms` whose ``design(params) -> Draft`` draws it, and its params model.

A new mechanism is its params model (a module of ``gearcad.profiles`` and its entry in
``MODELS``), its module here, and its line below.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..profiles import MODEL_OF

__all__ = ["Mechanism", "MECHANISMS"]


@dataclass(frozen=True)
class Mechanism:
    name: str
    """The profile's ``mechanism`` value."""
    module: str
    """Its module under gearcad.mechanisms, imported only when a profile of it is designed (a
    gear pair need not load the roller bodies', the rack drive's or the trains' numerics)."""

    @property
    def params(self) -> type:
        """Its profile model (``gearcad.profiles.MODELS``)."""
        return MODEL_OF[self.name]


MECHANISMS: dict[str, Mechanism] = {
    m.name: m
    for m in (
        Mechanism("gear-pair", "gear_pair"),
        Mechanism("roller-body", "roller_body"),
        Mechanism("rolling-wheel", "rolling_wheel"),
        Mechanism("carrier-train", "carrier_train"),
        Mechanism("nc-internal", "nc_internal"),
        Mechanism("nc-planetary", "nc_planetary"),
    )
}
