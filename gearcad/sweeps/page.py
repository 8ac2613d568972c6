"""The sweep's HTML page: the objectives plotted against each other (an inline SVG, no script),
with ticks and units on both axes, the Pareto front marked so that it reads in greyscale too
(dark filled diamonds; feasible designs hollow circles; designs outside the constraints light
crosses), the constraints with how many designs meet each, and for every front row its values
and the command that builds it.  A dot links to its row only where the page has that row."""

from __future__ import annotations

import html
import re
import shlex

import numpy as np

from .ticks import nice_ticks, tick_label

__all__ = ["sweep_page", "build_command", "unit", "nice_ticks"]

W, H = 760, 480
LEFT, RIGHT, TOP, BOTTOM = 84, 16, 16, 64
"""The plot's size and its margins (px): room for the tick labels and the axis titles."""

MAX_DOTS = 5000
"""Dots drawn at most (front rows first): beyond it every k-th other row, as the page says."""

MAX_ROWS = 500
"""Rows of the front table at most; front.csv holds them all."""

_LENGTH = {
    # profile keys (docs/reference.md) and report keys (docs/files.md) whose unit is mm
    "a", "b", "c", "r", "R", "L", "H", "radius", "radii", "travel", "scale", "center_distance", "module",
    "requested_module", "inner_module", "backlash", "clearance", "diameter", "keyway_width", "keyway_depth",
    "flat", "pilot", "kerf", "kerf_variation", "xy_compensation", "xy_variation", "elephant_foot",
    "tool_diameter", "center_distance_tolerance", "bore_play", "max_play", "tolerance", "thickness", "chamfer",
    "gap", "sheet", "bed", "r_min", "r_max", "perimeter", "min_curvature_radius", "min_concave_radius",
    "undercut_depth", "min_tip_thickness", "module_limit_undercut", "identical_deviation", "backlash_design",
    "backlash_min", "backlash_max", "contact_residual", "mate_shape_difference", "shape_difference", "depth",
    "flank_depth", "hob_depth", "window", "arc", "height", "offset", "nudge", "paper_table_offset",
}  # fmt: skip
_UNITS = {
    **dict.fromkeys(("area", "overlap", "allowed_overlap", "max_overlap", "nudged_min_overlap"), "mm²"),
    **dict.fromkeys(("closure_error", "shortfall", "blend_width", "phi", "worst_phi", "undercut_phi"), "rad"),
    **dict.fromkeys(("pressure_angle", "paper_turn_per_quarter"), "rad"),
    **dict.fromkeys(("slip_residual", "paper_slip"), "mm/rad"),
    **dict.fromkeys(("addendum", "dedendum", "tip_radius", "profile_shift"), "× module"),
    **dict.fromkeys(("ratio_min", "ratio_max"), "ω₂/ω₁"),
    **dict.fromkeys(("roller_radius", "amplitude"), "× R"),
}


def unit(key: str) -> str:
    """The unit of a table column (``set.<profile key>`` or a dotted report key), from
    docs/reference.md and docs/files.md: lengths in mm, the report's angles in rad, a profile
    key ending in ``_deg`` in degrees; "" for a count, a ratio of like quantities, or a key
    whose unit is not known."""
    leaf = key.rsplit(".", 1)[-1]
    if leaf.endswith("_deg"):
        return "°"
    if leaf.endswith("rpm"):
        return "rev/min"
    if leaf.endswith("_eps"):
        return "rad/s²"
    if ".kinematics." in f".{key}":
        if "acceleration" in leaf:
            return "rad/s²"
        if "speed" in leaf:
            return "rad/s"
    if key.startswith("set.body.") and leaf != "scale":  # a roller body's [body]: lengths in units of R
        return "× R" if leaf in _LENGTH or leaf in _UNITS else ""
    return "mm" if leaf in _LENGTH else _UNITS.get(leaf, "")


def _titled(key: str) -> str:
    u = unit(key)
    return f"{key} ({u})" if u else key


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


