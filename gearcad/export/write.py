"""The one writing loop: a design's files into a folder, the same for every mechanism."""

from __future__ import annotations

import csv
import json
import re
from importlib import import_module
from pathlib import Path

from ..errors import GearcadError
from ..formats import TABLE, Format
from ..mechanisms import Design
from .beside import Beside, can_fork
from .pieces import Made

__all__ = ["write_design"]

_FILE_STEM = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9._-]{0,63}")
"""A part's or table's file name: one plain component, so no file can leave its folder."""


def _check_names(design: Design) -> None:
    """Refuse names that would write outside the folder or over another file (a design changed
    through the API, e.g. ``model_copy(update=...)``, is not validated by the profile reader)."""
    seen: set[str] = set()
    names = [("part", p.name) for p in design.parts()] + [("table", t.file) for t in design.tables]
    for what, name in names:
        if not isinstance(name, str) or not _FILE_STEM.fullmatch(name):
            raise GearcadError(
                f"{what} name {name!r}: must be 1 to 64 letters, digits, '-', '_' or '.', not starting with '.' "
                "(it names a file in the profile's folder)"
            )
        if name.casefold() in seen:
            raise GearcadError(f"{what} name {name!r}: two files of the design would take this name")
        seen.add(name.casefold())


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


def _write_format(fmt: Format, design: Design, folder: Path, made: Made) -> dict[str, dict]:
    """Every file of one format, through the writer the format table names (one signature for
    every writer: the design, the folder, and the drawings and solids made once for all)."""
    module, function = fmt.writer.split(":")
    writer = getattr(import_module(f".{module}", __package__), function)
    return writer(design, folder, made)


def write_design(design: Design, folder: Path, *, beside: bool = False) -> dict[str, dict]:
    """Write every file the profile's [output] asks for into ``folder`` (which must exist);
    return the files block of the report (the report itself written last).

    ``beside``: draw the charts and the animation in forked processes while this one writes
    the rest (for a machine with a core to spare): matplotlib's import and drawing take about
    as long as all the other files together.
    """
    _check_names(design)
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
    formats = set(design.params.output.formats)
    files: dict[str, dict] = {}
    made = Made(design)
    for fmt in (f for f in TABLE if f.name in formats):
        files.update(_write_format(fmt, design, folder, made))
    for table in design.tables:
        path = folder / table.file
        _write_table(path, table)
        files[path.name] = _entry(path, kind="csv", rows=len(table.rows))
    for draw in (_animation, _charts):  # drawn here, or collected from the processes beside
        files.update(drawing[draw].result() if draw in drawing else draw(design, folder))
    files["index.html"] = {"kind": "html"}
    if "papers" in design.data:
        files["papers.html"] = {"kind": "html"}
    files["report.json"] = {"kind": "json"}
    report = design.report(files)
    text = json.dumps(report, indent=2, ensure_ascii=False, allow_nan=False)
    (folder / "report.json").write_text(text + "\n", encoding="utf-8")
    if "papers" in report:  # the papers' numbers beside gearcad's
        from .html_papers import write_papers_page

        write_papers_page(folder / "papers.html", report)
    from .html import write_profile_page

    write_profile_page(folder / "index.html", design, files)
    return files
