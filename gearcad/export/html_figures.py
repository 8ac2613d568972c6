"""Inline SVG figures of a design for the HTML report: parts, assembly, sheet and plate.

Each part's cut and mark paths are defined once per page (``defs``), in the encoding of
:mod:`gearcad.export.svg` (the same arcs as the SVG files), and every figure places them with
``<use>``.  The page's stylesheet fills and strokes them (hairlines that stay visible at any
zoom); the pivots are pointed at by four green ticks, drawn only here.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from html import escape

import numpy as np

from ..mechanisms import Design, Placement
from .drawing import cross
from .html_style import FILLS
from .svg import num, ring_path, stroke_path

__all__ = ["Figures"]


class Figures:
    """Each part's cut and mark paths as SVG path data, defined once in the page."""

    def __init__(self, design: Design):
        self.design = design
        self.parts = {p.name: p for p in design.parts()}
        self.index = {name: k for k, name in enumerate(self.parts)}
        self.reach = {name: float(np.hypot(*p.outline.outer.T).max()) for name, p in self.parts.items()}

    def defs(self) -> str:
        lines = ['<svg width="0" height="0" style="position:absolute" aria-hidden="true" focusable="false"><defs>']
        for name, part in self.parts.items():
            k = self.index[name]
            cut = " ".join(ring_path(r)[0] for r in part.cut)
            lines.append(f'<path id="cut{k}" fill-rule="evenodd" vector-effect="non-scaling-stroke" d="{cut}"/>')
            marks = [ring_path(r)[0] for r in part.mark]
            if part.pivot_mark > 0:
                marks += [stroke_path(s)[0] for s in cross((0.0, 0.0), part.pivot_mark)]
            if marks:
                d = " ".join(marks)
                lines.append(f'<path id="mark{k}" fill="none" vector-effect="non-scaling-stroke" d="{d}"/>')
        lines.append("</defs></svg>")
        return "\n".join(lines)

    def view(
        self,
        placements: Iterable[Placement],
        bounds,
        *,
        label: str,
        frame: tuple[float, float] | None = None,
    ) -> str:
        """An inline ``<svg>`` of the placed parts (mm, y up), each pivot between four green ticks.

        ``frame`` = (w, h) draws a sheet or bed from the origin and shows all of it."""
        xmin, ymin, xmax, ymax = bounds
        size = max(xmax - xmin, ymax - ymin)
        pad = 0.04 * size
        x0, y0 = xmin - pad, -ymax - pad
        w, h = xmax - xmin + 2 * pad, ymax - ymin + 2 * pad
        body = []
        if frame is not None:
            body.append(
                f'<rect class="frame" x="0" y="{num(-frame[1])}" width="{num(frame[0])}" '
                f'height="{num(frame[1])}" vector-effect="non-scaling-stroke"/>'
            )
        pivots = []
        for pl in placements:
            r = min(0.02 * size, 0.15 * self.reach[pl.part])  # stays inside small parts
            k = self.index[pl.part]
            move = f"translate({num(pl.offset[0])} {num(-pl.offset[1])}) rotate({num(-math.degrees(pl.angle))})"
            body.append(f'<use href="#cut{k}" class="part f{k % FILLS}" transform="{move}"/>')
            part = self.parts[pl.part]
            if part.mark or part.pivot_mark > 0:
                body.append(f'<use href="#mark{k}" class="mark" transform="{move}"/>')
            px, py = num(pl.offset[0]), num(-pl.offset[1])
            a, b = num(r), num(2.4 * r)  # four ticks pointing at the pivot, leaving its bore and cross in view
            pivots.append(
                f'<path class="pv" transform="translate({px} {py})" vector-effect="non-scaling-stroke" '
                f'd="M -{b} 0 H -{a} M {a} 0 H {b} M 0 -{b} V -{a} M 0 {a} V {b}"/>'
            )
        return (
            f'<svg viewBox="{num(x0)} {num(y0)} {num(w)} {num(h)}" preserveAspectRatio="xMidYMid meet" '
            f'role="img" aria-label="{escape(label)}"><title>{escape(label)}</title>'
            + "".join(body + pivots)
            + "</svg>"
        )