def _marker(kind: str, x: float, y: float, legend: bool = False) -> str:
    """A row's marker (``legend``: the legend's, of class "<kind> key": one class="front" per front row)."""
    css = f"{kind} key" if legend else kind
    if kind == "front":  # a dark filled diamond
        return f'<path class="{css}" d="M{x:.1f} {y - 6:.1f}l6 6-6 6-6-6z"/>'
    if kind == "ok":  # a hollow circle
        return f'<circle class="{css}" cx="{x:.1f}" cy="{y:.1f}" r="4"/>'
    return f'<path class="{css}" d="M{x - 3:.1f} {y - 3:.1f}l6 6m0-6l-6 6"/>'  # a light cross


def _numbers(table, key: str) -> np.ndarray:
    import pandas as pd

    return pd.to_numeric(table[key], errors="coerce").to_numpy(float)


def _shown_dots(kinds: np.ndarray, plotted: np.ndarray) -> tuple[np.ndarray, int]:
    """Rows to draw: every plotted front row, then the others thinned to :data:`MAX_DOTS` in
    all (every k-th by index); and how many were left out."""
    front = np.flatnonzero(plotted & (kinds == "front"))[:MAX_DOTS]
    others = np.flatnonzero(plotted & (kinds != "front"))
    room = MAX_DOTS - len(front)
    if len(others) > room:
        others = others[np.linspace(0, len(others) - 1, max(room, 0)).astype(int)] if room > 0 else others[:0]
    shown = np.concatenate([others, front])  # the front drawn last, on top
    return shown, int(plotted.sum()) - len(shown)


def _scatter(table, xkey: str, ykey: str, linked: set[int]) -> tuple[str, int, int]:
    """The chart, how many rows with both values were left out (thinned), and how many have both."""
    x, y = _numbers(table, xkey), _numbers(table, ykey)
    plotted = np.isfinite(x) & np.isfinite(y)
    kinds = np.where(table["pareto"].to_numpy(bool), "front", np.where(table["feasible"].to_numpy(bool), "ok", "out"))
    x0, x1, xticks, xd = nice_ticks(*(_range(x[plotted])))
    y0, y1, yticks, yd = nice_ticks(*(_range(y[plotted])))
    right, bottom = W - RIGHT, H - BOTTOM

    def sx(v):
        return LEFT + (v - x0) / (x1 - x0) * (right - LEFT)

    def sy(v):
        return bottom - (v - y0) / (y1 - y0) * (bottom - TOP)

    grid = []
    for t in xticks:
        grid.append(
            f'<line class="grid" x1="{sx(t):.1f}" y1="{TOP}" x2="{sx(t):.1f}" y2="{bottom + 5}"/>'
            f'<text x="{sx(t):.1f}" y="{bottom + 18}" text-anchor="middle">{tick_label(t, xd)}</text>'
        )
    for t in yticks:
        grid.append(
            f'<line class="grid" x1="{LEFT - 5}" y1="{sy(t):.1f}" x2="{right}" y2="{sy(t):.1f}"/>'
            f'<text x="{LEFT - 8}" y="{sy(t) + 4:.1f}" text-anchor="end">{tick_label(t, yd)}</text>'
        )
    goal = {k: " — minimised" for k in table.attrs.get("minimise", [])}
    goal.update({k: " — maximised" for k in table.attrs.get("maximise", [])})
    titles = (
        f'<text class="axis" x="{(LEFT + right) / 2:.0f}" y="{H - 14}" text-anchor="middle">'
        f"{html.escape(_titled(xkey) + goal.get(xkey, ''))}</text>"
        f'<text class="axis" x="16" y="{(TOP + bottom) / 2:.0f}" transform="rotate(-90 16 {(TOP + bottom) / 2:.0f})" '
        f'text-anchor="middle">{html.escape(_titled(ykey) + goal.get(ykey, ""))}</text>'
    )
    shown, left_out = _shown_dots(kinds, plotted)
    numbers = table["index"].to_numpy()
    dots = []
    for i in shown:
        number = int(numbers[i])
        tip = html.escape(f"#{number}: {xkey} = {x[i]:.6g}, {ykey} = {y[i]:.6g}")
        mark = f"{_marker(kinds[i], sx(x[i]), sy(y[i]))}"
        if number in linked:
            dots.append(f'<a href="#row-{number}"><g><title>{tip}</title>{mark}</g></a>')
        else:
            dots.append(f"<g><title>{tip}</title>{mark}</g>")
    frame = f'<rect class="frame" x="{LEFT}" y="{TOP}" width="{right - LEFT}" height="{bottom - TOP}"/>'
    svg = (
        f'<svg class="chart" xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {H}" width="{W}" height="{H}" '
        f'role="img" aria-label="{html.escape(ykey)} against {html.escape(xkey)}">'
    )
    return f"{svg}{''.join(grid)}{frame}{titles}{''.join(dots)}</svg>", left_out, int(plotted.sum())


