"""The coupon's files: one sheet (``coupon.dxf``, ``coupon.svg``), one plate (``coupon.3mf``)
and ``coupon.txt``, the key to set after measuring (see :mod:`gearcad.fitting.coupon`)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely
from shapely import affinity

from ..fitting.coupon import FEELER_STEP_MM, LABEL_CLEAR_MM, CouponData, Jig, Piece, fit_box
from ..geometry.arcfit import ArcRing
from ..geometry.outline import Outline
from .drawing import Drawing

__all__ = [
    "COUPON_FILES",
    "LABEL_MM",
    "coupon_drawing",
    "label_box",
    "label_region",
    "label_strokes",
    "play_lines",
    "write_coupon",
]

COUPON_FILES = ("coupon.dxf", "coupon.svg", "coupon.3mf", "coupon.txt")
_CLEAR_MM = LABEL_CLEAR_MM  # the engraving kept this far inside the drawn sector and off the hub


def _placed(polygon: shapely.Polygon, piece: Piece) -> shapely.Polygon:
    return affinity.translate(polygon, *piece.offset)


def _rings(polygon: shapely.Polygon) -> list[np.ndarray]:
    """Outer ring counter-clockwise, holes clockwise, each open ((n, 2) float, mm)."""
    polygon = shapely.geometry.polygon.orient(polygon, 1.0)
    return [np.asarray(r.coords)[:-1] for r in (polygon.exterior, *polygon.interiors)]


LABEL_MM = (1.5, 4.0)
"""The engraved labels' letter height (mm): the text's extents, digits and capitals."""


def label_region(piece: Piece) -> shapely.Polygon:
    """Where the piece's value is engraved (placed on the sheet): its drawn sector kept
    :data:`_CLEAR_MM` inside, off the hub and off the follower's tooth mark."""
    body = piece.nominal.buffer(-_CLEAR_MM).difference(shapely.Point(0, 0).buffer(piece.hub + _CLEAR_MM))
    if piece.mark:
        body = body.difference(shapely.Polygon(piece.mark).buffer(_CLEAR_MM))
    return _placed(body, piece)


def _jig_region(jig: Jig) -> shapely.Polygon:
    body = jig.nominal.buffer(-_CLEAR_MM)
    for x, d in zip((0.0, jig.center_distance), jig.diameters):
        body = body.difference(shapely.Point(x, 0.0).buffer(d / 2 + 1.5))
    return affinity.translate(body, *jig.offset)


def _glyphs(text: str) -> tuple[list[np.ndarray], np.ndarray]:
    """``text``'s outlines at size 1 and their extents ((x0, y0), (x1, y1)) as drawn."""
    from matplotlib.textpath import TextPath  # only when a coupon is written

    polygons = [p for p in TextPath((0.0, 0.0), text, size=1.0).to_polygons(closed_only=False) if len(p) >= 3]
    points = np.vstack(polygons)
    return polygons, np.array([points.min(axis=0), points.max(axis=0)])


def label_box(text: str, region: shapely.Polygon) -> tuple[float, float, float, float] | None:
    """Where ``text`` goes in ``region``: (x, y, angle, height) of its box's centre, along x
    (angle 0) or, where the region is narrow, along y reading upwards (90), as tall as fits up to
    :data:`LABEL_MM`'s largest (bisected over 0.25 mm steps); None where not even its smallest
    fits (:func:`~gearcad.fitting.coupon.fit_box`)."""
    _, extents = _glyphs(text)
    width, tall = extents[1] - extents[0]
    heights = np.arange(LABEL_MM[0], LABEL_MM[1] + 1e-9, 0.25)

    def fits(k: int):
        return fit_box(region, width * heights[k] / tall, heights[k])

    best = fits(0)
    if best is None:
        return None
    lo, hi = 0, len(heights)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        where = fits(mid)
        lo, hi, best = (mid, hi, where) if where is not None else (lo, mid, best)
    return (*best, float(heights[lo]))


def label_strokes(text: str, box: tuple[float, float, float, float] | None) -> list[np.ndarray]:
    """``text`` in outline letters ((k, 2) closed strokes, mm) centred in ``box`` (see
    :func:`label_box`), letters ``box``'s height tall; [] for no box."""
    if box is None:
        return []
    polygons, extents = _glyphs(text)
    x, y, angle, height = box
    scale = height / (extents[1, 1] - extents[0, 1])
    centre = extents.mean(axis=0) * scale
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    turn = np.array([[c, s], [-s, c]])  # row vectors: turned by +angle
    return [(np.vstack([p, p[:1]]) * scale - centre) @ turn + (x, y) for p in polygons]


def coupon_drawing(data: CouponData, *, cut_layer: str, mark_layer: str) -> Drawing:
    """Every piece's and the jig's path (cut layer), their engraved values and the follower's
    tooth marks (mark layer), as laid out."""
    closed: dict[str, list] = {cut_layer: [], mark_layer: []}
    strokes: dict[str, list] = {mark_layer: []}
    boxes: dict[tuple, tuple] = {}
    for piece in data.pieces:  # a row's sectors are alike: one box for its widest label
        row = (piece.gear, piece.place)
        if row not in boxes:
            widest = max((p.label for p in data.pieces if (p.gear, p.place) == row), key=_width)
            boxes[row] = (label_box(widest, label_region(piece)), piece.offset)
    for piece in data.pieces:
        closed[cut_layer] += [ArcRing(r, np.zeros(len(r))) for r in _rings(_placed(piece.path, piece))]
        box, at = boxes[piece.gear, piece.place]
        if box is not None:
            box = (box[0] + piece.offset[0] - at[0], box[1] + piece.offset[1] - at[1], *box[2:])
        strokes[mark_layer] += label_strokes(piece.label, box)
        if piece.mark:
            strokes[mark_layer].append(np.vstack([piece.mark, piece.mark[:1]]) + np.asarray(piece.offset))
    jig = data.jig
    closed[cut_layer] += [ArcRing(r, np.zeros(len(r))) for r in _rings(affinity.translate(jig.path, *jig.offset))]
    strokes[mark_layer] += label_strokes(jig.label, label_box(jig.label, _jig_region(jig)))
    what = "kerf" if data.kind == "laser" else "XY compensation"
    descriptions = {
        cut_layer: f"calibration coupon of {data.name}: {what} steps "
        + ", ".join(_values(data))
        + f"; jig {jig.center_distance:.3f} mm"
    }
    return Drawing(closed, strokes, descriptions)


