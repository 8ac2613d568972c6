"""A profile page's charts and its table of files (``html``)."""

from __future__ import annotations

from collections.abc import Mapping
from html import escape
from urllib.parse import quote

from ..formats import FORMATS, WHOLES, by_name
from .html_text import link as _link

__all__ = ["section_charts", "section_files"]


_OWN = {
    "report.json": "the report: every number of this page and more",
    "papers.html": "the paper's tables and claims beside gearcad's numbers",
}
"""The writing loop's own files (not of a format), by name."""


def _what(name: str, entry: Mapping) -> str:
    """What a file is: a whole or a part by its format's entry (``kind`` names the format), a
    chart, a table, the animation or one of the loop's own files; then its counts."""
    kind = entry.get("kind", "")
    part = entry.get("part")
    fmt = by_name(kind) if kind in FORMATS else None
    whole = fmt.whole_of(part) if fmt is not None and part else None
    bits = [WHOLES[whole]] if whole else [f"part {part}"] if part else []
    for key, unit in (("vertices", "vertices"), ("segments", "segments"), ("triangles", "triangles")):
        if key in entry:
            bits.append(f"{entry[key]} {unit}")
    if "faces" in entry:  # a STEP solid
        faces = " + ".join(f"{n} {kind}" for kind, n in sorted(entry["faces"].items()))
        bits += [f"solid: {faces} faces", f"{entry['volume']:.1f} mm³"]
    if "mid_deviation" in entry:
        bits.append(f"flank within {entry['mid_deviation']:.4f} mm of the exact section")
    if "rows" in entry:
        bits.append(f"table, {entry['rows']} rows")
    if "frames" in entry:
        bits.append(f"animation, {entry['frames']} frames")
    if kind == "png":
        bits.append("chart")
    if fmt is None and name in _OWN:
        bits.append(_OWN[name])
    return escape(", ".join(bits))


def _size(entry: Mapping) -> str:
    size = entry.get("bytes")
    if size is None:
        return ""
    return f"{size / 1024:.1f} kB" if size >= 1024 else f"{size} B"


def section_charts(files: Mapping) -> str:
    charts = [n for n, e in files.items() if e.get("kind") == "png"]
    if not charts:
        return ""
    figures = "".join(
        f'<figure><a href="{escape(quote(n))}"><img src="{escape(quote(n))}" alt="{escape(n)}"></a>'
        f'<figcaption>{escape(n)} (<a href="{escape(quote(n))}">full size</a>)</figcaption></figure>'
        for n in charts
    )
    return f'<h2 id="charts">Charts</h2><div class="charts">{figures}</div>'


def section_files(files: Mapping, page: str) -> str:
    rows = "".join(
        f"<tr><td>{_link(name)}</td><td>{escape(str(e.get('kind', '')))}</td><td>{_what(name, e)}</td>"
        f"<td class='num'>{_size(e)}</td></tr>"
        for name, e in files.items()
        if name != page
    )
    return (
        '<h2 id="files">Files</h2>'
        '<p class="note">To cut: <b>sheet.dxf</b> or <b>sheet.svg</b> (every part, laid out) or one file per part. '
        "To print: <b>plate.3mf</b> (every part on the bed) or one STL or 3MF per part. "
        "The <b>assembly</b> files place the parts where they work: they are for checking the fit.</p>"
        f"<table><tr><th>file</th><th>kind</th><th>what</th><th>size</th></tr>{rows}</table>"
    )
