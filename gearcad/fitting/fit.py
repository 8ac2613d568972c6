"""Parts that fit when made: the process's cutter width and backlash applied to a profile, and
the band of every mesh checked against it (see :mod:`.band`).

``made(params)`` is the profile as it will be cut: a laser's kerf (or a router's tool) offsets
the cut paths, and a gear pair whose profile leaves ``teeth.backlash`` out gets the backlash that
keeps the worst case of the process's tolerance stack free (the closed form for a spur pair:
4·δ/cos α for the edges, 2·Δa·tan α for the centres; the band then measures it, and a pair whose
band still jams is cut once more with what it lacks).  ``with_bands(design)`` adds the bands to
the report, the checks' lines and the findings (``jams`` is an error; ``loose``,
``backlash-fixed`` warn).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..findings import Finding, finding
from ..mechanisms.base import Design
from ..mechanisms.registry import MECHANISMS
from .band import Band, pair_band
from .pair_geometry import pair_geometry

__all__ = [
    "sliver",
    "smallest_fit",
    "chose_backlash",
    "chosen",
    "chosen_values",
    "largest_chamfer",
    "made",
    "needed_backlash",
    "pair_bands",
    "radial_room",
    "remedies",
    "tip_choices",
    "tips_reach_roots",
    "with_bands",
    "writing_play",
]


def _process(params):
    return getattr(params, "process", None)


def writing_play(params) -> float:
    """What the writing tolerance can take from a pair's play (mm on the pitch curve): each written
    outline strays up to ``output.tolerance`` towards its mate, on both flanks of a tooth space:
    4·tol/cos α."""
    return 4 * params.output.tolerance / math.cos(params.teeth.pressure_angle)


def needed_backlash(params) -> float:
    """The backlash the closed form asks for (mm): under a process 4·δ/cos α for the edges,
    2·Δa·tan α for the centres, and the band's margin (2·tol) with a quarter of a tolerance to
    spare, less what ``teeth.clearance`` leaves (4·c/cos α); with none, what the writing can take
    (:func:`writing_play`) and the mesh proof's
    allowed bite (its depth 2·tol, over cos α), less what ``teeth.clearance`` leaves."""
    process, teeth = _process(params), getattr(params, "teeth", None)
    if teeth is None:
        return 0.0
    alpha, tol = teeth.pressure_angle, params.output.tolerance
    if process is None or process.kind == "none":
        return max(0.0, 1.5 * writing_play(params) - 4 * teeth.clearance / math.cos(alpha))
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    need = 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 9 * tol / 4
    return max(0.0, need - 4 * teeth.clearance / math.cos(alpha))  # the clearance moved every flank in


def chose_backlash(params) -> bool:
    """Whether gearcad chooses this profile's backlash: a gear pair with teeth that leaves
    ``teeth.backlash`` out (with no process: the play the writing tolerance needs)."""
    teeth = getattr(params, "teeth", None)
    return (
        MECHANISMS[params.mechanism].play == "pair" and teeth is not None and "backlash" not in teeth.model_fields_set
    )


def sliver(module: float | None) -> float:
    """The backlash (mm) at which teeth of ``module`` keep under half their thickness (a quarter
    pitch less 80 % of it): the band asking for more means the tips reach the mate's roots, and
    no backlash frees them.  Infinite for teeth given by count (no module yet)."""
    return 0.8 * math.pi * module / 2 if module else math.inf


def made(params, backlash: float | None = None):
    """The profile as it will be cut: ``output.kerf`` the process's cutter width, and (a gear
    pair that leaves ``teeth.backlash`` out) the backlash ``backlash``, by default the closed
    form's (:func:`needed_backlash`)."""
    process = _process(params)
    update = {}
    if process is not None and process.kind != "none":
        update["output"] = params.output.model_copy(update={"kerf": process.cutter(params.output.kerf)})
        bore = getattr(params, "bore", None)
        if process.kind == "cnc" and bore is not None and "pilot" not in bore.model_fields_set:
            # a router cuts no hole narrower than its tool: the default pilot gives way to the cross
            update["bore"] = bore.model_copy(update={"pilot": 0.0})
    if chose_backlash(params):
        chosen = needed_backlash(params) if backlash is None else backlash
        update["teeth"] = params.teeth.model_copy(update={"backlash": chosen})
    return params.model_copy(update=update) if update else params


