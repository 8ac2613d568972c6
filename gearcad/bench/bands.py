"""The certified band's cost (issue 33): CPU seconds of one warm ``pair_bands`` per example gear
pair, as drawn, cut by a laser and printed (FDM), with the positions the certificate measured and
its least play — the default theorem's (``output.certificate = "theorem"``), and the estimate's
(``"estimate"``: ``estimate_s``, ``estimate_n``, ``estimate_mm``) on the same design — beside the
sampled band (one position a driver tooth, no bound between them: ``sampled_s``).  ``seconds`` is
the band as the report gives it, its least pinned down; ``verdict_s`` its share until the verdict
is proven (what each cut of the backlash search pays, :func:`~..fitting.prove.prove_lazily`).

The goal: the laser focus pair's proven band in at most 1 s of CPU, warm.  CPU time of this process (both
threads of the band's cases), not the wall clock: a shared machine's load stretches the latter.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

from ..fitting import design
from ..fitting.band import pair_band
from ..fitting.fit import pair_bands
from ..fitting.pair_geometry import pair_geometry
from ..profiles import load_profile
from .commands import PROFILES

__all__ = ["BAND_GOALS", "PAIRS", "bands_table", "bench_bands"]

PAIRS = ("elliptic_focus", "oval_centre", "elliptic_centre", "spur_pair", "walker", "herringbone_elliptic")
BAND_GOALS = {("elliptic_focus", "laser"): 1.0}
"""CPU seconds a warm band may take."""
_QUICK = {"output.charts": False, "output.animation": False}


def bench_bands(quick: bool = False, step: Callable[[str], None] | None = None) -> list[dict]:
    """One row per (pair, process): CPU seconds of the warm band under each certificate (the
    theorem, the default, and the estimate, on the same design: the backlash the default chose),
    positions, least play, whether proven (``quick``: the laser focus pair, the theorem only)."""
    rows = []
    cases = [("elliptic_focus", "laser")] if quick else [(p, k) for p in PAIRS for k in ("none", "laser", "fdm")]
    for name, kind in cases:
        sets = {**_QUICK, **({"process.kind": kind} if kind != "none" else {})}
        made = design(load_profile(PROFILES / f"{name}.toml", sets))
        pair_bands(made)  # warm
        start = time.process_time()
        (band,) = pair_bands(made)
        verdict = time.process_time() - start  # settled: fits or jams, proven
        band = band.pinned()  # and the least pinned down, as the report gives it
        seconds = time.process_time() - start
        sampled = _seconds(made, None)
        other = None if quick else _seconds(made, "estimate")
        goal = BAND_GOALS.get((name, kind))
        cert = band.certificate
        rows.append(
            {
                "study": "bands",
                "method": f"{name} {kind}",
                "n": cert.positions if cert else 0,
                "seconds": seconds,
                "per_second": 1 / seconds if seconds else float("inf"),
                "least_mm": band.least,
                "verdict_s": verdict,
                "sampled_s": sampled,
                "proven": bool(cert and cert.proven),
                **({} if other is None else {"estimate_s": other[0], "estimate_n": other[1], "estimate_mm": other[2]}),
                "goal": f"s ≤ {goal:g}" if goal else "",
                "met": seconds <= goal if goal else None,
            }
        )
        if step is not None:
            step(f"band {name} {kind}")
    return rows


def _seconds(made, certificate: str | None):
    """CPU seconds of the band measured another way: None, sampled (one position a driver tooth,
    no certificate; warm); "estimate" or "theorem", (seconds, positions, least play, proven) under
    that certificate (the default's run warmed the geometry)."""
    params, process = made.params, made.params.process
    g = pair_geometry(made)
    kw = {
        "edge": process.edge(params.output.chamfer),
        "spread": process.center_spread(),
        "tol": params.output.tolerance,
        "backlash": params.teeth.backlash,
    }
    if certificate is None:
        g = replace(g, at=None, ratio=None)
        pair_band(g, **kw)
    start = time.process_time()
    band = pair_band(g, **kw, certificate=certificate or "theorem")
    seconds = time.process_time() - start
    if certificate is None:
        return seconds
    cert = band.certificate
    return seconds, cert.positions if cert else 0, band.least, bool(cert and cert.proven)


def bands_table(rows: list[dict]) -> list[str]:
    """The rows as lines: pair and process; the theorem's CPU seconds, positions, least play and
    whether proven; the sampled band's seconds; the estimate's seconds, positions and least play."""
    return [
        f"{r['method']:28s} theorem {r['seconds']:7.3f} s (verdict {r.get('verdict_s', r['seconds']):.3f} s)"
        f" {r['n']:5d} pos {r['least_mm'] * 1000:+8.2f} µm {'proven' if r['proven'] else 'OPEN'}"
        f"  sampled {r['sampled_s']:.3f} s"
        + (
            f"  estimate {r['estimate_s']:7.3f} s {r['estimate_n']:5d} pos {r['estimate_mm'] * 1000:+8.2f} µm"
            f" (theorem {r['seconds'] / max(r['estimate_s'], 1e-9):.1f}x)"
            if "estimate_s" in r
            else ""
        )
        + (f"  ({r['goal']}: {'met' if r['met'] else 'MISSED'})" if r["goal"] else "")
        for r in rows
        if r["study"] == "bands"
    ]
