"""What ``gearcad bench`` writes and prints: CSV, markdown, the peers and goals tables."""

from __future__ import annotations

import csv
import math
from pathlib import Path

from .goals import goals_table

__all__ = ["write_csv", "markdown", "peers_table", "peer_ratios"]

_OWN_TABLES = ("peers", "goals", "stages", "front", "overhead", "throughput")


def write_csv(rows: list[dict], path: Path) -> None:
    keys = sorted({k for r in rows for k in r})
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def rows_of(rows: list[dict], study: str) -> list[dict]:
    return [r for r in rows if r["study"] == study]


def _mm(value) -> str:
    return "" if value is None or (isinstance(value, float) and math.isnan(value)) else f"{value:.1e}"


def peers_table(rows: list[dict]) -> list[str]:
    """gearcad and the peer side by side, as markdown table lines."""
    out = [
        "| tool | whole process (s) | CPU (s) | in process, first call (s) | in process, warm (s) | imports (s) "
        "| peak (MB) | vertices per outline (arcs) | deviation (mm): outline | flanks, tips | roots "
        "| vs rack cut | before DXF | runs |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["study"] != "peers":
            continue
        if "runs" not in r:  # the references against each other
            out.append(f"| {r['method']} | | | | | | | | {_mm(r['error'])} | | | | | |")
            continue
        warm = "" if math.isnan(r["seconds_warm"]) else f"{r['seconds_warm']:.2f}"
        out.append(
            f"| {r['method']} | {r['seconds']:.2f} | {r['seconds_cpu']:.2f} | {r['seconds_in_process']:.2f} | {warm} "
            f"| {r['seconds_imports']:.2f} | {r['peak_mb']:.0f} | {r['vertices']} ({r['arcs']}) "
            f"| {_mm(r['error'])} | {_mm(r['error_flanks'])} | {_mm(r['error_roots'])} "
            f"| {_mm(r.get('error_rack_cut'))} | {_mm(r.get('error_unsimplified'))} | {r['runs']} |"
        )
    return out


def peer_ratios(rows: list[dict]) -> list[str]:
    """How many times faster gearcad is than the peer, per gearcad configuration."""
    out = []
    for r in rows:
        if r["study"] == "peers" and "speedup" in r:
            warm = "" if math.isnan(r["speedup_warm"]) else f", warm in process {r['speedup_warm']:.1f}×"
            out.append(
                f"- {r['method']}: {r['speedup']:.1f}× faster than the peer whole-process, "
                f"{r['speedup_in_process']:.1f}× in process (first call){warm}"
            )
    return out


def markdown(rows: list[dict], stability: list[dict]) -> str:
    out = [
        "# gearcad benchmark",
        "",
        "| study | method | n / tol | time (ms) | median (ms) | error | extra |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["study"] in _OWN_TABLES:
            continue
        extra = ", ".join(
            f"{k} {r[k]:.0f}" if isinstance(r[k], float) else f"{k} {r[k]}"
            for k in ("vertices", "triangles", "bytes", "peak_mb")
            if k in r
        )
        median = f"{1000 * r['seconds_median']:.2f}" if "seconds_median" in r else ""
        out.append(
            f"| {r['study']} | {r['method']} | {r['n']:g} | {1000 * r['seconds']:.2f} | {median} "
            f"| {r['error']:.2e} | {extra} |"
        )
    if any(r["study"] == "peers" for r in rows):
        out += ["", "## Peers", "", *peers_table(rows), "", *peer_ratios(rows)]
    if any(r["study"] == "goals" for r in rows):
        out += [
            "",
            "## Goals (medians of whole-process runs)",
            "",
            *goals_table([r for r in rows if r["study"] == "goals"]),
        ]
    if any(r["study"] == "stages" for r in rows):
        from .stages import stages_table

        out += ["", "## Stages (warm, CPU time per design in process)", "", *stages_table(rows_of(rows, "stages"))]
    if any(r["study"] == "overhead" for r in rows):
        from .overhead import overhead_lines

        out += ["", "## A sweep's overhead per pitch-stage design (CPU)", "", *overhead_lines(rows)]
    if any(r["study"] == "throughput" for r in rows):
        from .cluster import throughput_lines

        out += [
            "",
            "## A sweep's throughput (wall, start-up included)",
            "",
            *throughput_lines(rows_of(rows, "throughput")),
        ]
    if any(r["study"] == "front" for r in rows):
        from .front import front_lines

        out += ["", "## The sweep's Pareto front (CPU seconds)", "", *front_lines(rows)]
    out += ["", "## Stability map", "", "| case | value | outcome | time (ms) |", "|---|---|---|---|"]
    out += [f"| {s['case']} | {s['value']:g} | {s['outcome']} | {1000 * s['seconds']:.0f} |" for s in stability]
    return "\n".join(out) + "\n"