def kerf_finding(params) -> Finding | None:
    """``kerf-ignored`` when the profile sets ``output.kerf`` and the process cuts with another
    width.  The rule (docs/fit.md): a laser cuts ``process.kerf`` wide (else ``output.kerf``,
    else 0.2 mm), a router its ``process.tool_diameter``; any other profile ``output.kerf``."""
    process = _process(params)
    output = getattr(params, "output", None)
    if process is None or output is None or "kerf" not in output.model_fields_set:
        return None
    used = process.cutter(output.kerf)
    if process.kind not in ("laser", "cnc") or abs(used - output.kerf) <= 1e-9:
        return None
    if process.kind == "cnc":
        source = f"process.tool_diameter = {used:g}"
    else:
        source = f"process.kerf = {used:g}" if process.kerf is not None else f"the laser's default kerf {used:g}"
    return finding(
        "kerf-ignored",
        f"output.kerf = {output.kerf:g} is not used: the cut paths are offset by half of {source} "
        f"(process.kind = {process.kind!r} cuts with the process's width; remove output.kerf or make them agree)",
        "output",
    )


def _excess(params, band: Band) -> float:
    """How much more play the band's worst case keeps than it must (mm; negative: short): the
    band's margin under a process, with none what the writing can take."""
    exact = _process(params) is None or _process(params).kind == "none"
    return band.least - (writing_play(params) if exact else band.margin)


def chosen(given, design_of, *, designs: int = 6):
    """(draft, bands) of ``given`` as made, with what gearcad chooses for the keys the profile
    leaves out: first the room of the tips in the mate's roots (:func:`tip_choices`: the chamfer
    against a printer's elephant foot, ``teeth.clearance``, a shorter ``teeth.addendum``), then
    the smallest backlash that keeps the band's worst case free — all over at most ``designs``
    cuts of the pair.

    The first backlash is the closed form's (:func:`needed_backlash`).  While it is short
    the next adds what the band says it lacks; a pair that fits by more than the resolution
    (a tolerance, or 1 % of the backlash) is cut again with the excess taken off, and between a
    backlash that jams and one that fits the next lies where the jam's shortfall runs out.  A
    noncircular pair's play is not linear in the backlash (the tips leave the roots at once), so
    this is a bracketing search, not one step.  With no process the closed form's play is cut
    once: more backlash must not hide an interference the mesh proof reports."""
    first = _foot_chamfer(given)  # a printer's teeth drafted with the chamfer they will most likely get
    params = made(with_choices(given, first))
    draft = design_of(params)
    bands = pair_bands(draft)
    exact = _process(given) is None or _process(given).kind == "none"
    if not bands or exact:  # exact parts: the closed form, never a cure
        return draft, bands
    tips = tip_choices(given, draft)
    given = with_choices(given, tips)
    if tips != first:  # the tips reach the roots: give them room first (no backlash frees them)
        params = made(given)
        draft = design_of(params)
        bands = pair_bands(draft)
        designs -= 1
    if not chose_backlash(given):
        return draft, bands

    def cut(backlash: float):
        retry = made(given, backlash)
        d = design_of(retry)
        found = pair_bands(d)
        return retry.teeth.backlash, _excess(retry, found[0]), (d, found)

    first = (params.teeth.backlash, _excess(params, bands[0]), (draft, bands))
    if tips_reach_roots(
        params, bands[0], draft.detail.teeth.plan.module
    ):  # no backlash frees it: the closed form's flanks, and the finding
        return draft, bands
    limit = sliver(params.teeth.module)  # a jam's shortfall: a shrink of the flanks, ~0.9 of the backlash
    return smallest_fit(first, cut, given.output.tolerance, limit=limit, gain=1.1, designs=designs, slope=True)


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
    return 5 * params.output.tolerance + TIP_SPARE * _height_unit(params, module)


