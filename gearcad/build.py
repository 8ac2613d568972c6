"""Build profiles into folders of files, atomically.

Everything is written into a staging folder beside the output folder and moved into place
only when every profile has built; on any error the output folder is left as it was.
"""

from __future__ import annotations

import csv
import shutil
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .design import DesignData, design
from .errors import GearcadError, ProfileError
from .export import charts
from .export.dxf import cross, write_dxf
from .export.report import write_report
from .pitch.discretize import polyline
from .profiles import GearPairParams
from .teeth.pair import ToothedPairData, cut_pair
from .tolerances import DEFAULT

__all__ = ["BuildResult", "build_profile", "build_all"]


@dataclass(frozen=True)
class BuildResult:
    name: str
    data: DesignData
    teeth: ToothedPairData | None
    files: dict[str, dict]
    seconds: float


def _file_entry(path: Path, **counts) -> dict:
    return {"bytes": path.stat().st_size, **counts}


def _write_kinematics_csv(data: DesignData, path: Path) -> None:
    k = data.kinematics
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(
            ["driver_angle_rad", "follower_angle_rad", "ratio", "follower_speed_rad_s", "follower_acceleration_rad_s2"]
        )
        for row in zip(k.driver_angle, k.follower_angle, k.ratio, k.speed, k.acceleration):
            w.writerow([f"{v:.12g}" for v in row])


def build_profile(params: GearPairParams, folder: Path) -> BuildResult:
    """Design one profile and write its files into ``folder`` (which must exist)."""
    start = time.perf_counter()
    tol = replace(DEFAULT, outline_mm=params.output.tolerance)
    data = design(params, tol=tol)
    teeth = cut_pair(data, params.teeth, tol=tol) if params.teeth is not None else None
    pitch = [polyline(g.curve, tol.outline_mm) for g in data.gears]
    files: dict[str, dict] = {}
    mark = 0.05 * min(g.r_min for g in data.gears)
    for i, (gear, ring) in enumerate(zip(data.gears, pitch)):
        path = folder / f"{gear.name}.dxf"
        cut = {"CUT": [teeth.gears[i].outline.outer]} if teeth else {}
        n = write_dxf(path, {**cut, "MARK": [ring]}, {"MARK": cross((0.0, 0.0), mark)})
        files[path.name] = _file_entry(path, vertices=n, kind="dxf", part=gear.name)
    path = folder / "pair.dxf"
    placed = [ring + np.asarray(g.pivot) for g, ring in zip(data.gears, pitch)]
    cut = {"CUT": [t.outline.outer + np.asarray(g.pivot) for g, t in zip(data.gears, teeth.gears)]} if teeth else {}
    n = write_dxf(path, {**cut, "MARK": placed}, {"MARK": [s for g in data.gears for s in cross(g.pivot, mark)]})
    files[path.name] = _file_entry(path, vertices=n, kind="dxf", part="assembly")
    path = folder / "kinematics.csv"
    _write_kinematics_csv(data, path)
    files[path.name] = _file_entry(path, kind="csv", rows=len(data.kinematics.driver_angle))
    if params.output.charts:
        charts_to_draw = [
            ("pitch_curves.png", lambda p: charts.pitch_chart(data, p, pitch)),
            ("kinematics.png", lambda p: charts.kinematics_chart(data, p)),
        ]
        if teeth:
            charts_to_draw.append(("mesh.png", lambda p: charts.mesh_chart(data, teeth, p)))
        for name, draw in charts_to_draw:
            draw(folder / name)
            files[name] = _file_entry(folder / name, kind="png")
    files["report.json"] = {"kind": "json"}
    write_report(data, teeth, files, folder / "report.json")
    return BuildResult(params.name, data, teeth, files, time.perf_counter() - start)


def build_all(
    profiles: list[GearPairParams], out: Path, progress: Callable[[int, int, BuildResult], None] = None
) -> list[BuildResult]:
    """Build every profile into ``out/<name>/``; all or nothing."""
    out = Path(out)
    names = [p.name for p in profiles]
    duplicates = {n for n in names if names.count(n) > 1}
    if duplicates:
        raise ProfileError(f"name = {sorted(duplicates)[0]!r}: two profiles build into the same folder")
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}-staging-", dir=out.parent))
    try:
        results = []
        for n, params in enumerate(profiles, 1):
            folder = staging / params.name
            folder.mkdir()
            try:
                result = build_profile(params, folder)
            except GearcadError as exc:
                raise type(exc)(f"{params.name}: {exc}") from None
            results.append(result)
            if progress:
                progress(n, len(profiles), result)
        out.mkdir(exist_ok=True)
        for params in profiles:
            target = out / params.name
            if target.exists():
                target.rename(staging / f".previous-{params.name}")
            (staging / params.name).rename(target)
        return results
    finally:
        shutil.rmtree(staging, ignore_errors=True)
