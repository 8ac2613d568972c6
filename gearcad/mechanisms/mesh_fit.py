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

from . import band_trains
from .band_trains import KEYS, radial_room
from .fit import made

__all__ = ["chooses", "closed_form", "chosen", "with_backlash"]


def _table(params):
    return params.train if params.mechanism == "carrier-train" else params.teeth


def _module(params, draft=None) -> float:
    """The smallest module of the mechanism's teeth, mm (a body's from its drawn teeth)."""
    if params.mechanism == "carrier-train":
        return min(params.modules)
    return draft.data["teeth"]["module"] if draft is not None else math.inf


def chooses(params) -> bool:
    """Whether gearcad chooses this profile's backlash: a carrier train or a toothed body, a
    process named, the backlash key left out."""
    if params.mechanism not in KEYS or params.process.kind == "none" or _table(params) is None:
        return False
    return "backlash" not in _table(params).model_fields_set


def with_backlash(params, backlash: float):
    """The profile with its train's or body's teeth cut with ``backlash`` mm."""
    section = "train" if params.mechanism == "carrier-train" else "teeth"
    table = _table(params).model_copy(update={"backlash": backlash})
    return params.model_copy(update={section: table})


def closed_form(params) -> float:
    """The backlash the closed form asks for under the process (mm): 4·δ/cos α, 2·Δa·tan α and
    the band's margin 2·tol with a quarter of a tolerance to spare (as a gear pair's)."""
    process, alpha = params.process, params.pressure_angle
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    tol = params.output.tolerance
    return 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 2 * tol + tol / 4


def _excess(bands) -> float:
    """How far the tightest mesh's worst case is above its margin (mm; negative: short)."""
    return min(mb.band.band[0] - mb.band.margin for mb in bands)


def chosen(given, design_of):
    """The draft of ``given`` as made (:func:`.fit.made`) with its bands in it, its backlash
    chosen when the profile leaves it to gearcad (:func:`chooses`), else as given."""
    params = made(given)
    if not chooses(given):
        return band_trains.with_mesh_bands(design_of(params))
    tol = params.output.tolerance
    first = with_backlash(params, closed_form(params))
    draft = design_of(first)
    module = _module(params, draft)
    bands = band_trains.mesh_bands(draft)
    tries = [(first.backlash, _excess(bands), draft, bands)]
    if radial_room(params, module) >= 2 * tol:  # else no backlash frees it: the closed form's flanks
        for _ in range(3):
            fits = [t for t in tries if t[1] >= 0]
            jams = [t for t in tries if t[1] < 0]
            best = min(fits, key=lambda t: t[0]) if fits else None
            short = max(jams, key=lambda t: t[0]) if jams else None
            resolution = max(tol, 0.01 * (best or short)[0])
            if best is not None and (best[1] <= resolution or (short and best[0] - short[0] <= resolution)):
                break
            guess = (best or short)[0] - (best or short)[1] + (0.25 * tol if best is None else 0.0)
            if best is not None and short is not None:  # between the two, the jam's side by the shortfall
                width = best[0] - short[0]
                guess = min(max(short[0] - short[1] + 0.25 * tol, short[0] + 0.1 * width), best[0] - 0.1 * width)
            if guess >= 0.8 * math.pi * module / 2:  # the teeth would be thinner than a sliver
                break
            draft = design_of(with_backlash(params, max(guess, 0.0)))
            bands = band_trains.mesh_bands(draft)
            tries.append((draft.params.backlash, _excess(bands), draft, bands))
    fits = [t for t in tries if t[1] >= 0]
    backlash, _, draft, bands = min(fits, key=lambda t: t[0]) if fits else tries[-1]
    return band_trains.with_mesh_bands(draft, bands, chosen=True)
