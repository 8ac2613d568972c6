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
from .band import Band, pair_band
from .made import chose_backlash, made, needed_backlash, process_of, sliver, writing_play
from .pair_geometry import pair_geometry
from .tips import (
    TIP_KEYS,
    chosen_values,
    foot_chamfer,
    height_unit,
    largest_chamfer,
    radial_room,
    tip_choices,
    tips_reach_roots,
    with_choices,
)

__all__ = [
    "process_block",
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


def kerf_finding(params) -> Finding | None:
    """``kerf-ignored`` when the profile sets ``output.kerf`` and the process cuts with another
    width.  The rule (docs/fit.md): a laser cuts ``process.kerf`` wide (else ``output.kerf``,
    else 0.2 mm), a router its ``process.tool_diameter``; any other profile ``output.kerf``."""
    process = process_of(params)
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
    exact = process_of(params) is None or process_of(params).kind == "none"
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
    first = foot_chamfer(given)  # a printer's teeth drafted with the chamfer they will most likely get
    params = made(with_choices(given, first))
    draft = design_of(params)
    bands = pair_bands(draft)
    exact = process_of(given) is None or process_of(given).kind == "none"
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
        addendum = math.floor((teeth.addendum - (lack + tol) / height_unit(given, module)) * 1000) / 1000
        if addendum > 0:
            tried.append(("teeth.addendum", addendum, {"teeth": teeth.model_copy(update={"addendum": addendum})}))
    else:
        backlash = math.ceil((teeth.backlash + band.needed_backlash + tol / 4) * 1000) / 1000
        tried.append(("teeth.backlash", backlash, {"teeth": teeth.model_copy(update={"backlash": backlash})}))
    good, bad = [], []
    for key, value, update in tried:
        for _ in range(3 if key == "teeth.backlash" else 1):
            try:
                trial = design(given.model_copy(update=update))
            except GearcadError as error:
                bad.append(f"{key} = {value:g} is refused ({error})")
                break
            if not any(f.code == "jams" for f in trial.findings):
                good.append(f"--set {key}={value:g}")
                break
            bad.append(f"{key} = {value:g} still jams")
            lacks = trial.data.get("bands") or [{}]
            if key != "teeth.backlash" or "needed_backlash" not in lacks[0]:
                break
            # more backlash: what the trial still lacks (a jam's play grows more slowly than it)
            value = math.ceil((value + 1.1 * lacks[0]["needed_backlash"] + tol / 4) * 1000) / 1000
            update = {"teeth": teeth.model_copy(update={"backlash": value})}
        else:
            continue
        if good and good[-1].startswith(f"--set {key}="):
            bad = [b for b in bad if not b.startswith(f"{key} = ")]
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
    again and again).  The search ends when a fit and a jam lie within two resolutions of each
    other: the play may jump there (the laser focus pair: −0.3 µm at 0.3035 mm, +52 µm at
    0.3071 mm, a tip passing a neck), and halving the bracket further only spends cuts.
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
            if best[1] <= resolution or (short is not None and best[0] - short[0] <= 2 * resolution):
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
    geometry = pair_geometry(design, written=True)  # what the files hold, as the cutter leaves it
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
        pin=True,
    )
    return (_as_driver(band, design, pin=True),)


def _as_driver(band: Band, design: Design, *, pin: bool = False) -> Band:
    """The band with its worst place given on the driver (``pair.driver``): where that is gear 2,
    its turn φ2 and its tooth at the contact (gear 1's turn kept as ``gear1_phi``).  ``pin``: its
    :meth:`~.band.Band.pinned` given so too."""
    if pin and band.pin is not None:
        raw = band
        band = replace(band, pin=lambda: _as_driver(raw.pinned(), design))
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
            f"−{b.center_spread:.3f} mm); it needs at least {b.needed_backlash:.3f} mm more"
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
            f"{b.band[0]:.4f}…{b.band[1]:.4f} mm made; {'fits' if b.fits else 'JAMS'}{least_said(b)}"
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
    data = {**design.data, "bands": [{**b.as_dict(), **chosen} for b in bands], "process": process_block(process)}
    return replace(design, findings=tuple(findings), details=tuple(lines), data=data)


def least_said(b: Band) -> str:
    """The least play the verdict rests on and how it is known: "proven" (the theorem),
    "estimated" (the slope estimate, ``output.certificate = "estimate"``) or "sampled" (measured
    at fixed positions only, no bound between them); "" where the budget left it open."""
    cert = b.certificate
    if cert is not None and cert.kind == "theorem" and not cert.proven:
        return ""
    how = "sampled" if cert is None else "proven" if cert.kind == "theorem" else "estimated"
    return f" (least {b.least:.4f} mm, {how})"


def process_block(process) -> dict:
    keys = ("kerf_variation", "xy_compensation", "xy_variation", "elephant_foot", "tool_diameter")
    return {
        "kind": process.kind,
        **{k: process.value(k) for k in keys},
        "center_distance_tolerance": process.value("center_distance_tolerance"),
        "bore_play": process.value("bore_play"),
        "max_play": process.value("max_play"),
    }
