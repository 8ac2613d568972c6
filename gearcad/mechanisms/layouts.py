"""Layouts of a design's parts: flat on a cutting sheet (``output.sheet``) and on a printer's bed
(``output.bed``), apart by ``output.gap``; made with the design, so ``check`` refuses what does
not fit exactly as ``build`` does.

Each part is laid out as often as the assembly places it (three rollers are three rollers on
the sheet).  A part is first turned to the angle of its smallest bounding rectangle, then the
parts, largest first, are packed by a skyline packer (bottom-left: lowest top edge, then
leftmost) that tries each part as it is and a quarter turn further.  Boxes are the exact
extents of the written paths (arcs included), so parts whose boxes are ``gap`` apart are at
least ``gap`` apart; the sheet's edges keep the same margin.  The packer is deterministic:
the same design always gives the same sheet.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from ..geometry.arcfit import ArcRing
from ..geometry.bounds import ring_bounds
from ..geometry.outline import place, rotate
from ..profiles.values import LARGEST_LENGTH
from .parts import Part, Placement

__all__ = [
    "SKIRT_MM",
    "Box",
    "pack",
    "upright_angle",
    "part_box",
    "footprint_box",
    "lay_out",
    "sheet_layout",
    "plate_layout",
    "in_place_layout",
    "Plates",
]

_TURN_GAIN = 0.05
"""A part is turned to its smallest bounding rectangle only when that saves more than 5 % of its
box's area: round parts (toothed or not) stay as designed."""
_EPS = 1e-9  # mm: boxes that touch the sheet's edge to within this fit


@dataclass(frozen=True)
class Box:
    """A part's extents when turned by ``angle`` (rad) about its pivot: ``(xmin, ymin, xmax,
    ymax)`` in mm, relative to the pivot."""

    part: str
    angle: float
    bounds: tuple[float, float, float, float]

    @property
    def width(self) -> float:
        return self.bounds[2] - self.bounds[0]

    @property
    def height(self) -> float:
        return self.bounds[3] - self.bounds[1]

    def turned(self) -> Box:
        """The same part a quarter turn further (counter-clockwise): (x, y) → (−y, x)."""
        x0, y0, x1, y1 = self.bounds
        return Box(self.part, self.angle + math.pi / 2, (-y1, x0, -y0, x1))

    def placed_at(self, x: float, y: float) -> Placement:
        """The placement that puts this box's lower-left corner at ``(x, y)``."""
        return Placement(self.part, self.angle, (x - self.bounds[0], y - self.bounds[1]))


def pack(sizes: Sequence[tuple[float, float]], width: float, height: float) -> list[tuple[float, float, bool]] | None:
    """Skyline bottom-left packing of rectangles into ``width`` × ``height``, in the given order.

    Parameters
    ----------
    sizes : sequence of (w, h), mm
        The rectangles, gap included (callers add it to each and to the region).
    width, height : float, mm
        The region.

    Returns
    -------
    list of (x, y, turned) or None
        Each rectangle's lower-left corner and whether it is turned a quarter (then it occupies
        h × w); None when some rectangle finds no place.

    Examples
    --------
    >>> pack([(2.0, 1.0), (2.0, 1.0)], 2.0, 2.0)
    [(0.0, 0.0, False), (0.0, 1.0, False)]
    >>> pack([(3.0, 1.0)], 2.0, 2.0) is None
    True
    """
    skyline = [[0.0, 0.0, width]]  # segments [x, y, w] left to right, covering [0, width]
    spots = []
    for w0, h0 in sizes:
        best = None
        for turned, (w, h) in ((False, (w0, h0)), (True, (h0, w0))):
            if turned and w0 == h0:
                break
            for i, (x, _, _) in enumerate(skyline):
                if x + w > width + _EPS:
                    break
                top, j = 0.0, i
                while j < len(skyline) and skyline[j][0] < x + w - _EPS:
                    top = max(top, skyline[j][1])
                    j += 1
                if top + h > height + _EPS:
                    continue
                key = (top + h, x, turned)
                if best is None or key < best[0]:
                    best = (key, x, top, w, h, turned)
        if best is None:
            return None
        _, x, y, w, h, turned = best
        spots.append((x, y, turned))
        _raise(skyline, x, w, y + h)
    return spots


