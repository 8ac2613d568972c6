"""A calibration coupon: short sectors of a gear pair's real teeth at five compensation steps.

A maker cuts or prints the coupon before the parts: for each step (the process's kerf or XY
compensation, −0.1 … +0.1 mm about the nominal) a sector of each gear, a few teeth wide, at the
tightest and at the loosest place of the mesh (where the band's worst case falls and where the
drawn play is largest; a pair whose play is the same everywhere, such as a circle pair, takes
one place).  Each sector keeps a hub about the gear's pivot with its hole (the bore or pilot, or
a Ø2 mm pin hole), so the two sectors of a step can be pinned at the centre distance and turned
against each other; the step that meshes with the designed play (or measures nominal across its
teeth) names the value to set.

Pure geometry: the sectors are the part's outline (at the tolerance) intersected with a fan
about the chosen angle; the paths are those sectors offset as the process makes them (a laser's
beam centre kerf/2 outside, a printed edge drawn the compensation inside).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely import affinity

from ..errors import ProfileError
from ..mechanisms.base import Design
from .band import play_along
from .fit import pair_geometry

__all__ = ["STEPS", "KEYS", "CouponData", "Piece", "check_coupon", "coupon_data", "step_offset"]

STEPS = (-0.1, -0.05, 0.0, 0.05, 0.1)
"""The steps about the nominal compensation, mm."""
KEYS = {"laser": "process.kerf", "fdm": "process.xy_compensation", "cnc": "process.xy_compensation"}
"""The one key a maker sets after measuring the coupon, per process."""
PIN_HOLE_MM = 2.0
"""The pin hole of a sector whose gear has no bore or pilot hole (a Ø2 mm pin or drill)."""
_TEETH_EACH_SIDE = 1.6
"""The sector reaches this many pitches either side of the contact (about three teeth)."""


@dataclass(frozen=True)
class Piece:
    """One sector of one step, pivot at the origin, turned so its teeth point up (+y).

    ``nominal`` is the sector as drawn, ``path`` what is written: a laser's cut path (``nominal``
    offset ``value``/2 outward), a printer's or router's drawn edge (``nominal`` offset by
    :func:`step_offset`).  ``offset`` places the pivot on the coupon's sheet (mm)."""

    name: str
    gear: int
    place: str
    value: float
    label: str
    nominal: shapely.Polygon
    path: shapely.Polygon
    hub: float
    turn: float
    """The turn (rad) from the gear's frame to the sector's (teeth up)."""
    offset: tuple[float, float]


@dataclass(frozen=True)
class CouponData:
    """A profile's coupon: what is stepped, where, and the pieces laid out on one sheet."""

    name: str
    kind: str
    key: str
    nominal: float
    steps: tuple[float, ...]
    places: tuple[tuple[str, float], ...]
    """(place, driver angle φ1 rad) per sector place: "tight" and "loose", or "any"."""
    gears: tuple[str, str]
    pieces: tuple[Piece, ...]
    size: tuple[float, float]
    thickness: float
    tolerance: float


def check_coupon(params) -> None:
    """Raise :class:`ProfileError` (one line) for a profile no coupon is made of."""
    if params.mechanism != "gear-pair":
        raise ProfileError(
            f"mechanism = {params.mechanism!r}: a coupon is cut from a gear pair's teeth; give a gear-pair profile"
        )
    kind = params.process.kind
    if kind not in KEYS:
        raise ProfileError(
            f"process.kind = {kind!r}: a coupon steps the process's kerf or compensation; "
            f"set process.kind to one of {', '.join(KEYS)}"
        )


def step_offset(kind: str, value: float, tool: float = 0.0) -> float:
    """How far a step's path lies outside the drawn sector (mm): a laser's beam centre half its
    kerf; a printed edge is drawn ``value`` inside (it comes out ``value`` outside); a router's
    tool centre its radius outside, less the compensation."""
    if kind == "laser":
        return value / 2
    return tool / 2 - value if kind == "cnc" else -value


