"""The tips' room (docs/fit.md, "The tips first"): what is left of the rack's radial clearance
under a process (:func:`radial_room`), and the keys gearcad chooses, of those a profile leaves
out, so that the tips keep clear of the mate's roots (:func:`tip_choices`): the first-layer
chamfer, ``teeth.clearance``, a shorter ``teeth.addendum``."""

from __future__ import annotations

import math

import numpy as np

from .band import Band
from .made import chose_backlash, made

__all__ = [
    "LEAST_ADDENDUM",
    "TIP_KEYS",
    "chosen_values",
    "largest_chamfer",
    "radial_room",
    "tip_choices",
    "tip_target",
    "tips_reach_roots",
    "with_choices",
    "foot_chamfer",
    "height_unit",
]


TIP_KEYS = ("output.chamfer", "teeth.clearance", "teeth.addendum")
"""The keys gearcad may choose for the tips' room, in the order it tries them."""
LEAST_ADDENDUM = 0.8
"""The shortest addendum (× module) gearcad chooses: 0.2·m of tip relief, the contact ratio kept."""
LEAST_TIP_LAND = 0.2
"""The tip land (× module) a chosen ``teeth.clearance`` leaves the thinnest tooth."""
TIP_SPARE = 0.03
"""Room (× module) the tips keep beyond twice the margin when gearcad gives them room: the mate's
root fillet rises from its root circle towards the flank, and a tip's corner passes near it (a
module-1.5 train at 5·tol of room took a backlash a third larger than at 0.03·m more)."""


def tip_target(params, module: float) -> float:
    """The radial room (mm) gearcad gives the tips when it chooses their keys: twice the margin and
    a tolerance (5·tol) and :data:`TIP_SPARE` of the module (the normal one for helical teeth)."""
    return 5 * params.output.tolerance + TIP_SPARE * height_unit(params, module)


def tip_choices(given, draft) -> dict[str, float]:
    """The values gearcad chooses, of the keys the profile leaves out, so that the tips keep
    :func:`tip_target` of room in the mate's roots (:func:`radial_room`); {} when they have it.
    In turn, as far as each goes: a printer's first-layer chamfer (``output.chamfer`` = the
    elephant foot, as far as the parts take it), ``teeth.clearance`` (every flank in: gives twice
    itself; the thinnest tip land kept 0.2·m) and a shorter ``teeth.addendum`` (tip relief, down
    to 0.8).  What they cannot give is left: the band jams, and its finding says so.  ``draft``
    is ``given`` as made, designed."""
    process, teeth = given.process, getattr(given, "teeth", None)
    if process is None or process.kind == "none" or teeth is None or not hasattr(teeth, "addendum"):
        return {}
    module = draft.detail.teeth.plan.module
    lack = tip_target(given, module) - radial_room(made(given), module)
    picks: dict[str, float] = {}
    if lack <= 0:
        return picks
    lack = foot_room(given, draft, lack, picks)
    if lack > 0 and "clearance" not in teeth.model_fields_set:
        land = min(float(np.min(g.tip_thickness)) for g in draft.detail.teeth.gears)
        most = _thousandths((land - LEAST_TIP_LAND * module) / 2, math.floor)
        clearance = min(_thousandths(teeth.clearance + lack / 2, math.ceil), most)
        if clearance > teeth.clearance:
            picks["teeth.clearance"] = clearance
            lack -= 2 * (clearance - teeth.clearance)
    if lack > 0 and "addendum" not in teeth.model_fields_set:
        unit = height_unit(given, module)
        addendum = max(_thousandths(teeth.addendum - lack / unit, math.floor), LEAST_ADDENDUM)
        if addendum < teeth.addendum:
            picks["teeth.addendum"] = addendum
    return picks


def _thousandths(value: float, rounding) -> float:
    """``value`` rounded to 0.001 by ``rounding`` (math.floor, math.ceil), a nanometre's noise
    forgiven (0.1/2 is 0.05, not 0.049)."""
    nudge = 1e-6 if rounding is math.floor else -1e-6
    return rounding(value * 1000 + nudge) / 1000


def foot_chamfer(given) -> dict[str, float]:
    """``{"output.chamfer": elephant foot}`` for a printed gear pair given by its module whose
    tips would reach the mate's roots and whose profile leaves the chamfer out (what
    :func:`tip_choices` gives first, unless the teeth cannot take it); else {}."""
    process, out, teeth = given.process, given.output, getattr(given, "teeth", None)
    if process.kind != "fdm" or "chamfer" in out.model_fields_set or getattr(teeth, "module", None) is None:
        return {}
    foot = process.value("elephant_foot")
    module = teeth.module / height_unit(given, 1.0)  # the transverse module (about: no draft yet)
    if foot <= out.chamfer or radial_room(made(given), module) >= tip_target(given, module):
        return {}
    return {"output.chamfer": foot}


