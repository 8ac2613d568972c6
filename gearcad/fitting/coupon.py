"""A calibration coupon: short sectors of a gear pair's real teeth at five compensation steps.

A maker cuts or prints the coupon before the parts: for each step (the process's kerf or XY
compensation, −0.1 … +0.1 mm about the nominal) a sector of each gear, a few teeth wide, at the
tightest and at the loosest place of the mesh (where the band's worst case falls and where the
drawn play is largest; a pair whose play is the same everywhere, such as a circle pair, takes
one place).  Each sector keeps a hub about the gear's pivot with its hole (the bore or pilot, or
a Ø2 mm pin hole), so the two sectors of a step can be pinned at the centre distance and turned
against each other on the jig (a plate with their two holes at the centre distance, on the same
sheet); the step that shows the designed play names the value to set.  Every piece carries its
step (a tab below the hub where its arm is too short for 1.5 mm letters), each follower sector a
triangle under the tooth where the feeler gauge goes; each step's play as made with the nominal
value is proven in :mod:`.coupon_play`.

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
from ..mechanisms.registry import MECHANISMS
from .coupon_play import Placed, feeler_gap, play_of, tooth_mark, turned
from .coupon_sheet import LABEL_CLEAR_MM, fit_box, with_tab
from .pair_geometry import pair_geometry
from .play import play_along

__all__ = [
    "STEPS",
    "KEYS",
    "LABEL_CLEAR_MM",
    "CouponData",
    "Jig",
    "Piece",
    "StepPlay",
    "check_coupon",
    "coupon_data",
    "fit_box",
    "pin_hole",
    "step_offset",
]

STEPS = (-0.1, -0.05, 0.0, 0.05, 0.1)
"""The steps about the nominal compensation, mm."""
KEYS = {"laser": "process.kerf", "fdm": "process.xy_compensation", "cnc": "process.xy_compensation"}
"""The one key a maker sets after measuring the coupon, per process."""
PIN_HOLE_MM = 2.0
"""The pin hole of a sector whose gear has no bore (a Ø2 mm pin, or a drill's shank); a router's
is at least 1.25 tool diameters, rounded up to 0.5 mm (it cannot cut a smaller one)."""
JIG_RIM_MM = 5.0
"""The jig's plate reaches this far beyond its larger hole."""
FEELER_STEP_MM = 0.05
"""The feeler gauges named: multiples of 0.05 mm (a common set's blades)."""
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
    hole: float = 0.0
    """The pivot hole's diameter (mm, as drawn): the bore, or the pin hole."""
    mark: tuple[tuple[float, float], ...] = ()
    """A follower's engraved triangle pointing at the tooth where the feeler gauge goes (sector's
    frame, mm); () for a driver's sector."""


@dataclass(frozen=True)
class Jig:
    """The plate that holds a step's two sectors at the pair's centre distance: the driver's hole
    at the origin, the follower's at (E, 0), each the diameter of the sectors' pivot holes, so that
    one pin (or dowel) through each carries the sector on its pivot.  ``path`` is the plate cut at
    the nominal kerf or compensation (its holes come out the drawn size)."""

    nominal: shapely.Polygon
    path: shapely.Polygon
    center_distance: float
    diameters: tuple[float, float]
    label: str
    offset: tuple[float, float] = (0.0, 0.0)


@dataclass(frozen=True)
class StepPlay:
    """What one step's pair does on the jig, made by the nominal process: the follower's free turn
    (driver held at the place's angle) as play on its pitch curve, and the gap a feeler gauge meets
    between the flanks at the marked tooth with the follower turned anticlockwise to its stop; each
    a proven (lower, upper) bracket, mm.  ``play`` None: the pair binds (proven: touching or
    overlapping everywhere within ±``bound`` mm of the rolling position, on the pitch curve);
    ``play[1]`` infinite: it turns more than ``play[0]`` (a pitch) free, out of mesh, and
    ``feeler`` is None."""

    place: str
    value: float
    play: tuple[float, float] | None
    feeler: tuple[float, float] | None
    bound: float


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
    jig: Jig
    plays: tuple[StepPlay, ...]
    """Per place and step (the pieces' order): the play as made with the nominal value."""


def check_coupon(params) -> None:
    """Raise :class:`ProfileError` (one line) for a profile no coupon is made of."""
    if not MECHANISMS[params.mechanism].coupons:
        cut = " or ".join(m.name for m in MECHANISMS.values() if m.coupons)
        raise ProfileError(
            f"mechanism = {params.mechanism!r}: a coupon is cut from a gear pair's teeth; give a {cut} profile"
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


def pin_hole(kind: str, tool: float = 0.0) -> float:
    """The pivot hole (mm) of a coupon's sector whose gear has no bore, and of the jig for it."""
    if kind != "cnc":
        return PIN_HOLE_MM
    return max(PIN_HOLE_MM, math.ceil(2 * 1.25 * tool) / 2)


def _circle(centre: tuple[float, float], radius: float, tol: float) -> shapely.Polygon:
    """A circle as a polygon whose chords stray at most ``tol`` inside it."""
    step = 2 * math.acos(max(1 - tol / radius, -1.0))
    return shapely.Point(centre).buffer(radius, quad_segs=max(8, math.ceil(math.pi / 2 / step)))


def _sector(
    part, theta: float, pitch_radius: float, module: float, pin: float, tol: float
) -> tuple[shapely.Polygon, float, float, float]:
    """The part's sector about polar angle ``theta`` with its hub and pivot hole (the bore, else a
    pin hole of ``pin`` mm), turned so ``theta`` points up; the hub's radius (mm), the turn (rad)
    and the pivot hole's diameter (mm)."""
    ring = part.outline.outer
    radius = np.hypot(ring[:, 0], ring[:, 1])
    pitch = math.pi * module / pitch_radius  # one pitch as an angle at the contact
    lo = _root_angle(ring, theta - _TEETH_EACH_SIDE * pitch, pitch / 2)
    hi = _root_angle(ring, theta + _TEETH_EACH_SIDE * pitch, pitch / 2)
    angle = np.arctan2(ring[:, 1], ring[:, 0])
    inside = np.abs((angle - (lo + hi) / 2 + np.pi) % (2 * np.pi) - np.pi) <= (hi - lo) / 2
    inner = 0.85 * float(radius[inside].min())  # inside every root of the sector
    origin = shapely.Point(0, 0)
    pivots = [h for h in part.outline.rings[1:] if shapely.Polygon(h).contains(origin)]
    bore = part.pivot == "bore" and bool(pivots)
    holes = [h for h in part.outline.rings[1:] if bore or not shapely.Polygon(h).contains(origin)]
    reach = max(float(np.hypot(h[:, 0], h[:, 1]).max()) for h in pivots) if bore else pin / 2
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
    if not bore:  # a pilot hole or a cross: the coupon's pin hole
        piece = shapely.difference(piece, _circle((0.0, 0.0), pin / 2, tol))
    piece = max(getattr(piece, "geoms", [piece]), key=lambda p: p.area)
    turned = affinity.rotate(piece, math.pi / 2 - theta, origin=(0, 0), use_radians=True)
    return shapely.geometry.polygon.orient(turned, 1.0), hub, math.pi / 2 - theta, 2 * reach


def _offset(polygon: shapely.Polygon, distance: float, tol: float) -> shapely.Polygon:
    """``polygon`` grown by ``distance`` mm (negative: shrunk), corners rounded within ``tol``."""
    if distance == 0:
        return polygon
    step = 2 * math.acos(max(1 - tol / abs(distance), -1.0))
    grown = polygon.buffer(distance, quad_segs=max(2, math.ceil(math.pi / 2 / step)))
    grown = max(getattr(grown, "geoms", [grown]), key=lambda p: p.area)
    return shapely.geometry.polygon.orient(grown, 1.0)


def coupon_data(design: Design) -> CouponData:
    """The coupon of a (made) gear-pair design: its pieces at every step, the jig, laid out on one
    sheet, and the play each step shows made with the nominal value."""
    params = design.params
    check_coupon(params)
    g = pair_geometry(design)
    out, process = params.output, params.process
    kind, tol = process.kind, out.tolerance
    nominal = _nominal_value(params)
    steps = tuple(sorted({round(max(0.0, nominal + s) if kind == "laser" else nominal + s, 6) for s in STEPS}))
    tool = process.value("tool_diameter") if kind == "cnc" else 0.0
    pin = pin_hole(kind, tool)
    made = -step_offset(kind, nominal, tool)  # the made edge lies this far outside the path
    parts = design.parts()
    places = _places(design, g)
    pieces, plays, holes = [], [], [0.0, 0.0]
    e = g.center_distance
    for place, phi1, phi2 in places:
        r1 = float(np.interp(phi1, g.phi1, g.r1))
        sectors = (
            _sector(parts[0], phi1, r1, g.module, pin, tol),
            _sector(parts[1], math.pi - phi2, e - r1, g.module, pin, tol),
        )
        pair = Placed(
            e,
            (-sectors[0][2] - phi1, -sectors[1][2] + phi2),
            e - r1,
            (e - r1) * math.cos(params.teeth.pressure_angle),
            g.module,
        )
        row: list[list[Piece]] = [[], []]
        for gear, (sector, hub, turn, hole) in enumerate(sectors):
            holes[gear] = hole
            texts = [f"{value:.2f}" if kind == "laser" else f"{value:+.2f}" for value in steps]
            labels = [text if place == "any" else f"{text} {place[0].upper()}" for text in texts]
            sector = with_tab(sector, hub, hole, max(labels, key=len))
            for value, text, label in zip(steps, texts, labels):
                path = _offset(sector, step_offset(kind, value, tool), tol)
                name = f"{parts[gear].name} {place} {text}"
                row[gear].append(Piece(name, gear, place, value, label, sector, path, hub, turn, (0.0, 0.0), hole))
        made_pairs = [
            (pair.world(_offset(d.path, made, tol), 0), pair.world(_offset(f.path, made, tol), 1)) for d, f in zip(*row)
        ]
        measured = [play_of(pair, *two) for two in made_pairs]
        # the feeler's place: the clockwise contact of the nominal step (else the nearest free one)
        order = sorted(range(len(steps)), key=lambda k: (abs(steps[k] - nominal), k))
        first = next((k for k in order if measured[k][1] is not None), None)
        mark = ()
        if first is not None:
            on_follower = at = measured[first][2][1]
            back = affinity.translate(shapely.Point(on_follower), -e, 0.0)  # into the sector's frame
            mark = tooth_mark(row[1][0].nominal, turned(back, (0.0, 0.0), -pair.angles[1]).coords[0], g.module)
        row[1] = [Piece(**{**p.__dict__, "mark": mark}) for p in row[1]]
        for k, (play, up, _) in enumerate(measured):
            feeler = None if up is None else feeler_gap(pair, *made_pairs[k], up, at)
            plays.append(StepPlay(place, steps[k], play, feeler, g.module))
        pieces += row[0] + row[1]
    jig = _jig(e, tuple(holes), kind, nominal, tool, tol)
    laid, size, jig = _layout(pieces, len(steps), out.gap, jig)
    return CouponData(
        params.name,
        kind,
        KEYS[kind],
        nominal,
        steps,
        tuple((p, phi1) for p, phi1, _ in places),
        (parts[0].name, parts[1].name),
        laid,
        size,
        out.thickness,
        tol,
        jig,
        tuple(plays),
    )


def _jig(e: float, holes: tuple[float, float], kind: str, nominal: float, tool: float, tol: float) -> Jig:
    """The plate: the hull of two discs :data:`JIG_RIM_MM` beyond the larger hole about the pivots,
    less the sectors' two pivot holes."""
    rim = max(holes) / 2 + JIG_RIM_MM
    plate = shapely.convex_hull(shapely.union(_circle((0.0, 0.0), rim, tol), _circle((e, 0.0), rim, tol)))
    plate = shapely.difference(
        plate, shapely.union(_circle((0.0, 0.0), holes[0] / 2, tol), _circle((e, 0.0), holes[1] / 2, tol))
    )
    plate = shapely.geometry.polygon.orient(plate, 1.0)
    return Jig(plate, _offset(plate, step_offset(kind, nominal, tool), tol), e, holes, f"{e:.2f} mm")


def _layout(
    pieces: list[Piece], columns: int, gap: float, jig: Jig
) -> tuple[tuple[Piece, ...], tuple[float, float], Jig]:
    """Pieces in a grid: one column per step (smallest on the left), one row per gear and place
    (the first at the bottom), the jig above them; ``gap`` mm between paths and around them.
    Returns the pieces placed, the sheet's size (mm) and the jig placed."""
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
    top = float(y0[-1] + heights[-1] + gap)
    jb = jig.path.bounds
    jig = Jig(**{**jig.__dict__, "offset": (gap - jb[0], top - jb[1])})
    width = max(float(x0[-1] + widths[-1] + gap), jb[2] - jb[0] + 2 * gap)
    return tuple(placed), (width, top + jb[3] - jb[1] + gap), jig
