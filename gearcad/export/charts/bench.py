"""Charts of ``gearcad bench``: speed against accuracy, output size, builds, stability."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from .png import save_png, subplots

__all__ = ["speed_accuracy", "speed_accuracy_figure", "output_size", "builds", "stability"]


def _ordered(points: list[tuple[float, float, float, float]]) -> list[tuple[float, float, float, float]]:
    """(parameter, best, median, error) in the order of more work: tolerances from coarse to fine,
    counts from few to many (joining points by time instead zigzags wherever timing is noisy)."""
    tolerances = all(0 < p[0] < 1 for p in points)
    return sorted(points, key=lambda p: -p[0] if tolerances else p[0])


def _log_ticks(axis) -> None:
    """Log ticks at 1, 2 and 5 per decade labelled as plain numbers; no labelled minor ticks
    (matplotlib labels minor ticks on a short range, and they ran into each other)."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0), numticks=12))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def speed_accuracy_figure(rows: list[dict]):
    """The figure: one panel per study, time (fastest round, and a bar to the median round)
    against error, points joined in the order of their parameter."""
    studies = [s for s in dict.fromkeys(r["study"] for r in rows) if s == "quadrature" or s.startswith("envelope")]
    fig, axes = subplots(1, len(studies), figsize=(5.4 * len(studies), 4.8))
    for ax, study in zip(np.atleast_1d(axes), studies):
        chosen = [r for r in rows if r["study"] == study]
        for k, method in enumerate(dict.fromkeys(r["method"] for r in chosen)):
            pts = _ordered(
                [
                    (r["n"], r["seconds"] * 1000, r.get("seconds_median", r["seconds"]) * 1000, max(r["error"], 1e-17))
                    for r in chosen
                    if r["method"] == method
                ]
            )
            n, best, median, err = (np.array(v) for v in zip(*pts))
            many = len(pts) > 1
            ax.loglog(best, err, "o-" if many else "*", ms=5 if many else 14, label=method, color=f"C{k}")
            ax.errorbar(best, err, xerr=[np.zeros_like(best), median - best], fmt="none", ecolor=f"C{k}", alpha=0.35)
            if study.startswith("envelope"):
                for x, y, p in zip(best, err, n):
                    text = f"{p:.0e}".replace("e-0", "e-") if p < 1 else f"N={p:g}"
                    ax.annotate(text, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6, color=f"C{k}")
        _log_ticks(ax.xaxis)
        times = [1000 * r[k] for r in chosen for k in ("seconds", "seconds_median") if k in r]
        ax.set_xlim(min(times) / 1.25, max(times) * 1.4)  # room for the labels of the outermost points
        ax.set_xlabel("time, ms (fastest of interleaved rounds; bar: to the median)")
        ax.set_ylabel("error (rad)" if study == "quadrature" else "largest deviation from the 1e-6 mm cut, mm")
        ax.set_title(study)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.suptitle("speed against accuracy (lower left is better)")
    fig.tight_layout()
    return fig


def speed_accuracy(rows: list[dict], path: Path) -> None:
    save_png(speed_accuracy_figure(rows), path)


def output_size(rows: list[dict], path: Path) -> None:
    chosen = [r for r in rows if r["study"] == "output"]
    fig, (a, b) = subplots(1, 2, figsize=(11, 4.4))
    for k, method in enumerate(dict.fromkeys(r["method"] for r in chosen)):
        pts = sorted(
            (r["n"], r.get("vertices", r.get("triangles")), r["bytes"]) for r in chosen if r["method"] == method
        )
        tol, count, size = zip(*pts)
        a.loglog(tol, count, "o-", label=f"{method} ({'triangles' if method == 'STL' else 'vertices'})", color=f"C{k}")
        b.loglog(tol, np.array(size) / 1024, "o-", label=method, color=f"C{k}")
    a.set_ylabel("vertices or triangles per file, count")
    b.set_ylabel("file size, KiB")
    for ax in (a, b):
        ax.set_xlabel("tolerance, mm")
        ax.invert_xaxis()
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle("output size of one 41-tooth elliptic gear against tolerance")
    fig.tight_layout()
    save_png(fig, path)


def builds(rows: list[dict], path: Path) -> None:
    chosen = [r for r in rows if r["study"] == "build"]
    scaling = sorted((r["n"], r["seconds"], r["peak_mb"]) for r in rows if r["study"] == "teeth-scaling")
    fig, (a, b) = subplots(1, 2, figsize=(12, 4.6))
    names = [r["method"] for r in chosen]
    a.barh(names, [r["seconds"] for r in chosen], color="C0")
    for k, r in enumerate(chosen):
        a.text(r["seconds"], k, f" {r['peak_mb']:.0f} MB", va="center", fontsize=7)
    a.set_xlabel("build in its own process without charts, s (peak memory beside)")
    z, t, mb = zip(*scaling)
    b.plot(z, t, "o-", label="time, s")
    if len(z) > 1:
        slope = np.polyfit(z, t, 1)
        b.plot(z, np.polyval(slope, z), "--", color="0.5", label=f"linear fit: {1000 * slope[0]:.1f} ms per tooth")
    b.set_xlabel("teeth on the pinion (spur pair, module 2; the gear has twice as many)")
    b.set_ylabel("build time, s")
    b2 = b.twinx()
    b2.plot(z, mb, "s:", color="C3", label="peak memory, MB")
    b2.set_ylabel("MB")
    b.legend(loc="upper left", fontsize=8)
    b2.legend(loc="lower right", fontsize=8)
    for ax in (a, b):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save_png(fig, path)


def stability(rows: list[dict], path: Path) -> None:
    fig, ax = subplots(figsize=(11, 0.32 * len(rows) + 1.2))
    colours = {"ok": "C2", "warning": "C1", "error": "C3"}
    for k, r in enumerate(rows):
        kind = r["outcome"].split(":")[0]
        ax.barh(k, 1, color=colours[kind])
        text = f"{r['case']} = {r['value']:g}: {r['outcome']}"
        ax.text(0.01, k, text if len(text) < 150 else text[:147] + "…", va="center", fontsize=7)
    ax.set_yticks([])
    ax.set_xticks([])
    ax.invert_yaxis()
    ax.set_title("stability map: ok (green), warning (orange), clear error (red)")
    fig.tight_layout()
    save_png(fig, path)
