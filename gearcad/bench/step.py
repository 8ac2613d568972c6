"""Study "step": the 41-tooth focus pair's two STEP files at the profile's tolerance (``--quick``:
0.01 mm) — write time and sizes against issue 21's goal (both in ≤ 2 s together, each ≤ 1 MB)."""

from __future__ import annotations

from pathlib import Path

from .commands import PROFILES
from .timing import Timing, time_once

__all__ = ["STEP_GOAL_SECONDS", "STEP_GOAL_BYTES", "bench_step", "step_lines"]

STEP_GOAL_SECONDS = 2.0
"""Both parts' STEP files written in at most this, s."""
STEP_GOAL_BYTES = 1_000_000
"""Each at most this large, bytes."""


def bench_step(quick: bool, folder: Path) -> list[dict]:
    """One row: the solids made and written for both gears (fastest and median of 5 rounds after
    a first call, which also loads OpenCASCADE; ``quick``: that first call), the files' sizes and
    faces, the goal met or not."""
    import time

    import gearcad

    from ..export.step import write_part_step
    from ..profiles import load_profile

    quiet = ['output.formats=["step"]', "output.charts=false", "output.animation=false"]
    params = load_profile(PROFILES / "elliptic_focus.toml", quiet + (["output.tolerance=0.01"] if quick else []))
    design = gearcad.design(params)
    folder.mkdir(parents=True, exist_ok=True)
    names = [p.name for p in design.parts()]

    def write_both() -> list[dict]:
        return [write_part_step(design, name, folder)[1] for name in names]

    start = time.perf_counter()
    entries = write_both()
    first = time.perf_counter() - start
    timing = Timing(first, first, entries) if quick else time_once(write_both, 5)  # quick: the first call only
    sizes = [e["bytes"] for e in entries]
    faces = {k: sum(e["faces"].get(k, 0) for e in entries) for k in ("plane", "cylinder", "cone", "bspline")}
    return [
        {
            "study": "step",
            "method": f"focus pair, {len(names)} STEP files ({', '.join(names)})",
            "n": params.output.tolerance,
            "seconds": timing.best,
            "seconds_median": timing.median,
            "seconds_first": first,
            "error": params.output.tolerance,
            "bytes": max(sizes),
            "bytes_total": sum(sizes),
            "faces": sum(faces.values()),
            **{f"faces_{k}": v for k, v in faces.items()},
            "goal_seconds": STEP_GOAL_SECONDS,
            "goal_bytes": STEP_GOAL_BYTES,
            "met": timing.best <= STEP_GOAL_SECONDS and max(sizes) <= STEP_GOAL_BYTES,
        }
    ]


def step_lines(rows: list[dict]) -> list[str]:
    """The STEP row as one line for the bench's summary."""
    out = []
    for r in rows:
        if r["study"] == "step":
            out.append(
                f"STEP: {r['method']}: {r['seconds']:.2f} s together (median {r['seconds_median']:.2f} s, first "
                f"{r['seconds_first']:.2f} s with OpenCASCADE's import; goal ≤ {r['goal_seconds']:g} s), "
                f"{r['bytes'] / 1e6:.2f} MB the larger (goal ≤ {r['goal_bytes'] / 1e6:g} MB), {r['faces']} faces "
                f"({r['faces_cylinder']} cylinders, {r['faces_plane']} planes): {'met' if r['met'] else 'not met'}"
            )
    return out
