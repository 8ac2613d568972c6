"""The backlash of a carrier train's meshes (``train.backlash``) and of a toothed body's rollers
(the roller body's ``teeth.backlash``), chosen under the profile's process as a gear pair's is
(:mod:`.fit`): the smallest that keeps every mesh's worst case free by the band's margin (twice
the writing tolerance).

The first cut takes the closed form — 4·δ/cos α for the edges, 2·Δa·tan α for the centres, the
margin and a quarter of a tolerance to spare — and the bands measure it (:mod:`.band_trains`).
On circles, and nearly on a body's pitch curve, the play grows one for one with the backlash
(each tooth half of it thinner), so a cut that is short or fits by more than the resolution
(a tolerance, or 1 % of the backlash) is cut again with the difference, at most three more times.
No backlash frees a mesh whose tips reach the mate's roots: the radial clearance c·m (0.25·m, the
rack's dedendum less its addendum) must take both edges grown and the centres' error; where it
cannot, the flanks are cut with the closed form and the ``jams`` finding says what would fit.
"""

from __future__ import annotations

import math

from ..mechanisms.registry import MECHANISMS
from . import band_trains
from .band_trains import radial_room
from .fit import largest_chamfer, made, sliver, smallest_fit, with_choices

__all__ = ["chooses", "closed_form", "chosen", "with_backlash"]


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


def _chamfered(given, design_of):
    """``given`` with ``output.chamfer`` the elephant foot (as far as the parts take it) when it is
    printed, leaves the chamfer out and the tips would reach the mates' roots (:func:`.band_trains.
    radial_room` under twice the margin and a tolerance): the first layers' bulge is the one
    error a chamfer takes off, and no backlash frees the tips."""
    process, out = given.process, given.output
    foot = process.value("elephant_foot") if process.kind == "fdm" else 0.0
    if foot <= out.chamfer or "chamfer" in out.model_fields_set:
        return given
    draft = design_of(made(given))
    if radial_room(made(given), _module(given, draft)) >= 5 * out.tolerance:
        return given
    chamfer = largest_chamfer(draft, foot)
    return with_choices(given, {"output.chamfer": chamfer}) if chamfer > out.chamfer else given


def _excess(bands) -> float:
    """How far the tightest mesh's worst case is above its margin (mm; negative: short)."""
    return min(mb.band.least - mb.band.margin for mb in bands)


def chosen(given, design_of):
    """The draft of ``given`` as made (:func:`.fit.made`) with its bands in it, its backlash
    chosen when the profile leaves it to gearcad (:func:`chooses`), else as given."""
    given = _chamfered(given, design_of)
    params = made(given)
    if not chooses(given):
        return band_trains.with_mesh_bands(design_of(params))
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
        draft, bands = smallest_fit(first, cut, tol, limit=sliver(module))
    return band_trains.with_mesh_bands(draft, bands, chosen=True)
