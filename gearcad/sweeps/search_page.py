"""sweep.html's sections for a search and a confirmation: the hypervolume after each generation
(a line, a table) against a grid's of the same budget, and the front rows re-designed at the full
stage with why the others fail."""

from __future__ import annotations

import html

from .ticks import nice_ticks, tick_label

__all__ = ["search_section", "confirmation_section"]


def _hypervolume_chart(volumes: list, attrs) -> str:
    """The hypervolume after each generation as a line (SVG), the grid's as a dashed one."""
    w, h, left, bottom = 360, 160, 60, 36
    top = max(max(volumes), attrs.get("grid_hypervolume", 0.0))
    y0, y1, yticks, yd = nice_ticks(0.0, top if top > 0 else 1.0, most=5)
    n = len(volumes)

    def sx(g):
        return left + (g / max(n - 1, 1)) * (w - left - 10)

    def sy(v):
        return h - bottom - (v - y0) / (y1 - y0) * (h - bottom - 10)

    grid = "".join(
        f'<line class="grid" x1="{left}" y1="{sy(t):.1f}" x2="{w - 10}" y2="{sy(t):.1f}"/>'
        f'<text x="{left - 6}" y="{sy(t) + 4:.1f}" text-anchor="end">{tick_label(t, yd)}</text>'
        for t in yticks
    )
    line = " ".join(f"{sx(g):.1f},{sy(v):.1f}" for g, v in enumerate(volumes))
    dots = "".join(f'<circle class="front" cx="{sx(g):.1f}" cy="{sy(v):.1f}" r="3"/>' for g, v in enumerate(volumes))
    ref = ""
    if "grid_hypervolume" in attrs:
        gy = sy(attrs["grid_hypervolume"])
        ref = f'<line class="gridhv" x1="{left}" y1="{gy:.1f}" x2="{w - 10}" y2="{gy:.1f}"/>'
    labels = "".join(
        f'<text x="{sx(g):.1f}" y="{h - bottom + 16}" text-anchor="middle">{g}</text>'
        for g in range(n)
        if n <= 12 or g % max(1, n // 10) == 0
    )
    svg = (
        f'<svg class="chart" xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" '
        f'role="img" aria-label="hypervolume after each generation">{grid}{ref}'
        f'<polyline class="hv" points="{line}"/>{dots}{labels}'
        f'<text class="axis" x="{(left + w) / 2:.0f}" y="{h - 4}" text-anchor="middle">generation</text></svg>'
    )
    return svg


def search_section(table) -> str:
    """A search's generations: the hypervolume of the front after each (a line and a table),
    against a grid's of the same budget where one was designed (``--against-grid``)."""
    attrs = table.attrs
    volumes = attrs.get("hypervolumes")
    if not volumes:
        return ""
    sizes = attrs.get("front_sizes", [])
    counts = table["generation"].value_counts().sort_index() if "generation" in table else None
    svg = _hypervolume_chart(volumes, attrs)
    n = len(volumes)
    rows = "".join(
        f"<tr><td>{g}</td><td>{int(counts.get(g, 0)) if counts is not None else ''}</td>"
        f"<td>{sizes[g] if g < len(sizes) else ''}</td><td>{volumes[g]:.6g}</td></tr>"
        for g in range(n)
    )
    reference = ", ".join(f"{v:.6g}" for v in attrs.get("reference_point", []))
    against = ""
    if "grid_hypervolume" in attrs:
        against = (
            f"<p>A grid of the same budget ({attrs['grid_evaluations']} designs over the same ranges; the dashed "
            f"line): {len(attrs.get('grid_front', []))} front points, hypervolume {attrs['grid_hypervolume']:.6g}; "
            f"this search: {sizes[-1] if sizes else '?'} front points, {volumes[-1]:.6g}, in {len(table)} designs.</p>"
        )
    method = html.escape(str(attrs.get("method", "search")).upper())
    return (
        f"<h2>The search ({method}, population {attrs.get('population')}, seed {attrs.get('seed')})</h2>"
        f"<p>The hypervolume of the feasible front after each generation: the area the front dominates up to the "
        f"reference point ({html.escape(reference)}: every objective minimised, a maximised one negated), the "
        f"nadir of the front{' and the grid’s' if against else ''} plus 10 % of its span.</p>"
        f"{svg}{against}<table><tr><th>generation</th><th>designs</th><th>front points</th>"
        f"<th>hypervolume</th></tr>{rows}</table>"
    )


def confirmation_section(table) -> str:
    """The front's rows re-designed at the full stage: which passed, and why the others failed."""
    if "confirmed" not in table:
        return ""
    tried = table[table["confirmed"].notna()]
    items = "".join(
        f"<li>#{int(r['index'])}: "
        + ("passes" if bool(r["confirmed"]) else f"fails — {html.escape(str(r['confirm_refusal']))}")
        + "</li>"
        for r in tried[["index", "confirmed", "confirm_refusal"]].to_dict("records")
    )
    held = int(tried["confirmed"].astype(bool).sum())
    return (
        f"<h2>Confirmed at the full stage</h2><p>{held} of the {len(tried)} front rows re-designed at the full "
        f"stage pass; the front is taken again among the rows not refuted.</p><ul>{items}</ul>"
    )
