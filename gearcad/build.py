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
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import shapely
import shapely.geometry

from .arcfit import ArcRing, decimate, fit_arcs
from .design import DesignData, design
from .errors import GearcadError, ProfileError
from .export import charts
from .export.animation import frames_for, write_gif
from .export.dxf import Drawing, cross, write_dxf
from .export.mesh import Solid, SolidItem, extrude, write_3mf, write_stl
from .export.report import write_report
from .outline import Outline, arc_steps
from .parts import with_bore
from .pitch.discretize import polyline
from .profiles import GearPairParams, OutputParams
from .teeth.pair import ToothedPairData, cut_pair
from .tolerances import DEFAULT

__all__ = ["Part", "BuildResult", "build_profile", "build_any", "build_all", "part_drawing", "pair_summary"]


@dataclass(frozen=True)
class Part:
    """One gear as a part: its cut shape at the tolerance (and finer, for DXF arcs)."""

    name: str
    pivot: tuple[float, float]
    outline: Outline
    fine: Outline
    pitch: np.ndarray
    pitch_fine: np.ndarray

    def arcs(self, kerf: float, tolerance: float) -> tuple[list[ArcRing], ArcRing]:
        """Cut rings and pitch curve as arcs (kerf-compensated), fitted once per part."""
        key = (kerf, tolerance)
        cache = self.__dict__.setdefault("_arcs", {})
        if key not in cache:
            fine = tolerance * DEFAULT.fine_fraction
            rings = [fit_arcs(r, tolerance - fine) for r in _kerf(self.fine, kerf, fine).rings]
            cache[key] = (rings, fit_arcs(self.pitch_fine, tolerance - fine))
        return cache[key]


@dataclass(frozen=True)
class BuildResult:
    name: str
    data: DesignData
    teeth: ToothedPairData | None
    parts: tuple[Part, ...]
    files: dict[str, dict]
    seconds: float

    @property
    def summary(self) -> str:
        return pair_summary(self.data, self.teeth)


def pair_summary(data: DesignData, teeth: ToothedPairData | None = None) -> str:
    """One line for a gear pair: centre distance, residuals, teeth, mesh, warnings."""
    pair = data.pair
    text = (
        f"E = {pair.center_distance:.6f} mm, closure {pair.closure_error:.1e} rad, "
        f"rolling {pair.rolling_residual:.1e} mm"
    )
    warnings = len(data.findings)
    if teeth is not None:
        z1, z2 = teeth.plan.teeth
        text += f", {z1}/{z2} teeth m = {teeth.plan.module:.4f}, {'meshes' if teeth.mesh.meshes else 'INTERFERES'}"
        warnings += len(teeth.findings)
    return f"{text}, {warnings} warning(s)"


def make_parts(data: DesignData, teeth: ToothedPairData | None, params: GearPairParams) -> tuple[Part, ...]:
    """Each gear's outline with its bore; without teeth the part is its pitch curve."""
    tol = params.output.tolerance
    fine_tol = tol * DEFAULT.fine_fraction
    parts = []
    for i, gear in enumerate(data.gears):
        pitch_fine = polyline(gear.curve, fine_tol)
        pitch = decimate(pitch_fine, tol - fine_tol)
        if teeth is not None:
            outer, fine, module = teeth.gears[i].outline.outer, teeth.fine[i], teeth.plan.module
        else:
            outer, fine, module = pitch, pitch_fine, None
        parts.append(
            Part(
                name=gear.name,
                pivot=gear.pivot,
                outline=with_bore(outer, params.bore, tol, part=gear.name, module=module),
                fine=with_bore(fine, params.bore, fine_tol, part=gear.name, module=module),
                pitch=pitch,
                pitch_fine=pitch_fine,
            )
        )
    return tuple(parts)


def _kerf(outline: Outline, kerf: float, tolerance: float) -> Outline:
    """Cut paths offset by half the kerf into the waste, so the part comes out at size."""
    if kerf <= 0:
        return outline
    steps = max(2, arc_steps(kerf / 2, tolerance, np.pi / 2))  # shapely counts segments per quarter
    grown = shapely.Polygon(outline.rings[0], outline.rings[1:]).buffer(kerf / 2, join_style="round", quad_segs=steps)
    grown = shapely.geometry.polygon.orient(grown, 1.0)
    rings = [np.asarray(grown.exterior.coords)[:-1]] + [np.asarray(r.coords)[:-1] for r in grown.interiors]
    return Outline(tuple(rings))


