"""The certified band's cost (issue 33): CPU seconds of one warm ``pair_bands`` per example gear
pair, as drawn, cut by a laser and printed (FDM), with the positions the certificate measured and
its least play, beside the sampled band it replaced (one position a driver tooth, no bound
between them: ``sampled_s``) — the issue's budget is 1.5 times that.

The goal: the laser focus pair's band in at most 1 s of CPU, warm.  CPU time of this process (both
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
    """One row per (pair, process): CPU seconds of the warm band, positions, least play
    (``quick``: the laser focus pair only)."""
    rows = []
    cases = [("elliptic_focus", "laser")] if quick else [(p, k) for p in PAIRS for k in ("none", "laser", "fdm")]
    for name, kind in cases:
        sets = {**_QUICK, **({"process.kind": kind} if kind != "none" else {})}
        made = design(load_profile(PROFILES / f"{name}.toml", sets))
        pair_bands(made)  # warm
        start = time.process_time()
        (band,) = pair_bands(made)
        seconds = time.process_time() - start
        goal = BAND_GOALS.get((name, kind))
        cert = band.certificate
        sampled = _sampled_seconds(made)
        rows.append(
            {
                "study": "bands",
                "method": f"{name} {kind}",
                "n": cert.positions if cert else 0,
                "seconds": seconds,
                "per_second": 1 / seconds if seconds else float("inf"),
                "least_mm": band.least,
                "proven": cert.proven if cert else None,
                "sampled_s": sampled,
                "goal": f"s ≤ {goal:g}" if goal else "",
                "met": seconds <= goal if goal else None,
            }
        )
        if step is not None:
            step(f"band {name} {kind}")
    return rows


def _sampled_seconds(made) -> float:
    """CPU seconds of the sampled band (one position a driver tooth, no certificate), warm."""
    params, process = made.params, made.params.process
    g = replace(pair_geometry(made), at=None, ratio=None)
    kw = {
        "edge": process.edge(params.output.chamfer),
        "spread": process.center_spread(),
        "tol": params.output.tolerance,
        "backlash": params.teeth.backlash,
    }
    pair_band(g, **kw)
    start = time.process_time()
    pair_band(g, **kw)
    return time.process_time() - start


def bands_table(rows: list[dict]) -> list[str]:
    """The rows as lines: pair and process, CPU seconds, positions, certified least play."""
    return [
        f"{r['method']:28s} {r['seconds']:7.3f} s  {r['n']:5d} positions  least {r['least_mm'] * 1000:+8.2f} µm"
        f"  {'proven' if r['proven'] else 'OPEN'}  sampled {r['sampled_s']:.3f} s"
        f" ({r['seconds'] / max(r['sampled_s'], 1e-9):.1f}x)"
        + (f"  ({r['goal']}: {'met' if r['met'] else 'MISSED'})" if r["goal"] else "")
        for r in rows
        if r["study"] == "bands"
    ]