def _raise(skyline: list[list[float]], x: float, w: float, top: float) -> None:
    """Set the skyline to ``top`` over [x, x + w], merging equal neighbours."""
    end = x + w
    pieces = []
    for sx, sy, sw in skyline:
        if sx < x:
            pieces.append([sx, sy, min(sw, x - sx)])
        if sx + sw > end:
            start = max(sx, end)
            pieces.append([start, sy, sx + sw - start])
    pieces.append([x, top, w])
    pieces.sort()
    merged: list[list[float]] = []
    for piece in pieces:
        if piece[2] <= 0:
            continue
        if merged and merged[-1][1] == piece[1]:
            merged[-1][2] = piece[0] + piece[2] - merged[-1][0]
        else:
            merged.append(piece)
    skyline[:] = merged


def upright_angle(points: np.ndarray) -> float:
    """The turn (rad, in [−π/2, π/2)) that lays ``points`` ((n, 2) float, mm) in their smallest
    bounding rectangle with its long side along x; 0 unless that saves over 5 % of the box."""
    hull = shapely.MultiPoint(points).convex_hull
    upright = np.array(hull.bounds)
    rect = np.asarray(shapely.oriented_envelope(hull).exterior.coords)[:4]
    edges = np.diff(np.vstack([rect, rect[:1]]), axis=0)
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    if lengths[0] * lengths[1] >= (1 - _TURN_GAIN) * np.prod(upright[2:] - upright[:2]):
        return 0.0
    long = edges[int(np.argmax(lengths[:2]))]
    angle = -math.atan2(long[1], long[0])  # the long side turned onto the x axis
    return (angle + math.pi / 2) % math.pi - math.pi / 2  # the nearer of the two ways


def _extents(boxes: list[np.ndarray]) -> tuple[float, float, float, float]:
    b = np.array(boxes)
    return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))


def part_box(part: Part) -> Box:
    """The part turned by :func:`upright_angle` and the exact extents of what a sheet draws of it:
    cut and mark paths with their arcs, and the pivot cross."""
    angle = upright_angle(part.outline.outer)
    boxes = [ring_bounds(ArcRing(rotate(r.vertices, angle), r.bulges)) for r in (*part.cut, *part.mark)]
    if part.pivot_mark > 0:
        boxes.append(np.array([-1.0, -1.0, 1.0, 1.0]) * part.pivot_mark)
    return Box(part.name, angle, _extents(boxes))


def footprint_box(part: Part, sections=None) -> Box:
    """The part turned by :func:`upright_angle` and the extents of its solid on a printer's bed:
    its outline's, or with helical ``sections`` ((n, m, 2) rings, mm) those of every twisted
    section (they reach past the base outline)."""
    angle = upright_angle(part.outline.outer)
    rings = [part.outline.outer] if sections is None else [part.outline.outer, np.reshape(sections, (-1, 2))]
    return Box(part.name, angle, _extents([ring_bounds(rotate(r, angle)) for r in rings]))