def foot_room(given, draft, lack: float, picks: dict[str, float]) -> float:
    """The tips' room the first-layer chamfer gives (a printer's, where the profile leaves
    ``output.chamfer`` out): the elephant foot, as far as every part's solid takes it
    (:func:`largest_chamfer`), put in ``picks``; what is still lacking of ``lack`` (mm)."""
    process, out = given.process, given.output
    foot = process.value("elephant_foot") if process.kind == "fdm" else 0.0
    if foot > out.chamfer and "chamfer" not in out.model_fields_set:
        chamfer = largest_chamfer(draft, foot)
        if chamfer > out.chamfer:
            picks["output.chamfer"] = chamfer
            lack -= 2 * (chamfer - out.chamfer)
    return lack


def largest_chamfer(draft, chamfer: float) -> float:
    """``chamfer`` (mm), or the largest every part's solid takes (under half its thickness, no cap's
    inset crossing itself: to 0.01 mm, 90 % of it, as the refusal suggests).  ``draft`` a
    mechanism's draft: its parts' outer rings and end sections (the bores are far from the teeth)."""
    from ..geometry.inset import chamfer_fits

    thickness = draft.params.output.thickness
    rings = [(p.outer, () if p.hole is None else (p.hole,)) for p in draft.parts]  # a ring's teeth: its hole
    rings += [(cap, ()) for p in draft.parts for cap in p.caps]

    def fits(c: float) -> bool:
        return 2 * c < thickness and all(chamfer_fits(outer, holes, c) for outer, holes in rings)

    if fits(chamfer):
        return chamfer
    good, bad = 0, math.ceil(chamfer * 100)
    while bad - good > 1:
        mid = (good + bad) // 2
        good, bad = (mid, bad) if fits(mid / 100) else (good, mid)
    return math.floor(0.9 * good) / 100


def with_choices(given, picks: dict[str, float]):
    """``given`` with the values ``picks`` gives its keys ("section.key")."""
    update: dict = {}
    for key, value in picks.items():
        section, name = key.split(".")
        table = update.get(section, getattr(given, section))
        update[section] = table.model_copy(update={name: value})
    return given.model_copy(update=update)


def chosen_values(given, used) -> dict:
    """What the report says of the keys gearcad may choose for a gear pair (``used``: the
    parameters as made): each key's value and whether gearcad chose it (``backlash``,
    ``backlash_chosen``, ``clearance``, …)."""
    teeth = getattr(given, "teeth", None)
    if teeth is None or not hasattr(teeth, "addendum"):
        return {}
    out = {"backlash": used.teeth.backlash, "backlash_chosen": chose_backlash(given)}
    for key in TIP_KEYS:
        section, name = key.split(".")
        table = getattr(given, section)
        value = getattr(getattr(used, section), name)
        out[name] = value
        out[f"{name}_chosen"] = name not in table.model_fields_set and value != getattr(table, name)
    return out


CLEARANCE = 0.25
"""Radial clearance of the standard rack the teeth are cut by (dedendum 1.25 less addendum 1), × module."""


def radial_room(params, module: float) -> float:
    """What is left of the radial clearance (mm) with both edges at their largest and the
    centres' error taken from it: the rack's (dedendum − addendum)·m, 0.25·m for the standard
    rack (``teeth.clearance`` moves every flank in, the tips too: it adds twice itself; ``module``
    the pitch curve's, transverse for helical teeth): below twice the band's margin, the tips
    reach the mate's roots."""
    process = params.process
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    teeth = getattr(params, "teeth", None)
    extra = 2 * getattr(teeth, "clearance", 0.0) if teeth is not None else 0.0
    gap = teeth.dedendum - teeth.addendum if hasattr(teeth, "addendum") else CLEARANCE
    return gap * height_unit(params, module) - 2 * edge - process.center_spread() + extra


def height_unit(params, module: float) -> float:
    """The length (mm) the rack's height coefficients multiply: the module, the normal one for
    helical teeth (heights are the same lengths in every section; ``module`` the transverse)."""
    return module * math.cos(getattr(getattr(params, "teeth", None), "helix_angle", 0.0))


def tips_reach_roots(params, band: Band, module: float) -> bool:
    """Whether the contact that closes the play is a tip against the mate's root (the radial
    room, :func:`radial_room`, under twice the margin): backlash cannot help, only the clearance,
    smaller edges or the centres."""
    return radial_room(params, module) < 2 * abs(band.margin)
