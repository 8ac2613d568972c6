"""``out/index.html``: one page over every profile of a build, linking each profile's page."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from html import escape
from pathlib import Path
from urllib.parse import quote

from ..findings import CODES
from .html_style import page

__all__ = ["index_entry", "index_page", "write_index"]


def index_entry(report: Mapping, link: str, summary: str = "") -> dict:
    """An entry for :func:`write_index` from a profile's report (``report.json`` as a dict), the
    relative link to its page (e.g. ``"walker/index.html"``) and its one-line summary; its picture
    shows the parts (a chart is unreadable at a thumbnail's size, and two variants of a profile
    draw the same limits chart): the animation, else the assembly's SVG, else a part's, else the
    rendered solids; a chart only when nothing else was written."""
    files = report.get("files", {})
    kinds = {n: e.get("kind") for n, e in files.items()}
    parts = {p["name"] for p in report.get("parts", [])}
    pictures = [n for n, k in kinds.items() if k == "gif"]
    pictures += [n for n in ("assembly.svg", *(f"{p}.svg" for p in sorted(parts)), "solid.png") if n in kinds]
    pictures += [n for n, k in kinds.items() if k == "png"]
    entry = {
        "name": report["name"],
        "title": report.get("title") or report["name"],
        "mechanism": report.get("mechanism", ""),
        "summary": summary,
        "warnings": len(report.get("warnings", [])),
        "codes": sorted({w["code"] for w in report.get("warnings", [])}),
        "link": link,
    }
    if pictures:  # beside the page it links to
        entry["image"] = f"{link.rsplit('/', 1)[0]}/{pictures[0]}" if "/" in link else pictures[0]
    return entry


def write_index(path: Path, entries: Sequence[Mapping]) -> None:
    """Write the ``index.html`` over all profiles of a build (see :func:`index_page`) at ``path``;
    every entry's ``link`` is relative to its folder."""
    Path(path).write_text(index_page(entries), encoding="utf-8")


def index_page(entries: Sequence[Mapping]) -> str:
    """The ``index.html`` over all profiles of a build, as text.

    Parameters
    ----------
    entries : sequence of mappings
        One per profile, in the order shown: ``name``, ``title``, ``mechanism``, ``summary``,
        ``warnings`` (the count) and ``link`` (relative, e.g. ``"walker/index.html"``); optional
        ``codes`` (the findings' codes) and ``image`` (a relative link to a picture of it).
    """
    rows = []
    total = 0
    for e in entries:
        count = int(e.get("warnings", 0))
        total += count
        codes = " ".join(
            f'<span class="code" title="{escape(CODES.get(c, ""))}">{escape(c)}</span>' for c in e.get("codes", ())
        )
        link = escape(quote(e["link"]))
        image = (
            f'<a href="{link}"><img class="thumb" src="{escape(quote(e["image"]))}" alt=""></a>'
            if e.get("image")
            else ""
        )
        rows.append(
            f'<tr><td class="thumb">{image}</td><td><a href="{link}"><b>{escape(e["name"])}</b></a></td>'
            f"<td>{escape(e.get('title', ''))}<br><span class='note'>{escape(e.get('summary', ''))}</span></td>"
            f"<td class='nowrap'>{escape(e.get('mechanism', ''))}</td>"
            f'<td><span class="count {"bad" if count else "good"}">{count}</span> {codes}</td></tr>'
        )
    body = (
        f"<header><h1>gearcad build</h1><p class='sub'>{len(entries)} profile{'s' * (len(entries) != 1)}, "
        f"{total} finding{'s' * (total != 1)} in all. Each profile's page shows its parts, assembly, findings, "
        "key numbers and files.</p></header>"
        "<table><tr><th></th><th>profile</th><th>title and summary</th><th>mechanism</th><th>findings</th></tr>"
        + "".join(rows)
        + "</table><footer>Written by gearcad; one file, nothing loaded from the network.</footer>"
    )
    return page("gearcad build", body)
