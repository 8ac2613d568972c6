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
    "process_block",
    "sliver",
    "smallest_fit",
    "chose_backlash",
    "chosen",
    "made",
    "needed_backlash",
    "pair_bands",
    "radial_room",
    "remedies",
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
    spare; with none, what the writing can take (:func:`writing_play`) and the mesh proof's
    allowed bite (its depth 2·tol, over cos α), less what ``teeth.clearance`` leaves."""
    process, teeth = _process(params), getattr(params, "teeth", None)
    if teeth is None:
        return 0.0
    alpha, tol = teeth.pressure_angle, params.output.tolerance
    if process is None or process.kind == "none":
        return max(0.0, 1.5 * writing_play(params) - 4 * teeth.clearance / math.cos(alpha))
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    return 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 9 * tol / 4


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
    """(draft, bands) of ``given`` as made, with the backlash gearcad chooses: the smallest that
    keeps the band's worst case free, found over at most ``designs`` cuts of the pair.

    The first cut takes the closed form's backlash (:func:`needed_backlash`).  While it is short
    the next adds what the band says it lacks; a pair that fits by more than the resolution
    (a tolerance, or 1 % of the backlash) is cut again with the excess taken off, and between a
    backlash that jams and one that fits the next lies where the jam's shortfall runs out.  A
    noncircular pair's play is not linear in the backlash (the tips leave the roots at once), so
    this is a bracketing search, not one step.  With no process the closed form's play is cut
    once: more backlash must not hide an interference the mesh proof reports."""
    params = made(given)
    draft = design_of(params)
    bands = pair_bands(draft)
    exact = _process(given) is None or _process(given).kind == "none"
    if not bands or not chose_backlash(given) or exact:  # exact parts: the closed form, never a cure
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
    return smallest_fit(first, cut, given.output.tolerance, limit=limit, gain=1.1, designs=designs)


CLEARANCE = 0.25
"""Radial clearance of the standard rack the teeth are cut by (dedendum 1.25 less addendum 1), × module."""


def radial_room(params, module: float) -> float:
    """What is left of the radial clearance (mm) with both edges at their largest and the
    centres' error taken from it (``teeth.clearance`` moves every flank in, the tips too: it adds
    twice itself): below the band's margin, the tips reach the mate's roots."""
    process = params.process
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    teeth = getattr(params, "teeth", None)
    extra = 2 * getattr(teeth, "clearance", 0.0) if teeth is not None else 0.0
    return CLEARANCE * module - 2 * edge - process.center_spread() + extra


def tips_reach_roots(params, band: Band, module: float) -> bool:
    """Whether the contact that closes the play is a tip against the mate's root (the radial
    room, :func:`radial_room`, under twice the margin): backlash cannot help, only the clearance,
    smaller edges or the centres."""
    return radial_room(params, module) < 2 * abs(band.margin)


def remedies(given, band: Band, design, module: float) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(remedies, refused): ``--set KEY=VALUE`` lines each of which, applied alone to ``given``,
    makes the pair fit — tried here by ``design`` (a full design of the profile so changed) — and
    what was tried and did not (one line each, why).  Which keys are tried follows the contact
    that closes the play: a tip in the mate's root (:func:`tips_reach_roots`) takes the first
    layers' bulge off (``output.chamfer``, printers) or moves every flank in (``teeth.clearance``);
    flanks take more backlash (``teeth.backlash``)."""
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
    else:
        backlash = math.ceil((teeth.backlash + band.needed_backlash + tol / 4) * 1000) / 1000
        tried.append(("teeth.backlash", backlash, {"teeth": teeth.model_copy(update={"backlash": backlash})}))
    good, bad = [], []
    for key, value, update in tried:
        line = f"--set {key}={value:g}"
        try:
            trial = design(given.model_copy(update=update))
        except GearcadError as error:
            bad.append(f"{line} is refused ({error})")
            continue
        if any(f.code == "jams" for f in trial.findings):
            bad.append(f"{line} still jams")
        else:
            good.append(line)
    return tuple(good), tuple(bad)


def smallest_fit(first, cut, tol: float, *, limit: float, gain: float = 1.0, designs: int = 4):
    """What ``cut`` made of the smallest backlash that keeps the worst case free, by a
    bracketing search over at most ``designs`` cuts (``first`` is the first, already made).

    A cut is (backlash as cut, excess, what was made): ``excess`` the worst case's play above
    its margin (negative: short).  While the cuts are short the next adds ``gain`` × what the
    shortest lacks; one that fits by more than the resolution (a tolerance, or 1 % of the
    backlash) is cut again with the excess taken off; between a backlash that jams and one that
    fits the next halves the bracket (a noncircular pair's play jumps as the tips leave the roots:
    the secant crept).
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
            if best is not None:  # bracketed: halve it (the play jumps as the tips leave the roots)
                guess = 0.5 * (short[0] + best[0])
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
        certificate=params.output.certificate,
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
            f"{b.mesh}: the play could not be {'proven' if b.certificate.kind == 'theorem' else 'certified'} within "
            f"the work budget between driver angles "
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


def with_bands(design: Design, bands: tuple[Band, ...], cures=None, fixed: bool | None = None) -> Design:
    """The design with its bands in the report, the checks' lines and the findings (``cures``:
    the remedies tried for a jam, :func:`remedies`; ``fixed``: whether the profile gave the
    backlash, default whether the design's parameters name it)."""
    if not bands:
        return design
    process = design.params.process
    findings, lines = list(design.findings), list(design.details)
    fixed = "backlash" in design.params.teeth.model_fields_set if fixed is None else fixed
    module = design.detail.teeth.plan.module
    for b in bands:
        lines.append(
            f"band {b.mesh} ({process.kind}): play {b.nominal[0]:.4f}…{b.nominal[1]:.4f} mm as drawn, "
            f"{b.band[0]:.4f}…{b.band[1]:.4f} mm made; {'fits' if b.fits else 'JAMS'}{_least_said(b)}"
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
    data = {**design.data, "bands": [b.as_dict() for b in bands], "process": process_block(process)}
    return replace(design, findings=tuple(findings), details=tuple(lines), data=data)


def _least_said(b: Band) -> str:
    """The least play the verdict rests on and how it is known: "estimated" (the slope
    estimate, ``output.certificate = "estimate"``) or "proven" (the theorem); "" without one."""
    cert = b.certificate
    if cert is None or (cert.kind == "theorem" and not cert.proven):
        return ""
    return f" (least {b.least:.4f} mm, {'proven' if cert.kind == 'theorem' else 'estimated'})"


def process_block(process) -> dict:
    keys = ("kerf_variation", "xy_compensation", "xy_variation", "elephant_foot", "tool_diameter")
    return {
        "kind": process.kind,
        **{k: process.value(k) for k in keys},
        "center_distance_tolerance": process.value("center_distance_tolerance"),
        "bore_play": process.value("bore_play"),
        "max_play": process.value("max_play"),
    }
