"""SVG files for laser software (LightBurn, Glowforge, xTool, Inkscape): 1 user unit = 1 mm.

Cut rings go into a red group, marks (pitch curve, pivot cross) into a blue one, each an
Inkscape layer.  Every closed ring is one closed path whose bulged segments are exact SVG
elliptical arcs (circles), so the laser follows the same arcs as from the DXF.  The writer
takes the drawing as built (kerf already applied) and only encodes it.
"""

from __future__ import annotations

import math
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from ..geometry import bulge as B
from ..geometry.arcfit import ArcRing
from .bounds import drawing_bounds
from .drawing import Drawing

__all__ = [
    "num",
    "ring_path",
    "stroke_path",
    "MARGIN_MM",
    "CUT_COLOUR",
    "MARK_COLOUR",
    "STROKE_WIDTH_MM",
    "PREVIEW_STYLE",
    "write_svg",
]

MARGIN_MM = 1.0
"""Empty border around the drawing, so no path lies on the page edge."""
CUT_COLOUR = "#ff0000"
MARK_COLOUR = "#0000ff"
"""Pure red cuts and pure blue marks: the colours laser software maps to cut and engrave/score."""
STROKE_WIDTH_MM = 0.01
"""A hairline.  LightBurn, Glowforge and xTool sort paths by colour and ignore the width, but the
Epilog and Universal print drivers cut only strokes at most 0.001 in (0.0254 mm) wide and raster
anything wider; 0.01 mm is below that everywhere.  Previews get a visible line from
:data:`PREVIEW_STYLE` instead of a wider stroke, which importers would then engrave instead of cut."""

PREVIEW_STYLE = "@media screen { path { vector-effect: non-scaling-stroke; stroke-width: 1px; } }"
"""How a browser or image viewer shows the file: one screen pixel wide whatever the zoom, so a
whole sheet's hairlines do not vanish in a preview.  A style rule for screens only: the hairline
attribute stays what laser software and print drivers read (Inkscape and laser importers do not
apply ``@media`` rules)."""

_DECIMALS = 6  # 1 nm: far below any laser's resolution, and fixed so the bytes are reproducible
_MIN_SWEEP = 1e-5
"""Arcs of a smaller sweep (rad) are written as lines.  Readers that follow the SVG
implementation notes take the sweep from arccos(u·v), which loses about ε/θ of it (ε = 1.1e-16)
and misplaces the arc's far end by chord·ε/θ²; a line strays by the sagitta, chord·θ/8.  The two
meet near 1e-5 rad, both about 1.2e-6 of the chord (0.12 µm on a 100 mm chord).  Fitted arcs
(sagitta above the outline tolerance) have larger sweeps."""
_INKSCAPE = "http://www.inkscape.org/namespaces/inkscape"


def num(value: float) -> str:
    """Fixed-point, at most six decimals, trailing zeros dropped, never ``-0``."""
    text = f"{value:.{_DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _xy(point) -> str:
    return f"{num(point[0])} {num(-point[1])}"  # SVG's y axis points down


def _arcs(a: np.ndarray, b: np.ndarray, bulge: float) -> list[str]:
    """SVG arc commands for the segment a → b with bulge ``tan(θ/4)``.

    The radius is ``chord / (2 |sin(θ/2)|)`` (:mod:`gearcad.geometry.bulge`).  A counter-clockwise arc (b > 0) in y-up
    coordinates runs the negative way in SVG's y-down ones: sweep-flag 0.  An SVG arc is fixed
    by its radius, and near a half turn the radius hardly changes while the arc does (a radius
    rounded to the last digit can move the arc's middle by far more than that digit, and
    importers that find the radius below half the chord silently enlarge it); so arcs of more
    than a quarter turn are written as equal pieces of at most a quarter turn, through points
    of the same circle.  No piece is then a large arc.
    """
    theta = float(B.sweep(bulge))
    centres, radii = B.centres(a[None], b[None], np.array([theta]))
    return _arc_pieces(a, b, bulge, theta, centres[0], float(radii[0]))


def _arc_pieces(
    a: np.ndarray, b: np.ndarray, bulge: float, theta: float, centre: np.ndarray, radius: float
) -> list[str]:
    """:func:`_arcs` with the arc's sweep ``theta``, centre and radius already worked out."""
    radius = num(radius)
    pieces = max(1, math.ceil(abs(theta) / (math.pi / 2) * (1 - 1e-12)))
    ends = [b]
    if pieces > 1:  # here |bulge| > tan(π/8): the centre is well defined
        turns = theta * np.arange(1, pieces) / pieces
        c, s = np.cos(turns), np.sin(turns)
        r = a - centre
        ends = [*(centre + np.column_stack([c * r[0] - s * r[1], s * r[0] + c * r[1]])), b]
    return [f"A {radius} {radius} 0 0 {int(bulge < 0)} {_xy(p)}" for p in ends]


