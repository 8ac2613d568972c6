"""How the HTML pages write a report's values: numbers to 6 significant digits, JSON objects as
tables, relative links."""

from __future__ import annotations

import math
from html import escape
from urllib.parse import quote

__all__ = ["fmt", "e", "as_html", "link"]


def fmt(value) -> str:
    """A number as a reader wants it: 6 significant digits, exponent only when very large or small."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if value == 0 or math.isnan(value):
            return "0" if value == 0 else "NaN"
        if 1e-3 <= abs(value) < 1e6:
            return f"{value:.6g}"
        return f"{value:.3e}"
    if value is None:
        return "—"
    return str(value)


def e(value) -> str:
    return escape(fmt(value))


def as_html(value, depth: int = 0) -> str:
    """Any JSON value of the report as HTML: tables for objects, lists inline where short."""
    if isinstance(value, dict):
        if not value:
            return "—"
        rows = "".join(f"<tr><th>{escape(str(k))}</th><td>{as_html(v, depth + 1)}</td></tr>" for k, v in value.items())
        return f'<table class="kv">{rows}</table>'
    if isinstance(value, list):
        if not value:
            return "none"
        if all(isinstance(v, dict) for v in value):
            blocks = []
            for k, v in enumerate(value):
                label = v.get("name", f"#{k + 1}")
                rest = {key: x for key, x in v.items() if key != "name"}
                blocks.append(f"<h3>{escape(str(label))}</h3>{as_html(rest, depth + 1)}")
            return "".join(blocks)
        shown = ", ".join(as_html(v, depth + 1) for v in value[:12])
        more = f", … ({len(value)} values)" if len(value) > 12 else ""
        return f"[{shown}{more}]"
    return e(value)


def link(name: str) -> str:
    return f'<a href="{escape(quote(name))}">{escape(name)}</a>'