def tip_choices(given, draft) -> dict[str, float]:
    """The values gearcad chooses, of the keys the profile leaves out, so that the tips keep
    :func:`tip_target` of room in the mate's roots (:func:`radial_room`); {} when they have it.
    In turn, as far as each goes: a printer's first-layer chamfer (``output.chamfer`` = the
    elephant foot, as far as the parts take it), ``teeth.clearance`` (every flank in: gives twice
    itself; the thinnest tip land kept 0.2·m) and a shorter ``teeth.addendum`` (tip relief, down
    to 0.8).  What they cannot give is left: the band jams, and its finding says so.  ``draft``
    is ``given`` as made, designed."""
    process, out, teeth = given.process, given.output, getattr(given, "teeth", None)
    if process is None or process.kind == "none" or teeth is None or not hasattr(teeth, "addendum"):
        return {}
    module = draft.detail.teeth.plan.module
    lack = tip_target(given, module) - radial_room(made(given), module)
    picks: dict[str, float] = {}
    if lack <= 0:
        return picks
    foot = process.value("elephant_foot") if process.kind == "fdm" else 0.0
    if foot > out.chamfer and "chamfer" not in out.model_fields_set:
        chamfer = largest_chamfer(draft, foot)
        if chamfer > out.chamfer:
            picks["output.chamfer"] = chamfer
            lack -= 2 * (chamfer - out.chamfer)
    if lack > 0 and "clearance" not in teeth.model_fields_set:
        land = min(float(np.min(g.tip_thickness)) for g in draft.detail.teeth.gears)
        most = _thousandths((land - LEAST_TIP_LAND * module) / 2, math.floor)
        clearance = min(_thousandths(teeth.clearance + lack / 2, math.ceil), most)
        if clearance > teeth.clearance:
            picks["teeth.clearance"] = clearance
            lack -= 2 * (clearance - teeth.clearance)
    if lack > 0 and "addendum" not in teeth.model_fields_set:
        unit = _height_unit(given, module)
        addendum = max(_thousandths(teeth.addendum - lack / unit, math.floor), LEAST_ADDENDUM)
        if addendum < teeth.addendum:
            picks["teeth.addendum"] = addendum
    return picks


def _thousandths(value: float, rounding) -> float:
    """``value`` rounded to 0.001 by ``rounding`` (math.floor, math.ceil), a nanometre's noise
    forgiven (0.1/2 is 0.05, not 0.049)."""
    nudge = 1e-6 if rounding is math.floor else -1e-6
    return rounding(value * 1000 + nudge) / 1000


def _foot_chamfer(given) -> dict[str, float]:
    """``{"output.chamfer": elephant foot}`` for a printed gear pair given by its module whose
    tips would reach the mate's roots and whose profile leaves the chamfer out (what
    :func:`tip_choices` gives first, unless the teeth cannot take it); else {}."""
    process, out, teeth = given.process, given.output, getattr(given, "teeth", None)
    if process.kind != "fdm" or "chamfer" in out.model_fields_set or getattr(teeth, "module", None) is None:
        return {}
    foot = process.value("elephant_foot")
    module = teeth.module / _height_unit(given, 1.0)  # the transverse module (about: no draft yet)
    if foot <= out.chamfer or radial_room(made(given), module) >= tip_target(given, module):
        return {}
    return {"output.chamfer": foot}


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
    return gap * _height_unit(params, module) - 2 * edge - process.center_spread() + extra


def _height_unit(params, module: float) -> float:
    """The length (mm) the rack's height coefficients multiply: the module, the normal one for
    helical teeth (heights are the same lengths in every section; ``module`` the transverse)."""
    return module * math.cos(getattr(getattr(params, "teeth", None), "helix_angle", 0.0))


