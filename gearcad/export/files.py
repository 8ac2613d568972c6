"""The writers the format table (:mod:`gearcad.formats`) names.  Every writer has one signature,
``writer(design, folder, made) -> {file name: entry}``: it writes all its format's files of the
design into ``folder``, reading the parts' drawings or solids from ``made`` (made once for every
format), and returns their entries in the report's files block."""

from __future__ import annotations

from pathlib import Path

from ..formats import by_name
from ..mechanisms import Design
from .pieces import Made, write_pieces

__all__ = ["write_dxf", "write_svg", "write_stl", "write_3mf"]

_TITLES = {"assembly": "assembly", "sheet": "cutting sheet"}


def write_dxf(design: Design, folder: Path, made: Made) -> dict[str, dict]:
    from .dxf import write_dxf as write

    out = design.params.output

    def one(path, whole, drawing):
        return {"vertices": write(path, drawing, flavour=out.dxf, cut_layer=out.cut_layer), "flavour": out.dxf}

    return write_pieces(by_name("dxf"), folder, made, one)


def write_svg(design: Design, folder: Path, made: Made) -> dict[str, dict]:
    from .svg import write_svg as write

    out = design.params.output
    layers = {"cut_layer": out.cut_layer, "mark_layer": out.mark_layer}

    def one(path, whole, drawing):
        title = f"{design.name}: {_TITLES.get(whole, path.stem)}"
        page = (0.0, 0.0, *out.sheet) if whole == "sheet" else None  # the sheet itself, as laid out
        return {"segments": write(path, drawing, title=title, page=page, **layers)}

    return write_pieces(by_name("svg"), folder, made, one)


def write_stl(design: Design, folder: Path, made: Made) -> dict[str, dict]:
    from .mesh import write_stl as write

    def one(path, whole, items):
        (item,) = items
        return {"triangles": write(path, item.solid), "volume": item.solid.volume}

    return write_pieces(by_name("stl"), folder, made, one)


def write_3mf(design: Design, folder: Path, made: Made) -> dict[str, dict]:
    from .mesh import write_3mf as write

    def one(path, whole, items):
        if whole == "plate":
            from .plate import write_plate

            return {"triangles": write_plate(path, design, items)}
        count = write(path, items)
        return {"triangles": count} if whole else {"triangles": count, "volume": items[0].solid.volume}

    return write_pieces(by_name("3mf"), folder, made, one)
