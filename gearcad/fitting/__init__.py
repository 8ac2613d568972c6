"""Fitting: the parts as made under the profile's process, the band of every mesh (its play over
the process's tolerance stack, certified between positions) and the search for the backlash that
keeps the worst case free.  Between the mechanisms and the batch: the mechanisms supply their
designs and geometry, this package calls them, each as its registry entry's hooks say
(:mod:`gearcad.mechanisms.registry`, :mod:`.hooks`).
"""

from __future__ import annotations

import time
from dataclasses import replace

from ..errors import GearcadError
from ..mechanisms import Design
from ..mechanisms.finish import finish
from ..mechanisms.registry import MECHANISMS
from ..profiles import ProfileParams
from . import fit

__all__ = ["design"]


def design(params: ProfileParams, stage: str = "full") -> Design:
    """The checked design of any mechanism's profile parameters, by one route: the entry's fit
    hook (else the draft of the profile as made), its bands hook, then :func:`finish`.
    ``stage`` other than "full" stops early, for a mechanism whose entry has ``stages``."""
    start = time.perf_counter()
    entry = MECHANISMS[params.mechanism]
    preset = getattr(getattr(params, "process", None), "fit", None)
    if preset is not None and not entry.presets:
        have = ", ".join(m.name for m in MECHANISMS.values() if m.presets)
        raise GearcadError(
            f"process.fit = {preset!r}: a {params.mechanism} takes no printer's fit preset yet (only: {have}); "
            "give teeth.backlash instead"
        )
    if stage != "full":
        stages = entry.hook("stages")
        if stages is None:
            have = ", ".join(m.name for m in MECHANISMS.values() if m.stages is not None)
            raise GearcadError(f"stage = {stage!r}: a {params.mechanism} has no stages before 'full' (only: {have})")
        return replace(stages(fit.made(params), stage), seconds=time.perf_counter() - start)
    fitted = entry.hook("fit")
    draft = fitted(params, entry.design) if fitted is not None else entry.design(fit.made(params))
    bands = entry.hook("bands")
    draft = bands(draft) if bands is not None else draft
    return finish(_kerf_noted(draft, params), start=start)


def _kerf_noted(draft, params: ProfileParams):
    """The draft with ``kerf-ignored`` among its findings when the profile's two kerfs differ."""
    found = fit.kerf_finding(params)
    return draft if found is None else replace(draft, findings=(*draft.findings, found))