def lay_out(
    boxes: Sequence[Box],
    size: tuple[float, float],
    gap: float,
    *,
    key: str,
    what: str,
    edge: float = 0.0,
    from_top: bool = False,
) -> tuple[Placement, ...]:
    """Place every box (one per part laid out) on ``size`` = (w, h) mm, ``gap`` apart and from the
    edges (``edge`` from the edges where that is more); ``from_top``: rows from the top edge down.

    Largest boxes go first (ties by name, so the result is reproducible).  ``key`` is the profile
    key named when they do not fit (``output.sheet``, ``output.bed``), ``what`` the noun
    ("sheet", "bed").

    Raises
    ------
    DesignError
        One line naming ``key``: which part is too large on its own, or the size that would take
        all of them.
    """
    extra = max(0.0, edge - gap)  # the margin beyond the gap, on every side
    size = (size[0] - 2 * extra, size[1] - 2 * extra)
    w, h = size
    order = sorted(boxes, key=lambda b: (-b.width * b.height, b.part))
    spots = _try(order, w, h, gap) if min(size) > 0 else None
    if spots is not None:
        return _placed(order, spots, extra, gap, top=size[1] + 2 * extra if from_top else None)
    counts = Counter(b.part for b in boxes)
    listed = ", ".join(f"{name} ×{n}" if n > 1 else name for name, n in counts.items())
    where = f"{key} = [{w + 2 * extra:g}, {h + 2 * extra:g}] mm with output.gap = {gap:g} mm" + (
        f" and {edge:g} mm from the edges" if extra else ""
    )
    alone = [b for b in order if _try([b], w, h, gap) is None]
    if alone:
        b = alone[0]
        raise DesignError(
            f"{where}: {b.part} ({b.width:.1f} × {b.height:.1f} mm) does not fit on the {what} even alone; "
            + _advice(
                what,
                max(b.width, b.height) + 2 * (gap + extra),
                min(b.width, b.height) + 2 * (gap + extra),
                "at least ",
            )
        )
    lo, hi = 1.0, 2.0
    while _try(order, w * hi, h * hi, gap) is None:
        lo, hi = hi, hi * 2
    while hi - lo > 0.005:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _try(order, w * mid, h * mid, gap) is None else (lo, mid)
    raise DesignError(
        f"{where}: the {len(boxes)} parts ({listed}) do not fit on the {what}; "
        + _advice(what, w * hi + 2 * extra, h * hi + 2 * extra, "")
    )


def _placed(order: Sequence[Box], spots, extra: float, gap: float, top: float | None = None) -> tuple[Placement, ...]:
    """The placements of packed boxes; with ``top`` (the height, mm) packed down from the top edge
    instead of up from the bottom one (the packer's rows mirrored)."""
    placed = []
    for b, (x, y, turned) in zip(order, spots):
        box = b.turned() if turned else b
        y = extra + gap + y if top is None else top - extra - gap - y - box.height
        placed.append(box.placed_at(extra + gap + x, y))
    return tuple(placed)


def _advice(what: str, width: float, height: float, least: str) -> str:
    """The sheet (or bed) to give, never one over the largest length a profile accepts."""
    if max(width, height) > LARGEST_LENGTH:
        allowed = f"at most {LARGEST_LENGTH:g} mm a side"
        return f"no {what} a profile allows ({allowed}) is large enough: make the parts smaller"
    return f"give a {what} of {least}{math.ceil(width)} × {math.ceil(height)} mm"


def _try(order: Sequence[Box], w: float, h: float, gap: float):
    # each box grows by the gap to its right and top; the region by one gap less than the margins
    return pack([(b.width + gap, b.height + gap) for b in order], w - gap, h - gap)


def sheet_layout(parts: Sequence[Part], placements: Sequence[Placement], output) -> tuple[Placement, ...]:
    """Every placed part laid out on ``output.sheet`` (lower-left corner at the origin), each turned
    about its pivot and moved; at least ``output.gap`` apart and from the edges.  The parts sit in
    rows from the sheet's top-left corner down: where an SVG page and a browser begin (a sheet
    laid out from the bottom showed a blank first screen), and where most laser beds home.

    Raises
    ------
    DesignError
        When they do not fit (one line naming ``output.sheet``).
    """
    boxes = {p.name: part_box(p) for p in parts}
    laid = [boxes[pl.part] for pl in placements]
    return lay_out(laid, tuple(output.sheet), output.gap, key="output.sheet", what="sheet", from_top=True)


SKIRT_MM = 7.0
"""Solids keep at least this far from the bed's edges, mm: a slicer's skirt goes around them
(PrusaSlicer's default skirt_distance is 6 mm, plus its line), and must stay on the bed."""


