"""``papers.html``: the papers' numbers beside gearcad's, for a profile that reproduces a seed
(report.json's ``papers`` block), and the section of the profile's page that links it."""

from __future__ import annotations

from collections.abc import Mapping
from html import escape
from pathlib import Path

from .html_style import page
from .html_text import e, link

__all__ = ["section_papers", "write_papers_page"]


def section_papers(report: Mapping) -> str:
    """The profile page's short section: which seed, how many numbers agree, the link."""
    block = report.get("papers")
    if not block:
        return ""
    held = sum(c["holds"] for c in block["claims"])
    claims = f"; {held} of {len(block['claims'])} claims of the text hold" if block["claims"] else ""
    return (
        '<h2 id="papers">The paper</h2>'
        f"<p>This profile reproduces seed {escape(block['seed'])} ({escape(block['paper'])}): "
        f'<b class="ok">{block["agree"]}</b> of its printed numbers agree with gearcad\'s to the printed '
        f'digits, <b class="{"bad" if block["differ"] else "ok"}">{block["differ"]}</b> differ (each with its '
        f"erratum){claims}. Every number side by side: "
        f"{link(block['page'])}.</p>"
    )


def _verdict(row: Mapping) -> str:
    if row["verdict"] == "agrees":
        return '<span class="ok">agrees</span>'
    return f'<span class="bad">differs</span>: {escape(row["erratum"] or "")}'


def _table(table: Mapping) -> str:
    rows = "".join(
        f"<tr><td>{escape(r['quantity'])}</td><td class='num'>{e(r['paper'])}</td>"
        f"<td class='num'>{e(r['gearcad'])}</td><td class='num'>{e(r['difference'])}</td>"
        f"<td>{_verdict(r)}</td></tr>"
        for r in table["rows"]
    )
    return (
        f"<h3>{escape(table['name'])}</h3><table><tr><th>quantity</th><th>paper (as printed)</th>"
        f"<th>gearcad</th><th>gearcad − paper</th><th>verdict</th></tr>{rows}</table>"
    )


def papers_page(report: Mapping, *, back: str = "index.html") -> str:
    """The page as text (``report`` as written to report.json, with its ``papers`` block)."""
    block = report["papers"]
    verdicts = ('<span class="bad">does not hold</span>', '<span class="ok">holds</span>')
    claims = "".join(
        f"<tr><td>{escape(c['claim'])}</td><td>{verdicts[c['holds']]}</td><td>{escape(c['message'])}</td></tr>"
        for c in block["claims"]
    )
    body = (
        f"<header><h1>Seed {escape(block['seed'])}: the paper beside gearcad</h1>"
        f"<p class='sub'>{escape(block['paper'])} · {escape(report['name'])} · <a href='{escape(back)}'>"
        "the profile's page</a></p>"
        f"<p class='note'>Source: {escape(block['source'])}. Paper values as printed (not corrected); gearcad's "
        "computed from this profile's geometry. A number agrees when the printed value is gearcad's rounded or "
        "truncated to the printed digits; a differing number names its erratum (docs/papers.md, "
        "\"What the papers get wrong\").</p></header>"
        + "".join(_table(t) for t in block["tables"])
        + (f"<h2>Claims of the text</h2><table><tr><th>claim</th><th>verdict</th><th>gearcad's finding</th></tr>"
           f"{claims}</table>" if claims else "")
        + "<footer>Written by gearcad; one file, nothing loaded from the network.</footer>"
    )  # fmt: skip
    return page(f"{report['name']}: seed {block['seed']} beside gearcad", body)


def write_papers_page(path: Path, report: Mapping) -> None:
    """Write ``papers.html`` beside the profile's ``index.html``."""
    Path(path).write_text(papers_page(report), encoding="utf-8")