def tips_reach_roots(params, band: Band, module: float) -> bool:
    """Whether the contact that closes the play is a tip against the mate's root (the radial
    room, :func:`radial_room`, under twice the margin): backlash cannot help, only the clearance,
    smaller edges or the centres."""
    return radial_room(params, module) < 2 * abs(band.margin)


def remedies(given, band: Band, design, module: float) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(remedies, refused): ``--set KEY=VALUE`` lines each of which, applied alone to ``given``,
    makes the pair fit — tried here by ``design`` (a full design of the profile so changed) — and
    what was tried and did not (one line each, ``KEY = VALUE`` and why: no ``--set`` line the
    message names fails when applied).  Which keys are tried follows the contact
    that closes the play: a tip in the mate's root (:func:`tips_reach_roots`) takes the first
    layers' bulge off (``output.chamfer``, printers), moves every flank in (``teeth.clearance``)
    or shortens the tips (``teeth.addendum``); flanks take more backlash (``teeth.backlash``).
    Each is tried on the profile as given: the keys it leaves out are still chosen."""
    from ..errors import GearcadError

    process, tol = given.process, given.output.tolerance
    teeth = given.teeth
    tried: list[tuple[str, float, dict]] = []
    if tips_reach_roots(made(given), band, module):
        foot = process.value("elephant_foot")
        if foot > given.output.chamfer:
            out = given.output.model_copy(update={"chamfer": foot})
            tried.append(("output.chamfer", foot, {"output": out}))
        lack = 2 * abs(band.margin) - radial_room(made(given), module)
        clearance = math.ceil((teeth.clearance + lack / 2 + tol) * 1000) / 1000
        tried.append(("teeth.clearance", clearance, {"teeth": teeth.model_copy(update={"clearance": clearance})}))
        addendum = math.floor((teeth.addendum - (lack + tol) / _height_unit(given, module)) * 1000) / 1000
        if addendum > 0:
            tried.append(("teeth.addendum", addendum, {"teeth": teeth.model_copy(update={"addendum": addendum})}))
    else:
        backlash = math.ceil((teeth.backlash + band.needed_backlash + tol / 4) * 1000) / 1000
        tried.append(("teeth.backlash", backlash, {"teeth": teeth.model_copy(update={"backlash": backlash})}))
    good, bad = [], []
    for key, value, update in tried:
        try:
            trial = design(given.model_copy(update=update))
        except GearcadError as error:
            bad.append(f"{key} = {value:g} is refused ({error})")
            continue
        if any(f.code == "jams" for f in trial.findings):
            bad.append(f"{key} = {value:g} still jams")
        else:
            good.append(f"--set {key}={value:g}")
    return tuple(good), tuple(bad)


def smallest_fit(first, cut, tol: float, *, limit: float, gain: float = 1.0, designs: int = 4, slope: bool = False):
    """What ``cut`` made of the smallest backlash that keeps the worst case free, by a
    bracketing search over at most ``designs`` cuts (``first`` is the first, already made).

    A cut is (backlash as cut, excess, what was made): ``excess`` the worst case's play above
    its margin (negative: short).  While the cuts are short the next adds ``gain`` × what the
    shortest lacks (``slope``: over the slope of the last two where that is less than one — a
    body's rollers, whose play grows about half as fast as the backlash, and a printed
    noncircular pair's jammed plays: without it the FDM oval and centre ellipse still jammed after
    six cuts; it may overshoot a little, the laser oval 0.2313 mm where 0.2261 fits); one that fits
    by more than the resolution (a tolerance, or 1 % of the backlash) is cut again with the
    excess taken off; between a backlash that jams and one that fits the next is where the line
    between them crosses the margin, a tenth of the bracket off either end, the fit's excess
    halved for each short cut since it (the Illinois rule: a jam's play, the shrink that frees
    it, grows more slowly with the backlash than a free pair's, so the plain line falls short
    again and again).
    No cut at ``limit`` mm or more (the teeth would be slivers).  Returns the smallest cut that
    fits, else the last."""
    tries = [first]
    for _ in range(designs - 1):
        fits = [t for t in tries if t[1] >= 0]
        jams = [t for t in tries if t[1] < 0]
        best = min(fits, key=lambda t: t[0]) if fits else None
        short = max(jams, key=lambda t: t[0]) if jams else None
        if best is not None:
            resolution = max(tol, 0.01 * best[0])
            if best[1] <= resolution or (short is not None and best[0] - short[0] <= resolution):
                break
        if short is None:  # fits by too much: take the excess off (the play grows at least as fast)
            guess = best[0] - best[1]
        else:
            guess = short[0] - gain * short[1] + 0.25 * tol
            below = sorted(jams, key=lambda t: t[0])[-2:]
            if slope and best is None and len(below) == 2 and below[1][0] > below[0][0]:  # two short: their slope
                rate = (below[1][1] - below[0][1]) / (below[1][0] - below[0][0])
                if rate > 0.1:  # the play grows more slowly than the backlash (a body's rollers: ~0.5)
                    guess = max(guess, short[0] + gain * (0.25 * tol - short[1]) / rate)
            if best is not None:  # bracketed: where the line between them crosses (Illinois: the fit's
                # excess halved for each short cut since it, so the line cannot keep falling short)
                since = next((k for k, t in enumerate(reversed(tries)) if t[1] >= 0), 0)
                width, over = best[0] - short[0], best[1] * 0.5**since
                cross = short[0] + width * (0.25 * tol - short[1]) / (over - short[1])
                guess = min(max(cross, short[0] + 0.1 * width), best[0] - 0.1 * width)
        if guess >= limit:
            break
        tries.append(cut(max(guess, 0.0)))
    fits = [t for t in tries if t[1] >= 0]
    return (min(fits, key=lambda t: t[0]) if fits else tries[-1])[2]


def pair_bands(design: Design) -> tuple[Band, ...]:
    """The band of a toothed gear pair under its profile's process (none: the nominal play only)."""
    params, detail = design.params, design.detail
    geometry = pair_geometry(design)
    if geometry is None:
        return ()
    process = params.process
    names = f"{detail.pitch.gears[0].name}/{detail.pitch.gears[1].name}"
    tol = params.output.tolerance
    band = pair_band(
        geometry,
        edge=process.edge(params.output.chamfer),
        spread=process.center_spread(),
        tol=tol,
        backlash=params.teeth.backlash,
        name=names,
    )
    return (_as_driver(band, design),)