def _range(values: np.ndarray) -> tuple[float, float]:
    """The values' span and 3 % more either side, so that no marker sits on the frame."""
    if not len(values):
        return 0.0, 1.0
    lo, hi = float(values.min()), float(values.max())
    return lo - 0.03 * (hi - lo), hi + 0.03 * (hi - lo)


def _legend(table) -> str:
    """The three markers, as drawn, with what they mean and how many there are."""
    front = int(table["pareto"].sum())
    feasible = int(table["feasible"].sum()) - front
    made = int(table["refusal"].isna().sum())
    out = made - front - feasible
    items = [
        ("front", f"on the Pareto front ({front})"),
        ("ok", f"feasible, not on the front ({feasible})"),
        ("out", f"made, outside the constraints ({out})"),
    ]
    return "".join(
        f'<span class="legend-item"><svg width="16" height="16" viewBox="0 0 16 16" aria-hidden="true">'
        f"{_marker(k, 8, 8, legend=True)}"
        f"</svg> {html.escape(text)}</span>"
        for k, text in items
    )


def _constraints(table) -> str:
    """Each constraint, its unit, and how many made designs meet it."""
    from ..errors import ProfileError
    from .front import feasible, parse_constraint

    made = table[table["refusal"].isna()]
    items = []
    for text in table.attrs.get("constraints", []):
        count = ""
        try:
            constraint = parse_constraint(text)
        except ProfileError:
            constraint = None
        if constraint is not None and constraint[0] in made:
            try:
                held = int(feasible(made, [constraint]).sum())
                count = f": met by {held} of {len(made)} made designs"
            except TypeError:  # a value of another type than the key's
                pass
        u = unit(str(constraint[0])) if constraint is not None else ""
        number = (
            constraint is not None and isinstance(constraint[2], (int, float)) and not isinstance(constraint[2], bool)
        )
        shown = f"{text} {u}" if u and number else text
        items.append(f"<li><code>{html.escape(shown)}</code>{html.escape(count)}</li>")
    return f"<ul>{''.join(items)}</ul>" if items else "<p>none: every made design is feasible</p>"


def _constraint_keys(table) -> list[str]:
    keys = []
    for text in table.attrs.get("constraints", []):
        key = re.split(r"\s*(?:<=|>=|==|!=|<|>)", text, maxsplit=1)[0].strip()
        if key in table.columns and key not in keys:
            keys.append(key)
    return keys


def _chart(table, linked: set[int]) -> str:
    """The scatter of the two axes (only the listed rows linked), its legend and what it leaves out."""
    axes = _axes(table)
    if len(axes) == 2:
        chart, left_out, plotted = _scatter(table, *axes, linked)
        notes = ["Only the rows listed below have a link."]
        if left_out:
            notes.append(
                f"{left_out} of the {plotted} designs with both values are not drawn (every k-th is, and the front)."
            )
        if len(table) > plotted:
            notes.append(f"{len(table) - plotted} designs (refused, or without a value of either axis) have no point.")
        chart += f'<p class="legend">{_legend(table)}</p><p>{" ".join(notes)}</p>'
    else:
        chart = "<p>(name two objectives, or vary a key, to plot)</p>"
    return chart


