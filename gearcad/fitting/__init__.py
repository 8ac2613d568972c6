"""Fitting: the parts as made under the profile's process, the band of every mesh (its play over
the process's tolerance stack, certified between positions) and the search for the backlash that
keeps the worst case free.  Between the mechanisms and the batch: the mechanisms supply their
designs and geometry, this package calls them.
"""

from __future__ import annotations

import time
from dataclasses import replace
from importlib import import_module

from ..errors import GearcadError
from ..mechanisms import Design
from ..mechanisms.finish import finish
from ..mechanisms.registry import MECHANISMS
from ..profiles import ProfileParams
from . import band_trains, fit, mesh_fit

__all__ = ["design"]


def design(params: ProfileParams, stage: str = "full") -> Design:
    """The checked design of any mechanism's profile parameters; ``stage`` "pitch" or "teeth"
    stops a gear pair early (:mod:`~gearcad.mechanisms.pair_stages`), with no parts."""
    start = time.perf_counter()
    if stage != "full":
        from ..mechanisms.pair_stages import staged_design

        if params.mechanism != "gear-pair":
            raise GearcadError(
                f"stage = {stage!r}: only a gear pair has stages before 'full' (this is a {params.mechanism})"
            )
        return replace(staged_design(fit.made(params), stage), seconds=time.perf_counter() - start)
    mechanism = import_module(f"..mechanisms.{MECHANISMS[params.mechanism].module}", __name__)
    if params.mechanism in mesh_fit.KEYS:  # a train's meshes, a body's rollers: their backlash and bands
        return finish(mesh_fit.chosen(params, mechanism.design), start=start)
    draft, bands = fit.chosen(params, mechanism.design)  # the process's cutter and the backlash it needs
    cures = None
    if bands and not bands[0].fits and params.process.kind != "none" and not _TRYING:
        module = draft.detail.teeth.plan.module
        cures = _tried(lambda: fit.remedies(params, bands[0], design, module))  # each tried before it is named
    teeth = getattr(params, "teeth", None)
    fixed = teeth is not None and "backlash" in teeth.model_fields_set
    draft = band_trains.with_mesh_bands(
        fit.with_bands(draft, bands, cures, fixed)
    )  # a train's meshes, a body's rollers
    return finish(draft, start=start)


_TRYING: list = []
"""Non-empty while a remedy is being tried: its own jam names none (no remedies of remedies)."""


def _tried(work):
    _TRYING.append(True)
    try:
        return work()
    finally:
        _TRYING.pop()
