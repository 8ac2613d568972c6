"""A profile's HTML report: its ``index.html``, beside its files (the page over all profiles: ``html_index``).

Self-contained: one file with its own CSS and no script, no web fonts, no network reference; it
opens from the file system.  The parts are drawn as inline SVG from the same cut and mark paths
the DXF and SVG files hold (each part's path defined once, placed with ``<use>``).  Charts and the
animation are linked relatively (``<img src="mesh.png">``), which keeps the page small; every
file of the folder is linked from the table at the end."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Mapping
from html import escape
from pathlib import Path
from urllib.parse import quote

from ..findings import CODES
from ..mechanisms import Design, Part, Placement
from .bounds import drawing_bounds
from .drawing import assembly_drawing, part_drawing
from .html_band import section_bands
from .html_figures import Figures
from .html_files import section_charts, section_files
from .html_papers import section_papers
from .html_style import page
from .html_text import as_html as _value
from .html_text import e as _e
from .html_text import link as _link

__all__ = ["pivot_marking", "write_profile_page"]

_STANDARD = {"schema", "name", "title", "mechanism", "units", "tolerance", "parts", "assembly", "output"}
_STANDARD |= {"warnings", "files", "papers"}


def pivot_marking(design: Design, part: Part, report_part: Mapping | None = None) -> str:
    """What shows where ``part`` turns: its bore, a pilot hole, an engraved cross, or the ring's
    concentric teeth (``part.pivot``, the same as the report's ``parts[].pivot``)."""
    out = design.params.output
    marks = []
    if part.pivot == "bore":
        bore = design.params.bore
        text = f"Ø{bore.diameter:g} mm bore"
        if bore.keyway_width > 0:
            text += f" with a {bore.keyway_width:g} × {bore.keyway_depth:g} mm keyway"
        elif bore.flat > 0:
            text += f" with a D-flat {bore.flat:g} mm from the centre"
        marks.append(text)
    elif part.pivot == "pilot":
        bored = [p.name for p in design.parts() if p.pivot == "bore"]
        why = f"bore.diameter is {', '.join(bored)}'s shaft" if bored else "no bore given"
        marks.append(f"Ø{part.pivot_diameter:g} mm pilot hole ({why}: drill or ream it to this part's axle)")
    elif part.pivot == "hole":
        marks.append("its inner teeth, concentric with the pivot")
    if part.pivot_mark > 0:
        marks.append(f"engraved cross ±{part.pivot_mark:.3g} mm (layer {out.mark_layer})")
    return " and ".join(marks) if marks else "not marked: no bore and no engraved cross"


def _section_parts(design: Design, figures: Figures, report: dict, counts: Counter) -> str:
    cards = []
    entries = {p["name"]: p for p in report["parts"]}
    for part in design.parts():
        bounds = drawing_bounds(part_drawing(design, part))
        svg = figures.view([Placement(part.name)], bounds, label=f"{part.name}, about its pivot")
        entry = entries.get(part.name, {})
        marking = pivot_marking(design, part, entry)
        unmarked = "none" if marking.startswith("not marked") else ""
        times = counts.get(part.name, 0)
        placed = f" × {times}" if times > 1 else ""
        w, h = bounds[2] - bounds[0], bounds[3] - bounds[1]
        holes = len(part.outline.rings) - 1
        cards.append(
            f'<div class="card">{svg}<h3>{escape(part.name)}{placed}</h3>'
            f"<p>{w:.1f} × {h:.1f} mm, area {_e(part.outline.area)} mm², {holes} hole{'s' * (holes != 1)}</p>"
            f'<p class="pivot-note {unmarked}"><b>Pivot:</b> {escape(marking)}</p></div>'
        )
    return (
        '<h2 id="parts">Parts</h2>'
        '<p class="legend">Each part about its pivot:<i style="border-color:var(--cut)"></i>cut path'
        '<i style="border-color:var(--mark)"></i>marks (pitch curve, engraved pivot cross)'
        '<i style="border-color:var(--pivot)"></i>the pivot, between four ticks (drawn here only)</p>'
        f'<div class="cards">{"".join(cards)}</div>'
    )


def _section_assembly(design: Design, figures: Figures, report: dict, files: Mapping) -> str:
    a = report["assembly"]
    verdict = '<b class="ok">fits</b>' if a.get("fits") else '<b class="bad">does not fit</b>'
    nudged = a.get("nudged_min_overlap")
    facts = (
        f"<p>Assembled, the parts overlap by at most {_e(a['overlap'])} mm² (allowed {_e(a['allowed_overlap'])} mm²"
        + (f"; turned a little they overlap by {_e(nudged)} mm²" if nudged is not None else "")
        + f", {_e(a['positions'])} position{'s' * (a['positions'] != 1)} checked): {verdict}.</p>"
    )
    svg = figures.view(design.placements, drawing_bounds(assembly_drawing(design)), label="the assembly")
    gif = next((n for n, e in files.items() if e.get("kind") == "gif"), None)
    right = (
        f'<figure><img src="{escape(quote(gif))}" alt="the mechanism in motion">'
        f"<figcaption>{_link(gif)}: one cycle of motion</figcaption></figure>"
        if gif
        else '<p class="note">No animation was written ('
        + ("output.animation is off" if not design.params.output.animation else "none is drawn for it")
        + ").</p>"
    )
    return (
        '<h2 id="assembly">Assembly</h2>'
        f'<div class="pair"><figure class="wide">{svg}<figcaption>The parts as assembled: {design.placed}, '
        "to check the fit; cut from the sheet and print from the plate.</figcaption></figure>"
        f"<div>{right}{facts}</div></div>"
    )


def _section_findings(report: dict) -> str:
    warnings = report["warnings"]
    if not warnings:
        return '<h2 id="findings">Findings</h2><p class="ok">No findings: nothing to warn about.</p>'
    rows = "".join(
        f'<tr><td><span class="code" title="{escape(CODES.get(w["code"], ""))}">{escape(w["code"])}</span></td>'
        f"<td>{escape(w.get('where') or '')}</td><td>{escape(w['message'])}</td></tr>"
        for w in warnings
    )
    codes = sorted({w["code"] for w in warnings})
    glossary = "".join(
        f'<tr><td><span class="code">{escape(c)}</span></td><td>{escape(CODES.get(c, ""))}</td></tr>' for c in codes
    )
    return (
        f'<h2 id="findings">Findings ({len(warnings)})</h2>'
        f"<table><tr><th>code</th><th>where</th><th>message</th></tr>{rows}</table>"
        f"<h3>What the codes mean</h3><table>{glossary}</table>"
    )


def _section_numbers(design: Design, report: dict, counts: Counter) -> str:
    lines = "".join(f"<li>{escape(line)}</li>" for line in design.details)
    units = ", ".join(f"{k} in {v}" for k, v in report.get("units", {}).items())
    rows = "".join(
        f"<tr><td>{escape(p['name'])}</td><td class='num'>{counts.get(p['name'], 0)}</td>"
        f"<td class='num'>{_e(p['area'])}</td><td class='num'>{_e(p['holes'])}</td>"
        f"<td class='num'>{_e(p['vertices'])}</td><td class='num'>{_e(p['cut_vertices'])}</td>"
        f"<td class='num'>{_e(math.degrees(p['placement']['angle']))}°</td>"
        f"<td>({', '.join(_e(v) for v in p['placement']['offset'])})</td></tr>"
        for p in report["parts"]
    )
    out = _output_table(report["output"], design.params.output)
    return (
        '<h2 id="numbers">Key numbers</h2>'
        f'<p class="note">Tolerance {_e(report["tolerance"])} mm; {escape(units)}.</p>'
        f'<ul class="lines">{lines}</ul>'
        "<h3>Parts</h3><table><tr><th>part</th><th>placed</th><th>area, mm²</th><th>holes</th>"
        "<th>outline vertices</th><th>cut vertices</th><th>assembly angle</th><th>pivot in the assembly, mm</th>"
        f"</tr>{rows}</table>"
        f"<h3>Output</h3>{out}"
    )


def _output_table(written: Mapping, params) -> str:
    """What was written and how, each value with its unit."""
    bore = written.get("bore") or {}
    mm = [("thickness", written["thickness"]), ("chamfer", written["chamfer"]), ("kerf", written["kerf"])]
    names = {"diameter": "bore", "keyway_width": "keyway width", "keyway_depth": "keyway depth"}
    names |= {"flat": "D-flat, from the centre", "pilot": "pilot hole"}
    mm += [(names.get(k, k), v) for k, v in bore.items() if v]
    rows = [(name, f"{_e(v)} mm") for name, v in mm]
    rows += [("cutting sheet", f"{params.sheet[0]:g} × {params.sheet[1]:g} mm"), ("gap", f"{params.gap:g} mm")]
    rows += [("print bed", f"{params.bed[0]:g} × {params.bed[1]:g} mm")]
    rows += [("formats", ", ".join(written["formats"])), ("DXF encoding", written["dxf"])]
    rows += [("layers", f"cut {written['layers']['cut']}, marks {written['layers']['mark']}")]
    body = "".join(f"<tr><th>{escape(k)}</th><td>{escape(v)}</td></tr>" for k, v in rows)
    return f'<table class="kv">{body}</table>'


def _section_report(report: dict, files: Mapping) -> str:
    """The mechanism's own report blocks, each folded."""
    blocks = "".join(
        f"<details><summary>{escape(k)}</summary>{_value(report[k])}</details>" for k in report if k not in _STANDARD
    )
    if not blocks:
        return ""
    return (
        '<h2 id="report">The mechanism in numbers</h2><p class="note">The blocks of '
        f"{_link('report.json') if 'report.json' in files else 'the report'} about this mechanism; "
        f"open one to read it.</p>{blocks}"
    )


def _section_layouts(design: Design, figures: Figures, files: Mapping) -> str:
    """The cutting sheet and the print plate as laid out in sheet.dxf/sheet.svg and plate.3mf."""
    out = design.params.output
    layouts = []
    sheets = [n for n in files if n.startswith("sheet.")]
    if sheets:
        layouts.append(("cutting sheet", out.sheet, design.sheet, sheets))
    plates = [(stem, layout) for stem, layout in zip(design.plate_files(), design.plates) if f"{stem}.3mf" in files]
    for k, (stem, layout) in enumerate(plates, 1):
        noun = f"print plate {k} of {len(plates)} (top view)" if len(plates) > 1 else "print plate (top view)"
        layouts.append((noun, out.bed, layout, [f"{stem}.3mf"]))
    shown = []
    for noun, (w, h), layout, names in layouts:
        svg = figures.view(layout, (0.0, 0.0, w, h), label=noun, frame=(w, h))
        links = ", ".join(_link(n) for n in names)
        shown.append(
            f'<figure class="wide">{svg}<figcaption>{links}: the {noun}, {w:g} × {h:g} mm, parts at least '
            f"{out.gap:g} mm apart and from the edges.</figcaption></figure>"
        )
    if not shown:
        return ""
    return '<h2 id="layouts">Sheet and plate</h2><div class="pair">' + "".join(shown) + "</div>"


def write_profile_page(
    path: Path, design: Design, files: Mapping[str, Mapping], *, index: str | None = "../index.html"
) -> None:
    """Write a profile's ``index.html`` into the folder of its files.

    Parameters
    ----------
    path : Path
        The page to write, in the same folder as ``files`` (links are relative to it).
    design : Design
        The design the files were written from.
    files : mapping of file name to entry
        The report's files block (``write_design``'s result): every file is linked; PNG charts
        and the GIF animation are shown by relative links.
    index : str or None
        Relative link to the page over all profiles (None: no link).
    """
    path = Path(path)
    report = design.report(dict(files))
    counts = Counter(pl.part for pl in design.placements)
    figures = Figures(design)
    warnings = len(report["warnings"])
    fits = report["assembly"].get("fits")
    badges = [
        f"<span>{escape(design.mechanism)}</span>",
        f"<span>{len(design.parts())} part{'s' * (len(design.parts()) != 1)}, {len(design.placements)} placed</span>",
        f'<span class="{"bad" if warnings else "good"}">{warnings} finding{"s" * (warnings != 1)}</span>',
        f'<span class="{"good" if fits else "bad"}">assembly {"fits" if fits else "does not fit"}</span>',
    ]
    sections = [
        ("parts", "Parts", _section_parts(design, figures, report, counts)),
        ("assembly", "Assembly", _section_assembly(design, figures, report, files)),
        ("findings", "Findings", _section_findings(report)),
        ("papers", "The paper", section_papers(report)),
        ("fit", "Fit when made", section_bands(report)),
        ("numbers", "Key numbers", _section_numbers(design, report, counts)),
        ("layouts", "Sheet and plate", _section_layouts(design, figures, files)),
        ("charts", "Charts", section_charts(files)),
        ("report", "Report", _section_report(report, files)),
        ("files", "Files", section_files(files, path.name)),
    ]
    nav = "".join(f'<a href="#{key}">{label}</a>' for key, label, text in sections if text)
    up = f' · <a href="{escape(quote(index))}">all profiles</a>' if index else ""
    header = (
        f"<header><h1>{escape(report['title'] or design.name)}</h1>"
        f'<p class="sub">{escape(design.name)} · gearcad report{up}</p>'
        f'<div class="summary">{escape(design.summary)}</div><div class="badges">{"".join(badges)}</div>'
        f"<nav>{nav}</nav></header>"
    )
    footer = (
        "<footer>Written by gearcad. This page is one file and loads nothing from the network; its charts and "
        "animation are the PNG and GIF files beside it, linked relatively.</footer>"
    )
    body = "\n".join([header, figures.defs(), *(text for _, _, text in sections if text), footer])
    path.write_text(page(f"{design.name}: gearcad report", body), encoding="utf-8")