def part_drawing(parts, out: OutputParams, *, placed: bool) -> Drawing:
    """The DXF content of one part (``placed=False``) or of the assembly."""
    tol = out.tolerance
    cut, mark = out.cut_layer, out.mark_layer
    mark_size = 0.05 * min(float(np.min(np.hypot(*p.pitch.T))) for p in parts)
    closed: dict[str, list] = {cut: [], mark: []}
    strokes: dict[str, list] = {mark: []}
    for part in parts:
        shift = np.asarray(part.pivot) if placed else np.zeros(2)
        if out.dxf == "polyline-flat":
            rings = [r + shift for r in _kerf(part.outline, out.kerf, tol).rings]
            closed[mark].append(part.pitch + shift)
        else:
            fitted, pitch = part.arcs(out.kerf, tol)
            rings = [ArcRing(r.vertices + shift, r.bulges) for r in fitted]
            closed[mark].append(ArcRing(pitch.vertices + shift, pitch.bulges))
        closed[cut] += rings
        strokes[mark] += cross(tuple(shift), mark_size)
    descriptions = {}
    if out.kerf > 0:
        descriptions[cut] = (
            f"kerf compensation: cut paths offset {out.kerf / 2:g} mm into the waste (kerf {out.kerf:g} mm)"
        )
    return Drawing(closed, strokes, descriptions)


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
    out = params.output
    tol = replace(DEFAULT, outline_mm=out.tolerance)
    data = design(params, tol=tol)
    teeth = cut_pair(data, params.teeth, tol=tol) if params.teeth is not None else None
    parts = make_parts(data, teeth, params)
    files: dict[str, dict] = {}

    if "dxf" in out.formats and out.dxf != "polyline-flat":
        # fit every part's arcs side by side: numpy's large-array loops release the GIL
        with ThreadPoolExecutor(max_workers=2) as pool:
            list(pool.map(lambda part: part.arcs(out.kerf, out.tolerance), parts))
    solids: list[Solid] = []
    for part in parts:
        if "dxf" in out.formats:
            path = folder / f"{part.name}.dxf"
            n = write_dxf(path, part_drawing([part], out, placed=False), flavour=out.dxf)
            files[path.name] = _file_entry(path, kind="dxf", part=part.name, vertices=n, flavour=out.dxf)
        if {"stl", "3mf"} & set(out.formats):
            solid = extrude(part.outline, out.thickness, name=part.name, chamfer=out.chamfer)
            solids.append(solid)
            for fmt in ("stl", "3mf"):
                if fmt in out.formats:
                    path = folder / f"{part.name}.{fmt}"
                    count = write_stl(path, solid) if fmt == "stl" else write_3mf(path, [SolidItem(solid)])
                    files[path.name] = _file_entry(path, kind=fmt, part=part.name, triangles=count, volume=solid.volume)
    if "dxf" in out.formats:
        path = folder / "assembly.dxf"
        n = write_dxf(path, part_drawing(parts, out, placed=True), flavour=out.dxf)
        files[path.name] = _file_entry(path, kind="dxf", part="assembly", vertices=n, flavour=out.dxf)
    if "3mf" in out.formats:
        path = folder / "assembly.3mf"
        count = write_3mf(path, [SolidItem(s, 0.0, (p.pivot[0], p.pivot[1], 0.0)) for s, p in zip(solids, parts)])
        files[path.name] = _file_entry(path, kind="3mf", part="assembly", triangles=count)
    path = folder / "kinematics.csv"
    _write_kinematics_csv(data, path)
    files[path.name] = _file_entry(path, kind="csv", rows=len(data.kinematics.driver_angle))
    if out.animation:
        path = folder / "animation.gif"
        z = teeth.plan.teeth[0] if teeth else None
        phi1 = np.linspace(0.0, data.pair.cycle, frames_for(data.pair.cycle, z), endpoint=False)
        angles = np.column_stack([-phi1, data.pair.angle_map(phi1)])
        frames = write_gif(path, [p.outline.outer for p in parts], [p.pivot for p in parts], angles)
        files[path.name] = _file_entry(path, kind="gif", frames=frames)
    if out.charts:
        drawn = [
            ("pitch_curves.png", lambda p: charts.pitch_chart(data, p, [part.pitch for part in parts])),
            ("kinematics.png", lambda p: charts.kinematics_chart(data, p)),
        ]
        if teeth:
            drawn.append(("mesh.png", lambda p: charts.mesh_chart(data, teeth, p)))
        for name, draw in drawn:
            draw(folder / name)
            files[name] = _file_entry(folder / name, kind="png")
    files["report.json"] = {"kind": "json"}
    write_report(data, teeth, parts, files, folder / "report.json")
    return BuildResult(params.name, data, teeth, parts, files, time.perf_counter() - start)


def build_any(params, folder: Path | None):
    """Build (or, with ``folder=None``, only check) a profile of any mechanism."""
    from . import build_more
    from .profiles import CarrierTrainParams, RollerBodyParams, RollingWheelParams

    if isinstance(params, GearPairParams):
        return build_profile(params, folder)
    builder = {
        RollerBodyParams: build_more.build_roller_body,
        RollingWheelParams: build_more.build_rolling_wheel,
        CarrierTrainParams: build_more.build_carrier_train,
    }[type(params)]
    return builder(params, folder)


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
                result = build_any(params, folder)
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
