"""The coupon's files: one sheet (``coupon.dxf``, ``coupon.svg``), one plate (``coupon.3mf``)
and ``coupon.txt``, the key to set after measuring (see :mod:`gearcad.fitting.coupon`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely
from shapely import affinity

from ..fitting.coupon import CouponData, Piece
from ..geometry.arcfit import ArcRing
from ..geometry.outline import Outline
from .drawing import Drawing
from .sheet import name_strokes

__all__ = ["COUPON_FILES", "coupon_drawing", "label_region", "write_coupon"]

COUPON_FILES = ("coupon.dxf", "coupon.svg", "coupon.3mf", "coupon.txt")
_CLEAR_MM = 0.8  # the engraving kept this far inside the drawn sector and off the hub's hole


def _placed(polygon: shapely.Polygon, piece: Piece) -> shapely.Polygon:
    return affinity.translate(polygon, *piece.offset)


def _rings(polygon: shapely.Polygon) -> list[np.ndarray]:
    """Outer ring counter-clockwise, holes clockwise, each open ((n, 2) float, mm)."""
    polygon = shapely.geometry.polygon.orient(polygon, 1.0)
    return [np.asarray(r.coords)[:-1] for r in (polygon.exterior, *polygon.interiors)]


def label_region(piece: Piece) -> shapely.Polygon:
    """Where the piece's value is engraved (placed on the sheet): its drawn sector kept
    :data:`_CLEAR_MM` inside, and off the hub."""
    body = piece.nominal.buffer(-_CLEAR_MM).difference(shapely.Point(0, 0).buffer(piece.hub + _CLEAR_MM))
    return _placed(body, piece)


def coupon_drawing(data: CouponData, *, cut_layer: str, mark_layer: str) -> Drawing:
    """Every piece's path (cut layer) and its engraved value (mark layer), as laid out."""
    closed: dict[str, list] = {cut_layer: [], mark_layer: []}
    strokes: dict[str, list] = {mark_layer: []}
    for piece in data.pieces:
        closed[cut_layer] += [ArcRing(r, np.zeros(len(r))) for r in _rings(_placed(piece.path, piece))]
        strokes[mark_layer] += name_strokes(piece.label, label_region(piece))
    what = "kerf" if data.kind == "laser" else "XY compensation"
    descriptions = {cut_layer: f"calibration coupon of {data.name}: {what} steps " + ", ".join(_values(data))}
    return Drawing(closed, strokes, descriptions)


def _values(data: CouponData) -> list[str]:
    return [f"{v:.2f}" if data.kind == "laser" else f"{v:+.2f}" for v in data.steps]


def _text(data: CouponData) -> str:
    what = "kerf" if data.kind == "laser" else "XY compensation"
    where = {
        "tight": "where the play is smallest (T)",
        "loose": "where it is largest (L)",
        "any": "(the play is the same all round)",
    }
    places = "; ".join(f"driver angle {np.degrees(phi) % 360:.1f}° {where[p]}" for p, phi in data.places)
    lines = [
        f"Calibration coupon of {data.name} ({data.kind}): sectors of {data.gears[0]} and {data.gears[1]}",
        f"at {places},",
        f"one column per {what} step: {', '.join(_values(data))} mm (nominal {data.nominal:.2f} mm);",
        "each sector is engraved with its step. Pin the two sectors of a step through their hub holes",
        "at the pair's centre distance and turn one against the other: the step that meshes with the",
        "designed play (neither binding nor loose) is your process's value.",
        "",
        f"After measuring, set {data.key} = <that step's value> in the profile's [process] table",
        f"(or: gearcad build PROFILE --set {data.key}=<value>).",
        "",
    ]
    return "\n".join(lines)


def write_coupon(data: CouponData, folder: Path, *, cut_layer: str, mark_layer: str, flavour: str) -> dict:
    """Write the coupon's files into ``folder``; returns the files block (name → counts)."""
    from .dxf import write_dxf
    from .mesh import SolidItem, extrude, write_3mf
    from .svg import write_svg

    drawing = coupon_drawing(data, cut_layer=cut_layer, mark_layer=mark_layer)
    files = {
        "coupon.dxf": {"vertices": write_dxf(folder / "coupon.dxf", drawing, flavour=flavour, cut_layer=cut_layer)},
        "coupon.svg": {
            "segments": write_svg(
                folder / "coupon.svg",
                drawing,
                cut_layer=cut_layer,
                mark_layer=mark_layer,
                title=f"{data.name}: calibration coupon",
                page=(0.0, 0.0, *data.size),
            )
        },
    }
    items = [
        SolidItem(extrude(Outline(tuple(_rings(p.path))), data.thickness, name=p.name), 0.0, (*p.offset, 0.0))
        for p in data.pieces
    ]
    files["coupon.3mf"] = {"triangles": write_3mf(folder / "coupon.3mf", items)}
    (folder / "coupon.txt").write_text(_text(data), encoding="utf-8")
    files["coupon.txt"] = {"key": data.key}
    return files