def _as_driver(band: Band, design: Design) -> Band:
    """The band with its worst place given on the driver (``pair.driver``): where that is gear 2,
    its turn φ2 and its tooth at the contact (gear 1's turn kept as ``gear1_phi``)."""
    if getattr(design.params, "driver", 1) != 2 or band.mate_phi is None:
        return band
    teeth = design.detail.teeth
    gear, frame = teeth.gears[1], teeth.frames[1]
    phi2 = float(band.mate_phi) % (2 * np.pi)
    arc = float(frame.arc(np.array([(np.pi - phi2) % (2 * np.pi)]))[0])  # the contact on gear 2
    tooth = int(np.floor((arc - gear.phase) / gear.rack.pitch)) % gear.teeth
    return replace(band, worst_phi=phi2, worst_tooth=tooth, gear1_phi=band.worst_phi)


def _jam_sentence(params, b: Band, where: str, cures, module: float) -> str:
    """The ``jams`` finding's sentence: how far short, where, which contact closes the play, and
    the remedies tried (``cures``: (fits, refused), :func:`remedies`; None: not tried)."""
    if b.unproven:
        lo, hi = (math.degrees(x) for x in b.certificate.open)
        head = (
            f"{b.mesh}: the play could not be certified within the work budget between driver angles "
            f"{lo:.2f}° and {hi:.2f}° (the bound reaches {b.least:.4f} mm, the margin is {b.margin:.4f} mm; "
            f"least measured {b.band[0]:.4f} mm at {where})"
        )
    else:
        head = (
            f"{b.mesh}: the play falls to {b.least:.4f} mm at {where} (edges {b.edge[2]:+.3f} mm, centres "
            f"−{b.center_spread:.3f} mm); it needs {b.needed_backlash:.3f} mm more"
        )
    tips = tips_reach_roots(params, b, module)
    contact = (
        "the tips reach the mate's roots (the radial clearance, 0.25 module, does not take both edges grown "
        "and the centres' error): backlash cannot free it"
        if tips
        else "flank against flank: more backlash frees it"
    )
    text = f"{head}; {contact}"
    if cures is None:
        return text
    good, bad = cures
    if good:
        text += "; it fits with " + " or ".join(good)
    else:
        text += "; no single key tried frees it (a larger teeth.module, or a tighter process)"
    if bad:
        text += " (" + "; ".join(bad) + ")"
    return text


