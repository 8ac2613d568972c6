"""Whole builds, one fresh process each (charts and animation off): every profile, and a spur
pair of growing tooth count (the pinion has z teeth, the gear 2z).  A quick run builds only the
spur pair as written (z = 20): one build, and the one point of the scaling."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from .commands import PROFILES
from .process import cli_command, run_child

__all__ = ["bench_builds"]

_NO_PICTURES = ["--set", "output.charts=false", "--set", "output.animation=false"]


def _row(study: str, method: str, n: int, run) -> dict:
    return {
        "study": study,
        "method": method,
        "n": n,
        "seconds": run.calls[0],
        "seconds_whole": run.wall,
        "error": 0.0,
        "peak_mb": run.peak_mb,
    }


def bench_builds(quick: bool, folder: Path, step: Callable[[str], None] | None = None) -> list[dict]:
    """``seconds``: the build in its process after ``import gearcad.cli`` (lazy imports
    included); ``seconds_whole``: the process from start to exit."""
    rows = []
    profiles = [PROFILES / "spur_pair.toml"] if quick else sorted(PROFILES.glob("*.toml"))
    for profile in profiles:
        argv = ["build", str(profile), *_NO_PICTURES, "--out", str(folder / "builds" / "out")]
        rows.append(_row("build", profile.stem, 0, run_child(cli_command(profile.stem, argv, folder / "builds"))))
        if step:
            step(f"build {profile.stem}")
    if quick:
        rows.append({**rows[0], "study": "teeth-scaling", "method": "spur pair, module 2", "n": 20})
    for z in [] if quick else [10, 20, 40, 80, 160, 400]:
        sets = [f"teeth.count={z}", f"gear1.radius={z}", "output.sheet=[5000, 5000]", "output.bed=[5000, 5000]"]
        argv = ["build", str(PROFILES / "spur_pair.toml"), *_NO_PICTURES, "--out", str(folder / "scaling" / "out")]
        for value in sets:
            argv[2:2] = ["--set", value]
        run = run_child(cli_command(f"spur z={z}", argv, folder / "scaling"))
        rows.append(_row("teeth-scaling", "spur pair, module 2", z, run))
    if step:
        step("scaling with teeth")
    return rows