def _nominal_value(params) -> float:
    process = params.process
    return params.output.kerf if process.kind == "laser" else process.value("xy_compensation")


def _places(design: Design, g) -> tuple[tuple[str, float, float], ...]:
    """(place, φ1, φ2): the band's worst case and the largest drawn play, or one place."""
    tol, module = design.params.output.tolerance, g.module
    play = play_along(g, edge=0.0, tol=tol, reach=design.params.teeth.backlash + module)
    worst = design.data["bands"][0]["worst_phi1"]  # gear 1's turn (``worst_phi`` is the driver's)
    tight = int(np.argmin(np.abs(g.phi1 - worst)))
    loose = int(np.nanargmax(play))
    if np.nanmax(play) - np.nanmin(play) <= max(4 * tol, 0.02 * float(np.nanmax(play))) or loose == tight:
        return (("any", float(g.phi1[tight]), float(g.phi2[tight])),)
    return tuple((p, float(g.phi1[k]), float(g.phi2[k])) for p, k in (("tight", tight), ("loose", loose)))


def _root_angle(ring: np.ndarray, around: float, within: float) -> float:
    """The polar angle of the ring's point nearest the pivot within ``within`` rad of ``around``:
    a tooth space's root, where a radial cut crosses the outline once."""
    theta = np.arctan2(ring[:, 1], ring[:, 0])
    near = np.abs((theta - around + np.pi) % (2 * np.pi) - np.pi) <= within
    radius = np.hypot(ring[:, 0], ring[:, 1])
    k = np.flatnonzero(near)[np.argmin(radius[near])]
    return around + ((theta[k] - around + np.pi) % (2 * np.pi) - np.pi)


def _sector(part, theta: float, pitch_radius: float, module: float) -> tuple[shapely.Polygon, float, float]:
    """The part's sector about polar angle ``theta`` with its hub and pivot hole, turned so
    ``theta`` points up; the hub's radius (mm) and the turn (rad)."""
    ring = part.outline.outer
    radius = np.hypot(ring[:, 0], ring[:, 1])
    pitch = math.pi * module / pitch_radius  # one pitch as an angle at the contact
    lo = _root_angle(ring, theta - _TEETH_EACH_SIDE * pitch, pitch / 2)
    hi = _root_angle(ring, theta + _TEETH_EACH_SIDE * pitch, pitch / 2)
    angle = np.arctan2(ring[:, 1], ring[:, 0])
    inside = np.abs((angle - (lo + hi) / 2 + np.pi) % (2 * np.pi) - np.pi) <= (hi - lo) / 2
    inner = 0.85 * float(radius[inside].min())  # inside every root of the sector
    holes = part.outline.rings[1:]
    reach = max((float(np.hypot(h[:, 0], h[:, 1]).max()) for h in holes), default=PIN_HOLE_MM / 2)
    hub = min(reach + 2.5, 0.8 * inner)
    outer = float(radius.max()) + 1.0
    arc = np.linspace(lo, hi, 64)
    fan = shapely.Polygon(
        [
            (inner * math.cos(lo), inner * math.sin(lo)),
            *zip(outer * np.cos(arc), outer * np.sin(arc)),
            (inner * math.cos(hi), inner * math.sin(hi)),
        ]
    )
    neck = shapely.convex_hull(
        shapely.union(
            shapely.Point(0, 0).buffer(hub, quad_segs=32),
            shapely.MultiPoint([(inner * math.cos(a), inner * math.sin(a)) for a in (lo, hi)]),
        )
    )
    gear = shapely.Polygon(ring, holes)
    piece = shapely.intersection(gear, shapely.union(fan, neck))
    if part.pivot == "cross":  # no hole to pin it by: a pin hole
        piece = shapely.difference(piece, shapely.Point(0, 0).buffer(PIN_HOLE_MM / 2, quad_segs=32))
    piece = max(getattr(piece, "geoms", [piece]), key=lambda p: p.area)
    turned = affinity.rotate(piece, math.pi / 2 - theta, origin=(0, 0), use_radians=True)
    return shapely.geometry.polygon.orient(turned, 1.0), hub, math.pi / 2 - theta