@dataclass(frozen=True)
class Plates:
    """The parts laid out on as many printer beds as they need (``output.bed`` each).

    ``plates``: each bed's placements, the first bed holding the largest parts; ``too_large``:
    the boxes of parts (one per placement) that no bed of that size takes even alone — they are
    left off the plates (each part still has its own STL/3MF), and the design says which.
    """

    plates: tuple[tuple[Placement, ...], ...] = ()
    too_large: tuple[Box, ...] = ()
    bed: tuple[float, float] = (0.0, 0.0)
    margin: float = 0.0
    """Added to a part's box on each side to get the bed it needs (gap and skirt)."""

    def needs(self, box: Box) -> tuple[int, int]:
        """The bed (w, h, mm, rounded up) that takes ``box`` alone, the long side along w."""
        long, short = max(box.width, box.height), min(box.width, box.height)
        return math.ceil(long + 2 * self.margin), math.ceil(short + 2 * self.margin)


def plate_layout(parts: Sequence[Part], placements: Sequence[Placement], output, sections=None) -> Plates:
    """Every placed part laid out on beds of ``output.bed`` (front-left corner at the origin),
    footprints at least ``output.gap`` apart and :data:`SKIRT_MM` (or the gap, if more) from the
    bed's edges; a helical part's footprint is that of its twisted sections (``sections``: name →
    GearSections).  The parts go on as few beds as first-fit takes them, largest first: a bed
    is filled with every part that still fits on it before the next is begun.  Parts too large
    for the bed alone are left off (:attr:`Plates.too_large`)."""
    twisted = {name: g.rings for name, g in (sections or {}).items()}
    boxes = {p.name: footprint_box(p, twisted.get(p.name)) for p in parts}
    laid = [boxes[pl.part] for pl in placements]
    gap = output.gap
    extra = max(0.0, SKIRT_MM - gap)
    w, h = output.bed[0] - 2 * extra, output.bed[1] - 2 * extra
    order = sorted(laid, key=lambda b: (-b.width * b.height, b.part))
    fits = [min(w, h) > 0 and _try([b], w, h, gap) is not None for b in order]
    rest = [b for b, ok in zip(order, fits) if ok]
    plates = []
    while rest:
        chosen, spots, left = [], None, []
        for b in rest:
            tried = _try([*chosen, b], w, h, gap)
            if tried is None:
                left.append(b)
            else:
                chosen, spots = [*chosen, b], tried
        plates.append(_placed(chosen, spots, extra, gap))
        rest = left
    return Plates(
        plates=tuple(plates),
        too_large=tuple(b for b, ok in zip(order, fits) if not ok),
        bed=tuple(output.bed),
        margin=gap + extra,
    )


def in_place_layout(parts: Sequence[Part], placements: Sequence[Placement], output, sections=None) -> Plates:
    """The assembly on one bed as placed, printed in place (a set whose parts cannot be put
    together loose: stacked tooth bands), its box centred on ``output.bed``.  A set whose box
    with the margins (gap and skirt, as :func:`plate_layout`'s) exceeds the bed is on no plate:
    :attr:`Plates.too_large` holds its box, named after its largest part."""
    outlines = {p.name: p.outline.outer for p in parts}
    bounds = [ring_bounds(place(outlines[pl.part], pl.angle, pl.offset)) for pl in placements]
    lo = np.min([b[:2] for b in bounds], axis=0)
    hi = np.max([b[2:] for b in bounds], axis=0)
    margin = output.gap + max(0.0, SKIRT_MM - output.gap)
    bed = tuple(output.bed)
    largest = max(parts, key=lambda p: abs(p.outline.area)).name
    box = Box(largest, 0.0, (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])))
    if box.width + 2 * margin > bed[0] or box.height + 2 * margin > bed[1]:
        return Plates(too_large=(box,), bed=bed, margin=margin)
    dx, dy = (float(v) for v in 0.5 * (np.asarray(bed) - lo - hi))
    moved = tuple(Placement(pl.part, pl.angle, (pl.offset[0] + dx, pl.offset[1] + dy)) for pl in placements)
    return Plates(plates=(moved,), bed=bed, margin=margin)
