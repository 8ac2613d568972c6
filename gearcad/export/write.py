"""The one writing loop: a design's files into a folder, the same for every mechanism."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from ..mechanisms import Design
from .beside import Beside, can_fork
from .drawing import assembly_drawing, part_drawing

__all__ = ["write_design"]


def _entry(path: Path, **counts) -> dict:
    return {"bytes": path.stat().st_size, **counts}


def _write_table(path: Path, table) -> None:
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(table.columns)
        for row in table.rows:
            w.writerow([f"{v:.12g}" for v in row])


def _animation(design: Design, folder: Path) -> dict[str, dict]:
    """The animated GIF (drawn with Pillow)."""
    out = design.params.output
    files: dict[str, dict] = {}
    if out.animation and design.motion is not None:
        from .animation import write_gif

        path = folder / "animation.gif"
        where = {pl.part: pl for pl in design.placements}
        m = design.motion
        frames = write_gif(
            path,
            [design.part(name).outline.outer for name in m.parts],
            [where[name].offset for name in m.parts],
            m.angles + [where[name].angle for name in m.parts],
        )
        files[path.name] = _entry(path, kind="gif", frames=frames)
    return files


def _charts(design: Design, folder: Path) -> dict[str, dict]:
    """The charts and the picture of the solids (drawn with matplotlib)."""
    out = design.params.output
    files: dict[str, dict] = {}
    if out.charts and design.sections:  # twisted teeth are best seen: a rendered picture
        from .charts.solid import draw_design

        path = folder / "solid.png"
        draw_design(path, design)
        files[path.name] = _entry(path, kind="png")
    if out.charts:
        from .charts import draw_charts

        for name in draw_charts(design, folder):
            files[name] = _entry(folder / name, kind="png")
    return files


def write_design(design: Design, folder: Path, *, beside: bool = False) -> dict[str, dict]:
    """Write every file the profile's [output] asks for into ``folder`` (which must exist);
    return the files block of the report (the report itself written last).

    ``beside``: draw the charts and the animation in forked processes while this one writes
    the rest (for a machine with a core to spare): matplotlib's import and drawing take about
    as long as all the other files together.
    """
    jobs: dict = {}
    try:
        if beside and can_fork():
            for draw in (_charts, _animation):
                try:
                    jobs[draw] = Beside(lambda draw=draw: draw(design, folder))
                except OSError:  # no process to spare (EAGAIN, ENOMEM): drawn here instead
                    break
        return _write(design, folder, jobs)
    finally:
        for job in jobs.values():
            job.cancel()


def _write(design: Design, folder: Path, drawing: dict) -> dict[str, dict]:
    out = design.params.output
    formats = set(out.formats)
    files: dict[str, dict] = {}
    parts = design.parts()
    if "dxf" in formats:
        from .dxf import write_dxf

        for part in parts:
            path = folder / f"{part.name}.dxf"
            n = write_dxf(path, part_drawing(design, part), flavour=out.dxf, cut_layer=out.cut_layer)
            files[path.name] = _entry(path, kind="dxf", part=part.name, vertices=n, flavour=out.dxf)
        path = folder / "assembly.dxf"
        n = write_dxf(path, assembly_drawing(design), flavour=out.dxf, cut_layer=out.cut_layer)
        files[path.name] = _entry(path, kind="dxf", part="assembly", vertices=n, flavour=out.dxf)
    if "svg" in formats:
        from .svg import write_svg

        layers = {"cut_layer": out.cut_layer, "mark_layer": out.mark_layer}
        for part in parts:
            path = folder / f"{part.name}.svg"
            n = write_svg(path, part_drawing(design, part), title=f"{design.name}: {part.name}", **layers)
            files[path.name] = _entry(path, kind="svg", part=part.name, segments=n)
        path = folder / "assembly.svg"
        n = write_svg(path, assembly_drawing(design), title=f"{design.name}: assembly", **layers)
        files[path.name] = _entry(path, kind="svg", part="assembly", segments=n)
    if formats & {"dxf", "svg"}:
        from .sheet import sheet_drawing

        sheet = sheet_drawing(design)
        if "dxf" in formats:
            path = folder / "sheet.dxf"
            n = write_dxf(path, sheet, flavour=out.dxf, cut_layer=out.cut_layer)
            files[path.name] = _entry(path, kind="dxf", part="sheet", vertices=n, flavour=out.dxf)
        if "svg" in formats:
            path = folder / "sheet.svg"
            page = (0.0, 0.0, *out.sheet)  # the sheet itself, as laid out (lower-left corner at 0)
            n = write_svg(path, sheet, title=f"{design.name}: cutting sheet", page=page, **layers)
            files[path.name] = _entry(path, kind="svg", part="sheet", segments=n)
    if formats & {"stl", "3mf"}:
        from .loft import loft
        from .mesh import SolidItem, extrude, write_3mf, write_stl

        def solid(part):
            twisted = design.sections.get(part.name)
            if twisted is None:
                return extrude(part.outline, out.thickness, name=part.name, chamfer=out.chamfer)
            holes = part.outline.rings[1:]
            return loft(twisted.heights, twisted.rings, name=part.name, holes=holes, chamfer=out.chamfer)

        solids = {p.name: solid(p) for p in parts}
        for name, solid in solids.items():
            if "stl" in formats:
                path = folder / f"{name}.stl"
                count = write_stl(path, solid)
                files[path.name] = _entry(path, kind="stl", part=name, triangles=count, volume=solid.volume)
            if "3mf" in formats:
                path = folder / f"{name}.3mf"
                count = write_3mf(path, [SolidItem(solid)])
                files[path.name] = _entry(path, kind="3mf", part=name, triangles=count, volume=solid.volume)
        if "3mf" in formats:
            path = folder / "assembly.3mf"
            items = [SolidItem(solids[pl.part], pl.angle, (*pl.offset, 0.0)) for pl in design.placements]
            files[path.name] = _entry(path, kind="3mf", part="assembly", triangles=write_3mf(path, items))
            from .plate import write_plate

            path = folder / "plate.3mf"
            files[path.name] = _entry(path, kind="3mf", part="plate", triangles=write_plate(path, design, solids))
    for table in design.tables:
        path = folder / table.file
        _write_table(path, table)
        files[path.name] = _entry(path, kind="csv", rows=len(table.rows))
    for draw in (_animation, _charts):  # drawn here, or collected from the processes beside
        files.update(drawing[draw].result() if draw in drawing else draw(design, folder))
    files["index.html"] = {"kind": "html"}
    files["report.json"] = {"kind": "json"}
    text = json.dumps(design.report(files), indent=2, ensure_ascii=False, allow_nan=False)
    (folder / "report.json").write_text(text + "\n", encoding="utf-8")
    from .html import write_profile_page

    write_profile_page(folder / "index.html", design, files)
    return files