def _listed(table, objectives: list, listed) -> tuple[str, str]:
    """The listed rows' table head and body: the inputs, objectives, constraints (and a search's
    generation and the confirmation) of each row, with the command that builds it."""
    attrs = table.attrs
    inputs = list(attrs.get("inputs", []))
    shown = [*inputs, *[k for k in objectives if k not in inputs]]
    shown += [k for k in _constraint_keys(table) if k not in shown]
    shown += [k for k in ("generation", "confirmed") if k in table.columns]
    head = "".join(f"<th>{html.escape(_titled(c)).replace('.', '.<wbr>')}</th>" for c in ["#", *shown])
    columns = list(dict.fromkeys(["index", *shown, *inputs]))
    records = listed[columns].to_dict("records")  # plain values: far quicker than iterrows
    body = "".join(
        f'<tr id="row-{r["index"]}"><td>{r["index"]}</td>'
        + "".join(f"<td>{html.escape(_cell(r[c]))}</td>" for c in shown)
        + f'</tr><tr class="build"><td></td><td colspan="{len(shown)}"><code>'
        f"{html.escape(build_command(table, r))}</code></td></tr>"
        for r in records
    )
    return head, body


def sweep_page(table) -> str:
    """The page as one HTML string."""
    from .search_page import confirmation_section, search_section

    attrs = table.attrs
    made = int(table["refusal"].isna().sum())
    objectives = [*attrs.get("minimise", []), *attrs.get("maximise", [])]
    has_front = bool(table["pareto"].any())
    rows = table[table["pareto"]] if has_front else table[table["feasible"]]
    if objectives and objectives[0] in rows:  # the front in order along its first objective
        rows = rows.iloc[np.argsort(_numbers(rows, objectives[0]), kind="stable")]
    listed = rows.head(MAX_ROWS)
    linked = {int(i) for i in listed["index"]}
    chart = _chart(table, linked)
    head, body = _listed(table, objectives, listed)
    more = (
        f"<p>The first {MAX_ROWS} of {len(rows)} rows; front.csv and sweep.csv hold them all.</p>"
        if len(rows) > MAX_ROWS
        else ""
    )
    refusals = table["refusal"].dropna().value_counts().head(8)
    refused = "".join(f"<li>{n} × {html.escape(reason)}</li>" for reason, n in refusals.items())
    title = html.escape(f"Sweep of {attrs.get('name', 'profile')} at stage {attrs.get('stage', '?')}")
    goals = "; ".join(
        [
            *(f"minimise {_titled(k)}" for k in attrs.get("minimise", [])),
            *(f"maximise {_titled(k)}" for k in attrs.get("maximise", [])),
        ]
    )
    heading = "The front" if has_front else ("Feasible designs" if len(rows) else "No feasible design")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>body{{font:14px system-ui,sans-serif;margin:2em;max-width:72em;color:#111}}
table{{border-collapse:collapse;max-width:100%}} td,th{{border:1px solid #ccc;padding:2px 6px;text-align:right}}
th{{background:#f2f2f2;vertical-align:bottom}}
tr.build td{{text-align:left;border-top:none;padding-bottom:6px}}
tr.build code{{white-space:normal;overflow-wrap:anywhere;font-size:12px}}
svg.chart{{max-width:100%;height:auto}} svg text{{font-size:12px;fill:#111}} svg text.axis{{font-size:13px}}
.front{{fill:#1a1a66;stroke:#000;stroke-width:1}} .ok{{fill:#fff;stroke:#555;stroke-width:1.5}}
.out{{fill:none;stroke:#b0b0b0;stroke-width:1.5}} rect.frame{{fill:none;stroke:#666}} line.grid{{stroke:#e4e4e4}}
polyline.hv{{fill:none;stroke:#1a1a66;stroke-width:2}} line.gridhv{{stroke:#555;stroke-dasharray:6 4;stroke-width:1.5}}
.legend-item{{margin-right:1.5em;white-space:nowrap}} .legend-item svg{{vertical-align:middle}}</style></head><body>
<h1>{title}</h1>
<p>{len(table)} designs: {made} made, {len(table) - made} refused, {int(table["feasible"].sum())} feasible,
{int(table["pareto"].sum())} on the Pareto front. {html.escape(goals)}</p>
<h2>Constraints</h2>
{_constraints(table)}
{chart}
{search_section(table)}{confirmation_section(table)}
<h2>{heading}</h2>
{more}<table><tr>{head}</tr>{body}</table>
<h2>Refusals</h2><ul>{refused or "<li>none</li>"}</ul>
</body></html>
"""


def _cell(value) -> str:
    if value is None or type(value).__name__ == "NAType":  # pandas' missing value (a row not confirmed)
        return ""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (float, np.floating)):
        return f"{value:.6g}"
    return str(value)