def ring_path(ring) -> tuple[str, int]:
    """Path data of one closed ring and its segment count (lines, arc pieces, closing line)."""
    v, bulges = B.segments(ring)
    n = len(v)
    ends = np.roll(v, -1, axis=0)
    sweeps = B.sweep(bulges)
    # an arc whose sagitta is below the written resolution is a line at that resolution
    curved = (np.hypot(*(ends - v).T) * np.abs(bulges) / 2 >= 0.5 * 10.0**-_DECIMALS) & (np.abs(sweeps) >= _MIN_SWEEP)
    arcs = np.flatnonzero(curved)
    centres, radii = B.centres(v[arcs], ends[arcs], sweeps[arcs])  # every arc's at once
    circle = dict(zip(arcs.tolist(), range(len(arcs))))
    commands = [f"M {_xy(v[0])}"]
    closing_line = 0
    for k in range(n):
        if k in circle:
            j = circle[k]
            commands += _arc_pieces(v[k], ends[k], float(bulges[k]), float(sweeps[k]), centres[j], float(radii[j]))
        elif k < n - 1:
            commands.append(f"L {_xy(ends[k])}")
        else:
            closing_line = 1  # drawn by the Z
    return " ".join([*commands, "Z"]), len(commands) - 1 + closing_line


def stroke_path(stroke) -> tuple[str, int]:
    """Path data of one open polyline (or an ArcRing left open: dashes with arcs) and its segment count."""
    if isinstance(stroke, ArcRing):
        v, bulges = np.asarray(stroke.vertices, dtype=float), np.asarray(stroke.bulges, dtype=float)
        commands = [f"M {_xy(v[0])}"]
        for k in range(len(v) - 1):
            commands += _arcs(v[k], v[k + 1], float(bulges[k])) if bulges[k] != 0 else [f"L {_xy(v[k + 1])}"]
        return " ".join(commands), len(commands) - 1
    points = np.asarray(stroke, dtype=float)
    data = f"M {_xy(points[0])} " + " ".join(f"L {_xy(p)}" for p in points[1:])
    return data, len(points) - 1


def _group(drawing: Drawing, layer: str, group_id: str, colour: str) -> tuple[list[str], int]:
    # the style sits on every path as well as on the group: some laser importers do not
    # inherit presentation attributes from groups
    style = f'fill="none" stroke="{colour}" stroke-width="{num(STROKE_WIDTH_MM)}"'
    lines = [f'  <g id="{group_id}" inkscape:groupmode="layer" inkscape:label={quoteattr(layer)} {style}>']
    if layer in drawing.descriptions:
        lines.append(f"    <desc>{escape(drawing.descriptions[layer])}</desc>")
    count = 0
    encoded = [ring_path(r) for r in drawing.closed.get(layer, [])]
    encoded += [stroke_path(s) for s in drawing.strokes.get(layer, [])]
    for data, segments in encoded:
        lines.append(f'    <path {style} d="{data}"/>')
        count += segments
    lines.append("  </g>")
    return lines, count


def write_svg(
    path: Path,
    drawing: Drawing,
    *,
    cut_layer: str,
    mark_layer: str,
    title: str = "",
    page: tuple[float, float, float, float] | None = None,
) -> int:
    """Write the drawing as one SVG file in mm; return the number of path segments written.

    Parameters
    ----------
    path : Path
        The file to write (UTF-8; the same drawing always gives the same bytes).
    drawing : Drawing
        Closed rings (ArcRing or (n, 2) float, mm) and open strokes per layer, kerf applied.
    cut_layer, mark_layer : str
        The drawing's layer names for cut paths (red group ``cut``) and marks (blue group
        ``mark``); they become the Inkscape layer labels.
    title : str
        The document's ``<title>``.
    page : (xmin, ymin, xmax, ymax), mm, optional
        The page (a cutting sheet's size); default: the drawing's extents and :data:`MARGIN_MM`.

    Returns
    -------
    int
        Segments written: lines (the closing Z of a ring included when it draws one), arcs
        (one per bulge, two to four for bulges of more than a quarter turn) and stroke edges.

    Raises
    ------
    ValueError
        If the drawing has layers other than ``cut_layer`` and ``mark_layer``, or is empty.
    """
    extra = sorted({*drawing.closed, *drawing.strokes} - {cut_layer, mark_layer})
    if extra:
        raise ValueError(f"layers {extra} are neither cut_layer {cut_layer!r} nor mark_layer {mark_layer!r}")
    margin = MARGIN_MM if page is None else 0.0
    xmin, ymin, xmax, ymax = drawing_bounds(drawing) if page is None else page
    x0, y0 = num(xmin - margin), num(-ymax - margin)  # the top-left corner after the y flip
    # sizes from the corner as written, so each edge is off by one rounding at most
    width, height = num(xmax + margin - float(x0)), num(-ymin + margin - float(y0))
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="{_INKSCAPE}" version="1.1"',
        f'     width="{width}mm" height="{height}mm" viewBox="{x0} {y0} {width} {height}">',
        f"  <title>{escape(title)}</title>",
        f"  <style>{PREVIEW_STYLE}</style>",
    ]
    # marks first: laser software that runs groups in document order scores the part before
    # cutting it free, while it still lies where it was placed
    marks, n_marks = _group(drawing, mark_layer, "mark", MARK_COLOUR)
    cuts, n_cuts = _group(drawing, cut_layer, "cut", CUT_COLOUR)
    lines += marks + cuts + ["</svg>", ""]
    Path(path).write_bytes("\n".join(lines).encode("utf-8"))
    return n_marks + n_cuts
