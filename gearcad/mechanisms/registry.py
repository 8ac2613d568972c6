"""The mechanisms gearcad designs: one entry each — the profile's ``mechanism`` value, the module
whose ``design(params) -> Draft`` draws it, and the hooks the shared stages ask it for.

Nothing outside a mechanism's own modules and this table says a mechanism's name: every shared
stage (the fitting, the finishing line, the early stages) asks the entry.  A hook is a
``"module:function"`` reference (imported only when a profile of the mechanism is designed: a
gear pair need not load the roller bodies', the rack drive's or the trains' numerics, and this
table, below :mod:`gearcad.fitting` in the layers, may name the fitting's functions without
importing them) or a callable.  Left out, a hook does nothing.

A new mechanism is its params model (``gearcad.profiles.MODEL_OF[name] = Model``), its module,
and its entry here (``MECHANISMS[name] = Mechanism(...)``) — see docs/architecture.md.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module

from ..profiles import MODEL_OF

__all__ = ["Mechanism", "MECHANISMS", "resolve"]

Hook = str | Callable | None


def resolve(ref: Hook) -> Callable | None:
    """The callable a hook names (``"gearcad.fitting.hooks:gear_pair_fit"``), imported now."""
    if ref is None or callable(ref):
        return ref
    module, _, name = ref.partition(":")
    return getattr(import_module(module), name)


@dataclass(frozen=True)
class Mechanism:
    name: str
    """The profile's ``mechanism`` value."""
    module: str
    """The module whose ``design(params) -> Draft`` draws it: a name under gearcad.mechanisms, or
    a full dotted module name."""
    fit: Hook = None
    """``fit(params, design_of) -> Draft``: the draft as made under the profile's process, its
    play chosen and its meshes' bands measured.  Left out: ``design_of`` of the profile as made
    (the process's kerf), then :attr:`bands`."""
    bands: Hook = None
    """``bands(draft) -> Draft``: the draft with its meshes' bands measured (after :attr:`fit`)."""
    papers: Hook = None
    """``papers(params, data) -> dict | None``: the ``papers`` block of a profile that reproduces a
    seed (the papers' numbers beside gearcad's)."""
    stages: Hook = None
    """``stages(params_as_made, stage) -> Design``: the design stopped at an early stage ("pitch",
    "teeth"); left out, the mechanism has only "full"."""
    marks: Hook = None
    """``marks(draft, parts) -> parts``: the parts with the mechanism's assembly marks engraved."""
    coupons: bool = False
    """Whether ``gearcad coupon`` cuts a test coupon of its teeth (:mod:`gearcad.fitting.coupon`)."""
    play: str = "none"
    """Whose backlash the fitting chooses: ``"pair"`` (a gear pair's, also for exact parts: the
    play the writing tolerance needs), ``"meshes"`` (each of :attr:`meshes`, under a process
    only) or ``"none"``."""
    backlash_table: str = "teeth"
    """The profile table holding the ``backlash`` key the fitting chooses (``teeth``, ``train``)."""
    presets: bool = False
    """Whether its fit honours the printer's fit presets (``process.fit``); else a profile naming
    one is refused."""
    meshes: Hook = None
    """``meshes(draft) -> list``: the meshes the fitting measures bands of, other than a pair's:
    (name, geometry, inside, contact) each (:mod:`gearcad.fitting.band_trains`)."""

    @property
    def params(self) -> type:
        """Its profile model (``gearcad.profiles.MODEL_OF``)."""
        return MODEL_OF[self.name]

    @property
    def design(self) -> Callable:
        """Its module's ``design(params) -> Draft``."""
        name = self.module if "." in self.module else f"gearcad.mechanisms.{self.module}"
        return import_module(name).design

    def hook(self, name: str) -> Callable | None:
        """The hook ``name`` (``"fit"``, ``"bands"``, …), None when the entry leaves it out."""
        return resolve(getattr(self, name))


_FITTING = "gearcad.fitting.hooks"
_PAPERS = "gearcad.mechanisms.papers"

MECHANISMS: dict[str, Mechanism] = {
    m.name: m
    for m in (
        Mechanism(
            "gear-pair",
            "gear_pair",
            fit=f"{_FITTING}:gear_pair_fit",
            papers=f"{_PAPERS}:gear_pair_papers",
            stages="gearcad.mechanisms.pair_stages:staged_design",
            marks="gearcad.mechanisms.marks:assembly_marks",
            coupons=True,
            play="pair",
        ),
        Mechanism(
            "roller-body",
            "roller_body",
            fit=f"{_FITTING}:meshes_fit",
            papers=f"{_PAPERS}:roller_body_papers",
            play="meshes",
            meshes="gearcad.fitting.band_trains:roller_meshes",
        ),
        Mechanism("rolling-wheel", "rolling_wheel", papers=f"{_PAPERS}:rolling_wheel_papers"),
        Mechanism(
            "carrier-train",
            "carrier_train",
            fit=f"{_FITTING}:meshes_fit",
            papers=f"{_PAPERS}:carrier_train_papers",
            play="meshes",
            backlash_table="train",
            meshes="gearcad.fitting.band_trains:train_meshes",
        ),
        Mechanism("nc-internal", "nc_internal", fit=f"{_FITTING}:nc_fit", play="meshes", presets=True),
        Mechanism("nc-planetary", "nc_planetary", fit=f"{_FITTING}:nc_fit", play="meshes", presets=True),
    )
}
"""Every mechanism, the default (a profile that names none) first."""
