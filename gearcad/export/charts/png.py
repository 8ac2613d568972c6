"""The one PNG writer of the charts: matplotlib's Agg canvas without pyplot, no creation time.

Figures are made on their own Agg canvas at :data:`_DPI` (:func:`figure`, :func:`subplots`): no
pyplot figure manager, no registry of open figures to close.  matplotlib draws the figure;
Pillow encodes the pixels as 8-bit RGB (the charts are opaque: an alpha channel of 255 everywhere
is a quarter of the pixels' bytes to compress for nothing) at zlib level 3 (as small as
matplotlib's own RGBA files at level 6, in about half the time).

Every chart is audited as it is written: titles inside the canvas, legends clear of the data
(:func:`layout_problems`).  With ``GEARCAD_CHART_AUDIT`` naming a file, the problems found are
appended to it as JSON lines (the test suite reads them after building every profile).
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.category import StrCategoryFormatter
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from PIL import Image, PngImagePlugin

__all__ = ["figure", "subplots", "save_png", "layout_problems", "PolyCollection"]

_SOFTWARE = "gearcad"  # and no creation time: the same design gives the same bytes
_DPI = 110
_COMPRESS_LEVEL = 3
_AUDIT = "GEARCAD_CHART_AUDIT"


def figure(figsize: tuple[float, float]) -> Figure:
    """An empty figure of ``figsize`` inches on its own Agg canvas, at the dpi it is written at:
    ``tight_layout`` measures the text as it will be drawn, and the drawing finds it measured
    (at another dpi every title and tick label was measured twice, once for each)."""
    fig = Figure(figsize=figsize, dpi=_DPI)
    FigureCanvasAgg(fig)
    return fig


def subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float], **kwargs):
    """``(figure, axes)`` as ``matplotlib.pyplot.subplots`` makes them (``kwargs``: ``sharex``,
    ``squeeze``, ``gridspec_kw`` ...), the figure on its own Agg canvas."""
    fig = figure(figsize)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def _titles(fig) -> list:
    texts = [fig._suptitle] if fig._suptitle is not None else []
    for ax in fig.axes:
        texts += [ax.title, ax._left_title, ax._right_title]
    return [t for t in texts if t.get_visible() and t.get_text().strip()]


_UNIT = re.compile(r"[,(]\s*\S|\b(in|per)\s+\S|\S\s*/\s*\S")
"""What gives an axis its unit: ", mm", "(rad)", "in mm", "per turn", or a ratio "a / R"."""


def _unit_problems(ax) -> list[str]:
    """An axis with numbered ticks and no label, or a label with no unit (after a comma, in
    brackets, after "in" or "per", or a ratio to a named quantity)."""
    if not ax.axison:
        return []
    problems = []
    for name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
        numbered = axis.get_visible() and any(t.get_visible() and t.get_text() for t in axis.get_ticklabels())
        if not numbered or isinstance(axis.get_major_formatter(), StrCategoryFormatter):  # names, not numbers
            continue
        label = axis.get_label_text().strip()
        if not label or not _UNIT.search(label):
            problems.append(f"{name} axis of {ax.get_title()[:40]!r} has no unit ({label!r})")
    return problems


def layout_problems(fig) -> list[str]:
    """What a reader would trip on in a drawn figure: a title cut by the canvas's edge, a legend
    drawn over data points of its own axes (lines and scatter points), a figure legend off the
    canvas or over a plot, a numbered axis without a unit."""
    renderer = fig.canvas.get_renderer()
    width, height = fig.bbox.width, fig.bbox.height
    problems = []
    for text in _titles(fig):
        box = text.get_window_extent(renderer)
        if box.x0 < -0.5 or box.y0 < -0.5 or box.x1 > width + 0.5 or box.y1 > height + 0.5:
            problems.append(f"title {text.get_text()[:40]!r} runs off the canvas")
    for legend in fig.legends:
        box = legend.get_window_extent(renderer)
        if box.x0 < -0.5 or box.y0 < -0.5 or box.x1 > width + 0.5 or box.y1 > height + 0.5:
            problems.append("the figure's legend runs off the canvas")
        if any(box.overlaps(ax.get_window_extent(renderer)) for ax in fig.axes):
            problems.append("the figure's legend lies over a plot")
    for ax in fig.axes:
        problems += _unit_problems(ax)
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        box = legend.get_window_extent(renderer)
        points = [
            line.get_xydata() for line in ax.get_lines() if line.get_visible() and line.get_label() != "_nolegend_"
        ]
        points += [c.get_offsets() for c in ax.collections if c.get_visible() and len(c.get_offsets()) > 1]
        points = [np.asarray(p, dtype=float) for p in points if len(p)]
        if not points:
            continue
        xy = ax.transData.transform(np.vstack(points))
        inside = (xy[:, 0] > box.x0) & (xy[:, 0] < box.x1) & (xy[:, 1] > box.y0) & (xy[:, 1] < box.y1)
        if np.count_nonzero(inside):
            problems.append(f"legend of {ax.get_title()[:40]!r} covers {np.count_nonzero(inside)} data points")
    return problems


def _write_png(fig, path: Path) -> None:
    """Draw the figure at :data:`_DPI` (the dpi :func:`figure` gives it; the audit measures what
    was drawn) and write its pixels with Pillow: RGB where every pixel is opaque (every chart),
    else RGBA, at zlib level :data:`_COMPRESS_LEVEL`."""
    fig.set_dpi(_DPI)
    fig.canvas.draw()
    image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba()))
    if image.getextrema()[3] == (255, 255):
        image = image.convert("RGB")
    info = PngImagePlugin.PngInfo()
    info.add_text("Software", _SOFTWARE)
    image.save(path, format="png", pnginfo=info, dpi=(_DPI, _DPI), compress_level=_COMPRESS_LEVEL)


def save_png(fig, path: Path) -> None:
    """Write a figure without a creation time (the same chart gives the same bytes)."""
    _write_png(fig, path)
    audit = os.environ.get(_AUDIT)
    if audit:
        with open(audit, "a", encoding="utf-8") as f:
            f.write(
                json.dumps({"file": f"{Path(path).parent.name}/{Path(path).name}", "problems": layout_problems(fig)})
                + "\n"
            )
