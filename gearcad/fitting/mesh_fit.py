"""The backlash of a carrier train's meshes (``train.backlash``) and of a toothed body's rollers
(the roller body's ``teeth.backlash``), chosen under the profile's process as a gear pair's is
(:mod:`.fit`): the smallest that keeps every mesh's worst case free by the band's margin (twice
the writing tolerance).

The first cut takes the closed form — 4·δ/cos α for the edges, 2·Δa·tan α for the centres, the
margin and a quarter of a tolerance to spare — and the bands measure it (:mod:`.band_trains`).
On circles, and nearly on a body's pitch curve, the play grows one for one with the backlash
(each tooth half of it thinner), so a cut that is short or fits by more than the resolution
(a tolerance, or 1 % of the backlash) is cut again with the difference, at most five more times
(:data:`DESIGNS`).
No backlash frees a mesh whose tips reach the mate's roots: the radial clearance c·m (0.25·m, the
rack's dedendum less its addendum) must take both edges grown and the centres' error; where it
cannot, the flanks are cut with the closed form and the ``jams`` finding says what would fit.
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..mechanisms.registry import MECHANISMS
from . import band_trains
from .fit import smallest_fit
from .made import made, sliver
from .tips import LEAST_ADDENDUM, foot_room, tip_target, with_choices

__all__ = ["chooses", "closed_form", "chosen", "radial_room", "with_backlash"]


DESIGNS = 6
"""Cuts of a mesh's backlash at most: a printed body's rollers take five (their play grows ever
more slowly with the backlash: 0.56, 0.44, 0.32 mm a mm; four cuts, the last at 0.924 mm, still
jammed by 2.5 µm under the proven band)."""


def _table(params):
    return getattr(params, MECHANISMS[params.mechanism].backlash_table, None)


def _module(params, draft=None) -> float:
    """The smallest module of the mechanism's teeth, mm (a body's from its drawn teeth)."""
    if hasattr(params, "modules"):  # a train's gears, each of its own module
        return min(params.modules)
    return draft.data["teeth"]["module"] if draft is not None else math.inf


def chooses(params) -> bool:
    """Whether gearcad chooses this profile's backlash: a carrier train or a toothed body, a
    process named, the backlash key left out."""
    if MECHANISMS[params.mechanism].play != "meshes" or params.process.kind == "none" or _table(params) is None:
        return False
    return "backlash" not in _table(params).model_fields_set


def with_backlash(params, backlash: float):
    """The profile with its train's or body's teeth cut with ``backlash`` mm."""
    section = MECHANISMS[params.mechanism].backlash_table
    table = _table(params).model_copy(update={"backlash": backlash})
    return params.model_copy(update={section: table})


def closed_form(params) -> float:
    """The backlash the closed form asks for under the process (mm): 4·δ/cos α, 2·Δa·tan α and
    the band's margin 2·tol with a quarter of a tolerance to spare (as a gear pair's)."""
    process, alpha = params.process, params.pressure_angle
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    tol = params.output.tolerance
    return 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 2 * tol + tol / 4


def radial_room(params, module: float) -> float:
    """:func:`.band_trains.radial_room` with the train's own tips: the roots 1.25·m deep, the tips
    ``train.addendum``·m high (1 unless set or chosen), so (1.25 − addendum)·m of clearance."""
    addendum = getattr(_table(params), "addendum", 1.0)
    return band_trains.radial_room(params, module) + (1.0 - addendum) * module


def _tips(given, design_of):
    """``given`` with the tips' room chosen, of the keys it leaves out, when the process's worst
    case would bring the tips into the mates' roots (:func:`radial_room` under
    :func:`.fit.tip_target`): ``output.chamfer`` the elephant foot when printed (as far as the parts take
    it: the first layers' bulge is the one error a chamfer takes off), then a shorter
    ``train.addendum`` (down to :data:`.fit.LEAST_ADDENDUM`).  No backlash frees the tips."""
    process = given.process
    if process.kind == "none":
        return given
    draft = None if hasattr(given, "modules") else design_of(made(given))  # a body's module: its draft's
    module = _module(given, draft)
    lack = tip_target(given, module) - radial_room(made(given), module)
    if lack <= 0:
        return given
    draft = draft or design_of(made(given))
    picks: dict[str, float] = {}
    lack = foot_room(given, draft, lack, picks)
    table, section = _table(given), MECHANISMS[given.mechanism].backlash_table
    if lack > 0 and hasattr(table, "addendum") and "addendum" not in table.model_fields_set:
        addendum = max(math.floor((table.addendum - lack / module) * 1000 + 1e-6) / 1000, LEAST_ADDENDUM)
        if addendum < table.addendum:
            picks[f"{section}.addendum"] = addendum
    return with_choices(given, picks) if picks else given


def _excess(bands) -> float:
    """How far the tightest mesh's worst case is above its margin (mm; negative: short)."""
    return min(mb.band.least - mb.band.margin for mb in bands)


def chosen(given, design_of):
    """The draft of ``given`` as made (:func:`.fit.made`) with its bands in it, its backlash
    chosen when the profile leaves it to gearcad (:func:`chooses`), else as given."""
    original, given = given, _tips(given, design_of)
    params = made(given)
    if not chooses(given):
        return _noted(band_trains.with_mesh_bands(design_of(params)), original)
    tol = params.output.tolerance
    draft = design_of(with_backlash(params, closed_form(params)))
    module = _module(params, draft)

    def cut(backlash: float):
        d = design_of(with_backlash(params, backlash))
        found = band_trains.mesh_bands(d)
        return d.params.backlash, _excess(found), (d, found)

    bands = band_trains.mesh_bands(draft)
    first = (draft.params.backlash, _excess(bands), (draft, bands))
    if radial_room(params, module) >= 2 * tol:  # else no backlash frees it: the closed form's flanks
        draft, bands = smallest_fit(first, cut, tol, limit=sliver(module), slope=True, designs=DESIGNS)
    return _noted(band_trains.with_mesh_bands(draft, bands, chosen=True), original)


def _noted(design, given):
    """The design with each mesh band's entry saying the tips' keys as cut and whether gearcad
    chose them (``chamfer``/``chamfer_chosen``, ``addendum``/``addendum_chosen``, a train's), and
    a check line for those it chose."""
    used, section = design.params, MECHANISMS[given.mechanism].backlash_table
    keys = [("output", "chamfer")] + ([(section, "addendum")] if hasattr(_table(given), "addendum") else [])
    notes: dict = {}
    for table, key in keys:
        value = getattr(getattr(used, table), key)
        notes[key] = value
        notes[f"{key}_chosen"] = key not in getattr(given, table).model_fields_set and value != getattr(
            getattr(given, table), key
        )
    picked = [f"{t}.{k} = {notes[k]:g}" for t, k in keys if notes[f"{k}_chosen"]]
    if not picked or "bands" not in design.data:
        return design
    bands = [b | notes if "backlash" in b else b for b in design.data["bands"]]
    line = ", ".join(picked) + " (chosen: the tips' room in the mates' roots under the process's worst case)"
    return replace(design, data={**design.data, "bands": bands}, details=(*design.details, line))