def _offset(polygon: shapely.Polygon, distance: float, tol: float) -> shapely.Polygon:
    """``polygon`` grown by ``distance`` mm (negative: shrunk), corners rounded within ``tol``."""
    if distance == 0:
        return polygon
    step = 2 * math.acos(max(1 - tol / abs(distance), -1.0))
    grown = polygon.buffer(distance, quad_segs=max(2, math.ceil(math.pi / 2 / step)))
    grown = max(getattr(grown, "geoms", [grown]), key=lambda p: p.area)
    return shapely.geometry.polygon.orient(grown, 1.0)


def coupon_data(design: Design) -> CouponData:
    """The coupon of a (made) gear-pair design: its pieces at every step, laid out on one sheet."""
    params = design.params
    check_coupon(params)
    g = pair_geometry(design)
    out, process = params.output, params.process
    nominal = _nominal_value(params)
    steps = tuple(sorted({round(max(0.0, nominal + s) if process.kind == "laser" else nominal + s, 6) for s in STEPS}))
    tool = process.value("tool_diameter")
    parts = design.parts()
    places = _places(design, g)
    pieces = []
    for place, phi1, phi2 in places:
        r1 = float(np.interp(phi1, g.phi1, g.r1))
        sectors = (
            _sector(parts[0], phi1, r1, g.module),
            _sector(parts[1], math.pi - phi2, g.center_distance - r1, g.module),
        )
        for gear, (sector, hub, turn) in enumerate(sectors):
            for value in steps:
                text = f"{value:.2f}" if process.kind == "laser" else f"{value:+.2f}"
                label = text if place == "any" else f"{text} {place[0].upper()}"
                path = _offset(sector, step_offset(process.kind, value, tool), out.tolerance)
                name = f"{parts[gear].name} {place} {text}"
                pieces.append(Piece(name, gear, place, value, label, sector, path, hub, turn, (0.0, 0.0)))
    laid, size = _layout(pieces, len(steps), out.gap)
    return CouponData(
        params.name,
        process.kind,
        KEYS[process.kind],
        nominal,
        steps,
        tuple((p, phi1) for p, phi1, _ in places),
        (parts[0].name, parts[1].name),
        laid,
        size,
        out.thickness,
        out.tolerance,
    )


def _layout(pieces: list[Piece], columns: int, gap: float) -> tuple[tuple[Piece, ...], tuple[float, float]]:
    """Pieces in a grid: one column per step (smallest on the left), one row per gear and place
    (the first at the bottom); ``gap`` mm between paths and around them.  Returns the pieces
    placed and the sheet's size (mm)."""
    rows = len(pieces) // columns
    bounds = np.array([p.path.bounds for p in pieces]).reshape(rows, columns, 4)
    widths = (bounds[:, :, 2] - bounds[:, :, 0]).max(axis=0)
    heights = (bounds[:, :, 3] - bounds[:, :, 1]).max(axis=1)
    x0 = gap + np.concatenate([[0.0], np.cumsum(widths + gap)[:-1]])
    y0 = gap + np.concatenate([[0.0], np.cumsum(heights + gap)[:-1]])
    placed = []
    for k, p in enumerate(pieces):
        row, col = divmod(k, columns)
        b = bounds[row, col]
        placed.append(Piece(**{**p.__dict__, "offset": (float(x0[col] - b[0]), float(y0[row] - b[1]))}))
    size = (float(x0[-1] + widths[-1] + gap), float(y0[-1] + heights[-1] + gap))
    return tuple(placed), size