def with_bands(
    design: Design, bands: tuple[Band, ...], cures=None, fixed: bool | None = None, chosen: dict | None = None
) -> Design:
    """The design with its bands in the report, the checks' lines and the findings (``cures``:
    the remedies tried for a jam, :func:`remedies`; ``fixed``: whether the profile gave the
    backlash, default whether the design's parameters name it; ``chosen``: the keys gearcad may
    choose, :func:`chosen_values`, into each band's entry and a check line for those it chose)."""
    if not bands:
        return design
    process = design.params.process
    findings, lines = list(design.findings), list(design.details)
    fixed = "backlash" in design.params.teeth.model_fields_set if fixed is None else fixed
    module = design.detail.teeth.plan.module
    chosen = chosen or {}
    picked = [
        f"{key} = {chosen[key.split('.')[1]]:g}{' × module' if key == 'teeth.addendum' else ' mm'}"
        for key in TIP_KEYS
        if chosen.get(f"{key.split('.')[1]}_chosen")
    ]
    if picked:
        lines.append(", ".join(picked) + " (chosen: the tips' room in the mate's roots under the process's worst case)")
    for b in bands:
        lines.append(
            f"band {b.mesh} ({process.kind}): play {b.nominal[0]:.4f}…{b.nominal[1]:.4f} mm as drawn, "
            f"{b.band[0]:.4f}…{b.band[1]:.4f} mm made; {'fits' if b.fits else 'JAMS'}"
        )
        where = f"tooth {b.worst_tooth} of the driver at driver angle {math.degrees(b.worst_phi):.1f}°"
        if not b.fits:
            findings.append(finding("jams", _jam_sentence(design.params, b, where, cures, module), b.mesh))
            if fixed and not tips_reach_roots(design.params, b, module):
                need = design.params.teeth.backlash + b.needed_backlash
                findings.append(
                    finding("backlash-fixed", f"{b.mesh}: teeth.backlash = {need:.3f} mm keeps the worst case free")
                )
        writing = writing_play(design.params)
        if process.kind == "none" and fixed and b.band[0] < writing:
            need = design.params.teeth.backlash + writing - b.band[0]
            findings.append(
                finding(
                    "backlash-fixed",
                    f"{b.mesh}: the play falls to {b.band[0]:.4f} mm at {where}, less than the writing tolerance "
                    f"can take ({writing:.4f} mm): the written outlines may touch; teeth.backlash = {need:.4f} mm "
                    "keeps them apart",
                    b.mesh,
                )
            )
        limit = process.value("max_play")
        if process.kind != "none" and limit and b.band[1] > limit:
            findings.append(
                finding("loose", f"{b.mesh}: the play may reach {b.band[1]:.3f} mm (process.max_play = {limit:g})")
            )
    data = {**design.data, "bands": [{**b.as_dict(), **chosen} for b in bands], "process": _process_block(process)}
    return replace(design, findings=tuple(findings), details=tuple(lines), data=data)


def _process_block(process) -> dict:
    keys = ("kerf_variation", "xy_compensation", "xy_variation", "elephant_foot", "tool_diameter")
    return {
        "kind": process.kind,
        **{k: process.value(k) for k in keys},
        "center_distance_tolerance": process.value("center_distance_tolerance"),
        "bore_play": process.value("bore_play"),
        "max_play": process.value("max_play"),
    }