def _width(label: str) -> float:
    """A label's width over its height (its letters' extents)."""
    size = np.ptp(_glyphs(label)[1], axis=0)
    return float(size[0] / size[1])


def _values(data: CouponData) -> list[str]:
    return [_value(data, v) for v in data.steps]


def _value(data: CouponData, v: float) -> str:
    return f"{v:.2f}" if data.kind == "laser" else f"{v:+.2f}"


def _feeler(gap: tuple[float, float], module: float) -> str:
    """What a feeler gauge set says of a gap (a proven bracket, mm)."""
    cap = 0.5 * module
    if gap[0] >= cap:
        return f"a {cap:.2f} feeler fits"
    fits = math.floor(gap[0] / FEELER_STEP_MM + 1e-9) * FEELER_STEP_MM
    above = math.floor(gap[1] / FEELER_STEP_MM + 1e-9) * FEELER_STEP_MM + FEELER_STEP_MM
    if fits <= 0:
        return f"the gap is {gap[0]:.3f} mm: no {FEELER_STEP_MM:.2f} feeler fits"
    return f"a {fits:.2f} feeler fits, {above:.2f} does not"


def play_lines(data: CouponData) -> list[str]:
    """One line per place and step: the play and the feeler gap the pair shows, made with the
    nominal value."""
    mark = {"tight": "T", "loose": "L", "any": ""}
    lines = []
    for p in data.plays:
        step = f"step {_value(data, p.value)}" + (f" {mark[p.place]}" if mark[p.place] else "")
        if p.play is None:
            lines.append(f"  {step}: binds (no free turn within ±{p.bound:.2f} mm of the rolling position)")
            continue
        if p.feeler is None:
            lines.append(f"  {step}: turns more than {p.play[0]:.2f} mm (a pitch): the teeth slip out of mesh")
            continue
        if p.play[1] > math.pi * p.bound / 4:  # past a quarter pitch the marked point leaves its flank
            lines.append(f"  {step}: turns with {p.play[0]:.2f} mm of play (too loose for a feeler gauge)")
            continue
        lines.append(
            f"  {step}: turns with {p.play[0]:.2f} mm of play; at the marked tooth {_feeler(p.feeler, p.bound)}"
        )
    return lines


def _text(data: CouponData) -> str:
    what = "kerf" if data.kind == "laser" else "XY compensation"
    where = {
        "tight": "where the play is smallest (T)",
        "loose": "where it is largest (L)",
        "any": "(the play is the same all round)",
    }
    places = "; ".join(f"driver angle {np.degrees(phi) % 360:.1f}° {where[p]}" for p, phi in data.places)
    jig, nominal = data.jig, _value(data, data.nominal)
    holes = " and ".join(f"Ø{d:.2f}" for d in jig.diameters)
    designed = [p for p in data.plays if abs(p.value - data.nominal) < 1e-9 and p.feeler is not None]
    target = "; ".join(
        f"{p.play[0]:.2f} mm" + ("" if p.place == "any" else f" at {p.place[0].upper()}") for p in designed
    )
    lines = [
        f"Calibration coupon of {data.name} ({data.kind}): sectors of {data.gears[0]} and {data.gears[1]}",
        f"at {places},",
        f"one column per {what} step: {', '.join(_values(data))} mm (nominal {nominal} mm);",
        "each sector is engraved with its step, the follower's with a triangle under the tooth to measure.",
        f"The jig (top): holes {holes} mm, {jig.center_distance:.3f} mm apart (engraved): driver's hole on the left.",
        "",
        "Put a pin (or dowel) in each of the jig's holes, a step's driver sector on the left pin and its",
        "follower sector on the right (engraved faces up, teeth in mesh). Hold the driver; turn the",
        "follower clockwise and anticlockwise between its stops: that is the play (mm on its pitch",
        "curve). Turned anticlockwise to its stop, a feeler gauge slides between the flanks at the",
        "marked tooth.",
        "",
        f"Play per step, made with the nominal {what} ({nominal} mm):",
        *play_lines(data),
        f"The step whose pair turns with the designed play ({target}; the nominal step's) is your {what}:",
        f"set {data.key} = <that step's value> in the profile's [process] table"
        + (", which wins over output.kerf" if data.kind == "laser" else "")
        + f" (or: gearcad build PROFILE --set {data.key}=<value>).",
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
    jig = extrude(Outline(tuple(_rings(data.jig.path))), data.thickness, name="jig")
    items.append(SolidItem(jig, 0.0, (*data.jig.offset, 0.0)))
    files["coupon.3mf"] = {"triangles": write_3mf(folder / "coupon.3mf", items)}
    (folder / "coupon.txt").write_text(_text(data), encoding="utf-8")
    files["coupon.txt"] = {"key": data.key}
    return files
