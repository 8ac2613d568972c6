"""Print plates: every solid of a mechanism on the printer's bed (``output.bed``), ``output.gap`` apart.

``plate.3mf`` holds one object per part and one build item per part placed (three rollers: one
roller object, three items), each item carrying its transform: turned about z, moved onto the
bed, bottom at z = 0.  Bed coordinates run from the bed's front-left corner, as slicers' bed
shapes do (PrusaSlicer's ``bed_shape = 0x0,250x0,250x210,0x210``), so a slicer that keeps the
items' transforms prints the arrangement as laid out.  PrusaSlicer keeps them when it opens the
file; its command line re-arranges unless given ``--dont-arrange``, which the file's
Description says.
"""

from __future__ import annotations

import io
import zipfile
from collections import Counter
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..errors import DesignError
from ..geometry.outline import place
from ..mechanisms import Design, Placement
from .mesh import CONTENT_TYPES, RELS, SolidItem, xml_name

__all__ = ["write_plate"]

_ON_BED = 1e-6  # mm: how far a placed solid may stray past the bed's edge by rounding


def _matrix(angle: float, offset: tuple[float, float, float]) -> str:
    """A 3MF transform (row vectors: p' = p · M): turn by ``angle`` about z, then move."""
    c, s = np.cos(angle), np.sin(angle)
    m = [c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0, *offset]
    return " ".join(f"{v + 0.0:.9f}" for v in m)


def _metadata(name: str, value: str) -> str:
    return f'<metadata name="{name}">{xml_name(value)}</metadata>\n'


def _build_items(layout, solids: dict, ids: dict, counts: Counter, bed) -> list[str]:
    """The build's items: each placed solid turned, moved onto the bed and standing on it,
    numbered where a part is placed more than once; a solid reaching off the bed refuses."""
    bed_w, bed_h = bed
    items = []
    seen: Counter[str] = Counter()
    for pl in layout:
        solid = solids[pl.part]
        xy = place(solid.vertices[:, :2], pl.angle, pl.offset)
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        if lo.min() < -_ON_BED or hi[0] > bed_w + _ON_BED or hi[1] > bed_h + _ON_BED:
            # the footprint was measured on the part's outline; a solid reaching past it is not that part's
            raise DesignError(f"{pl.part}: its solid reaches outside its outline's footprint, off the bed")
        z = -float(solid.vertices[:, 2].min())
        seen[pl.part] += 1
        number = f" {seen[pl.part]}/{counts[pl.part]}" if counts[pl.part] > 1 else ""
        items.append(
            f'<item objectid="{ids[pl.part]}" transform="{_matrix(pl.angle, (*pl.offset, z))}" '
            f'partnumber="{xml_name(pl.part + number)}"/>\n'
        )
    return items


def _write_zip(path: Path, model: str) -> None:
    """The 3MF package: its content types, relationships and model, with fixed dates."""
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=1) as z:
        for name, content in (
            ("[Content_Types].xml", CONTENT_TYPES),
            ("_rels/.rels", RELS),
            ("3D/3dmodel.model", model),
        ):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, content.encode("utf-8"), compresslevel=1)


def _model(design: Design, stem: str, names: list, solids: dict, ids: dict, counts: Counter, items: list) -> str:
    """The plate's 3D model: its title and description, each part's mesh once, the build's items."""
    out = design.params.output
    bed_w, bed_h = out.bed
    text = io.StringIO()
    text.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    text.write(
        '<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n'
    )
    plates = len(design.plates)
    which = f" {1 if stem == 'plate' else stem.rpartition('-')[2]} of {plates}" if plates > 1 else ""
    text.write(_metadata("Title", f"{design.name}: print plate{which}"))
    text.write(_metadata("Application", "gearcad"))
    listed = ", ".join(f"{n} ×{counts[n]}" if counts[n] > 1 else n for n in names)
    text.write(
        _metadata(
            "Description",
            f"{listed} laid out on a {bed_w:g} × {bed_h:g} mm bed (origin at its front-left corner), "
            f"{out.gap:g} mm apart, {out.thickness:g} mm thick; keep the arrangement "
            "(PrusaSlicer command line: --dont-arrange)",
        )
    )
    text.write("<resources>\n")
    for name in names:
        solid = solids[name]
        text.write(f'<object id="{ids[name]}" type="model" name="{xml_name(name)}"><mesh><vertices>\n')
        text.write(solid.xml)
        text.write("</triangles></mesh></object>\n")
    text.write("</resources>\n<build>\n")
    text.writelines(items)
    text.write("</build>\n</model>\n")
    return text.getvalue()


def write_plate(path: Path, design: Design, items: Sequence[SolidItem]) -> int:
    """Write one print plate (``plate.3mf``, ``plate-2.3mf``, …): solids placed on the bed.

    Parameters
    ----------
    path : Path
        The file to write (the same design and solids always give the same bytes).
    design : Design
        Gives ``output.bed``/``output.gap``/``output.thickness`` and the number of plates.
    items : sequence of SolidItem
        The plate's solids (pivot at the origin, standing on z ≥ 0, as ``extrude`` makes them),
        each turned and moved onto the bed as a layout of ``design.plates`` places it.

    Returns
    -------
    int
        Triangles on the plate (a part placed three times counts three times).

    Raises
    ------
    DesignError
        When the parts do not fit on the bed (naming ``output.bed``).
    """
    out = design.params.output
    solids = {i.solid.name: i.solid for i in items}
    layout = [Placement(i.solid.name, i.angle, tuple(i.offset[:2])) for i in items]
    names = list(dict.fromkeys(pl.part for pl in layout))
    ids = {name: k for k, name in enumerate(names, 1)}
    counts = Counter(pl.part for pl in layout)
    items = _build_items(layout, solids, ids, counts, out.bed)
    _write_zip(path, _model(design, Path(path).stem, names, solids, ids, counts, items))
    return sum(solids[pl.part].triangle_count for pl in layout)
