"""The sweep's HTML page: the objectives plotted against each other (an inline SVG, no script),
the Pareto front highlighted, and for every front row the command that builds it."""

from __future__ import annotations

import html
import math
import shlex

import numpy as np

__all__ = ["sweep_page", "build_command"]

W, H, PAD = 640, 420, 56


def build_command(table, row) -> str:
    """``gearcad build PROFILE --set KEY=VALUE …`` for one row of the table."""
    profile = table.attrs.get("profile") or "PROFILE.toml"
    sets = [f"--set {shlex.quote(f'{c[4:]}={_toml(row[c])}')}" for c in table.attrs.get("inputs", [])]
    return " ".join(["gearcad build", shlex.quote(profile), *sets])


def _toml(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def _axes(table) -> list[str]:
    objectives = [*table.attrs.get("minimise", []), *table.attrs.get("maximise", [])]
    inputs = table.attrs.get("inputs", [])
    return (objectives + inputs)[:2] if len(objectives) < 2 else objectives[:2]


def _scale(values: np.ndarray, lo_px: float, hi_px: float):
    finite = values[np.isfinite(values)]
    lo, hi = (float(finite.min()), float(finite.max())) if len(finite) else (0.0, 1.0)
    if hi <= lo:
        lo, hi = lo - 0.5, hi + 0.5
    return lambda v: lo_px + (v - lo) / (hi - lo) * (hi_px - lo_px), (lo, hi)


def _scatter(table, xkey: str, ykey: str) -> str:
    import pandas as pd

    x = pd.to_numeric(table[xkey], errors="coerce").to_numpy(float)
    y = pd.to_numeric(table[ykey], errors="coerce").to_numpy(float)
    sx, (x0, x1) = _scale(x, PAD, W - 16)
    sy, (y0, y1) = _scale(y, H - PAD, 16)
    dots = []
    order = np.argsort(table["pareto"].to_numpy(bool), kind="stable")  # the front drawn last, on top
    for i in order:
        if not (math.isfinite(x[i]) and math.isfinite(y[i])):
            continue
        row = table.iloc[i]
        kind = "front" if row["pareto"] else ("ok" if row["feasible"] else "out")
        tip = html.escape(f"#{row['index']}: {xkey} = {x[i]:.6g}, {ykey} = {y[i]:.6g}")
        dots.append(
            f'<a href="#row-{row["index"]}"><circle class="{kind}" cx="{sx(x[i]):.1f}" cy="{sy(y[i]):.1f}" r="4">'
            f"<title>{tip}</title></circle></a>"
        )
    labels = (
        f'<text x="{PAD}" y="{H - 20}">{x0:.4g}</text><text x="{W - 16}" y="{H - 20}" text-anchor="end">{x1:.4g}</text>'
        f'<text x="{(W + PAD) / 2}" y="{H - 4}" text-anchor="middle">{html.escape(xkey)}</text>'
        f'<text x="{PAD - 4}" y="{H - PAD}" text-anchor="end">{y0:.4g}</text>'
        f'<text x="{PAD - 4}" y="22" text-anchor="end">{y1:.4g}</text>'
        f'<text x="14" y="{H / 2}" transform="rotate(-90 14 {H / 2})" text-anchor="middle">{html.escape(ykey)}</text>'
    )
    frame = f'<rect x="{PAD}" y="16" width="{W - PAD - 16}" height="{H - PAD - 16}" class="frame"/>'
    svg = f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {H}" width="{W}" height="{H}">'
    return f"{svg}{frame}{labels}{''.join(dots)}</svg>"


def sweep_page(table) -> str:
    """The page as one HTML string."""
    attrs = table.attrs
    made = int(table["refusal"].isna().sum())
    axes = _axes(table)
    chart = _scatter(table, *axes) if len(axes) == 2 else "<p>(name two objectives, or vary a key, to plot)</p>"
    front = table[table["pareto"]] if table["pareto"].any() else table[table["feasible"]].head(50)
    shown = [*attrs.get("inputs", []), *[k for k in (*attrs.get("minimise", []), *attrs.get("maximise", []))]]
    head = "".join(f"<th>{html.escape(c)}</th>" for c in ["#", *shown, "build"])
    body = "".join(
        f'<tr id="row-{r["index"]}"><td>{r["index"]}</td>'
        + "".join(f"<td>{html.escape(_cell(r[c]))}</td>" for c in shown)
        + f"<td><code>{html.escape(build_command(table, r))}</code></td></tr>"
        for _, r in front.iterrows()
    )
    refusals = table["refusal"].dropna().value_counts().head(8)
    refused = "".join(f"<li>{n} × {html.escape(reason)}</li>" for reason, n in refusals.items())
    title = html.escape(f"Sweep of {attrs.get('name', 'profile')} at stage {attrs.get('stage', '?')}")
    goals = "; ".join(
        [
            *(f"minimise {k}" for k in attrs.get("minimise", [])),
            *(f"maximise {k}" for k in attrs.get("maximise", [])),
            *(f"{c}" for c in attrs.get("constraints", [])),
        ]
    )
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>body{{font:14px system-ui,sans-serif;margin:2em;max-width:72em}} table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:2px 6px;text-align:right}} td code{{white-space:nowrap}}
circle.ok{{fill:#9ab}} circle.out{{fill:#ddd}} circle.front{{fill:#d40;stroke:#000}} rect.frame{{fill:none;stroke:#888}}
text{{font-size:11px}}</style></head><body>
<h1>{title}</h1>
<p>{len(table)} designs: {made} made, {len(table) - made} refused, {int(table["feasible"].sum())} feasible,
{int(table["pareto"].sum())} on the Pareto front. {html.escape(goals)}</p>
{chart}
<p>Red: the front; blue: feasible; grey: made but outside the constraints. A dot links to its row.</p>
<h2>{"The front" if table["pareto"].any() else "Feasible designs"}</h2>
<table><tr>{head}</tr>{body}</table>
<h2>Refusals</h2><ul>{refused or "<li>none</li>"}</ul>
</body></html>
"""


def _cell(value) -> str:
    if isinstance(value, (float, np.floating)):
        return f"{value:.6g}"
    return str(value)
