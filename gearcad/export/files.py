"""The writers the format table (:mod:`gearcad.formats`) names: each writes one file of one
format and returns its entry in the report's files block."""

from __future__ import annotations

from pathlib import Path

from ..mechanisms import Design
from .drawing import Drawing

__all__ = ["write_dxf", "write_svg", "write_stl", "write_3mf"]

_TITLES = {"assembly": "assembly", "sheet": "cutting sheet"}


def write_dxf(path: Path, drawing: Drawing, *, design: Design, whole: str | None = None) -> dict:
    from .dxf import write_dxf as write

    out = design.params.output
    n = write(path, drawing, flavour=out.dxf, cut_layer=out.cut_layer)
    return {"vertices": n, "flavour": out.dxf}


def write_svg(path: Path, drawing: Drawing, *, design: Design, whole: str | None = None) -> dict:
    from .svg import write_svg as write

    out = design.params.output
    title = f"{design.name}: {_TITLES.get(whole, path.stem)}"
    page = (0.0, 0.0, *out.sheet) if whole == "sheet" else None  # the sheet itself, as laid out
    layers = {"cut_layer": out.cut_layer, "mark_layer": out.mark_layer}
    return {"segments": write(path, drawing, title=title, page=page, **layers)}


def write_stl(path: Path, items: list, *, design: Design, whole: str | None = None) -> dict:
    from .mesh import write_stl as write

    (item,) = items
    return {"triangles": write(path, item.solid), "volume": item.solid.volume}


def write_3mf(path: Path, items: list, *, design: Design, whole: str | None = None) -> dict:
    if whole == "plate":
        from .plate import write_plate

        return {"triangles": write_plate(path, design, items)}
    from .mesh import write_3mf as write

    count = write(path, items)
    return {"triangles": count} if whole else {"triangles": count, "volume": items[0].solid.volume}
