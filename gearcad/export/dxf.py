"""DXF files for laser cutters, CAD and CAM: closed outlines on named layers, units mm.

Three encodings of the same geometry (``[output] dxf``):

* ``polyline`` — one closed LWPOLYLINE per cut ring, arcs as bulges (laser software, CAD);
* ``lines-arcs`` — the cut rings as LINE and ARC entities sharing end points (CAM, and readers
  that take ARC entities but not bulges);
* ``polyline-flat`` — one closed LWPOLYLINE per cut ring without bulges, chords within the
  tolerance (the simplest importers).

What every encoding shares, so that each program reads the part right with its defaults:

* **Cut rings are the only region-forming entities.**  Everything engraved (pitch curves, pivot
  crosses: every layer but the cut layer) is written as classic 2-D POLYLINE entities, closed
  where the path is, with bulges.  Laser software, LibreCAD, Inkscape and FreeCAD read them as
  the same paths; OpenSCAD reads only LINE, LWPOLYLINE, ARC, CIRCLE and ELLIPSE (it has never
  read POLYLINE) and so a plain ``import("part.dxf")`` gives the cut region alone, with a
  warning that it skipped the POLYLINE entities — instead of the even-odd mix of outline and
  pitch curve it made when marks were LWPOLYLINEs.
* **No arc sweeps so far that its chord matters.**  A reader that ignores bulges (OpenSCAD's
  LWPOLYLINE, many simple importers) draws every arc as its chord; arcs are split (into equal
  sub-arcs: the same path, more vertices) so that the polygon of the written vertices stays
  within :data:`CHORD_AREA` of each ring's area — the segments between arcs and chords summed,
  a chord of radius r and sweep θ cutting off r²(θ − sin θ)/2 — and of each part's net area
  (outer ring less its holes, where chords of convex and concave arcs partly cancel); engraved
  rings within :data:`MARK_CHORD_AREA` of theirs.  A bore stays round (a 3–5 arc circle becomes
  a 52-gon), a toothed outline at 0.001 mm keeps its arcs as they are.
  ARC entities (``lines-arcs``) are split alike, so OpenSCAD's own coarse tessellation of an
  ARC (never fewer than one chord) stays within the same bound.
* **Header:** R2010, ``$INSUNITS`` = mm, ``$MEASUREMENT`` = metric, ``$EXTMIN``/``$EXTMAX`` the
  exact extents (:func:`gearcad.export.bounds.drawing_bounds`), the ``*Active`` viewport centred on
  them (a reader opens on the part, not on the origin), paper scale 1:1 with the drawing inset
  by :data:`PAPER_MARGIN_MM` (``$PSVPSCALE``, ``$PINSBASE``: LibreCAD's ``dxf2pdf`` with no
  options prints the part, not a blank page); no ``$PDMODE``/``$PDSIZE``
  (point display, which Inkscape warns about on every import; the files hold no points).
* **Reproducible bytes:** ezdxf's fixed dates and ids, and the CLASSES section registered in
  sorted order (ezdxf adds the classes of the entity types in use in set order, which follows
  the process's hash seed).
"""

from __future__ import annotations

import heapq
import math
from contextlib import contextmanager
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf import units

from ..formats import by_name
from ..geometry import bulge as B
from ..geometry.arcfit import ArcRing
from .bounds import drawing_bounds
from .drawing import Drawing
from .dxf_marks import Marks

__all__ = ["FLAVOURS", "CHORD_AREA", "MARK_CHORD_AREA", "write_dxf", "limit_sweep", "ring_area_with_arcs"]

FLAVOURS = by_name("dxf").flavours
CHORD_AREA = 0.0025
"""Largest share of a ring's (and of a part's) area that the chords of its written arcs may cut
off: what a reader ignoring bulges loses at most (0.25 %, half the 0.5 % the consumer table
promises).  Engraved rings take :data:`MARK_CHORD_AREA`."""
MARK_CHORD_AREA = 0.004
"""The same for engraved rings (pitch curves): no part's size depends on them, so only their
shape is kept — a pitch circle stays round, not a pentagon — within 0.4 % of their area."""

PAPER_MARGIN_MM = 10.0
"""Where a printed drawing starts on the paper (``$PINSBASE``), mm from its lower-left corner."""
_MIN_SWEEP = math.radians(1.0)
"""No arc is split into pieces under 1° (their chords cut off under 5e-5 of their sector)."""
_LAYER_COLOURS = {"CUT": 1, "MARK": 5}
_DROPPED_HEADER = ("$PDMODE", "$PDSIZE")


@contextmanager
def _reproducible():
    """ezdxf's fixed dates, ids and markers: the same drawing always gives the same bytes."""
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before


def _x_minus_sin(x: np.ndarray) -> np.ndarray:
    """x − sin x without cancellation for small x (series to x⁷: relative error < 1e-16 below 0.01)."""
    x = np.asarray(x, dtype=float)
    x2 = x * x
    series = x * x2 / 6 * (1 - x2 / 20 * (1 - x2 / 42))
    return np.where(np.abs(x) < 0.01, series, x - np.sin(x))


def _arc_shape(v: np.ndarray, bulges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Radius and signed sweep (rad, positive counter-clockwise) of every segment (0, 0 for lines)."""
    chord = np.hypot(*(np.roll(v, -1, axis=0) - v).T)
    sweep = B.sweep(bulges)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius = np.where(bulges != 0, B.radius(chord, sweep), 0.0)
    return radius, sweep


def ring_area_with_arcs(ring) -> float:
    """Signed area of a closed ring with its arcs (mm², positive counter-clockwise): the
    shoelace area of the vertices plus each arc's circular segment r²(θ − sin θ)/2."""
    v, bulges = B.segments(ring)
    x, y = v[:, 0], v[:, 1]
    polygon = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    radius, sweep = _arc_shape(v, bulges)
    return polygon + float(np.sum(radius**2 * _x_minus_sin(sweep) / 2))


def _chord_loss(radius: float, sweep: float, pieces: int) -> float:
    """Area between an arc and the chords of ``pieces`` equal sub-arcs: pieces·r²(θ/n − sin θ/n)/2
    (one arc at a time, in floats: the greedy splitting calls it thousands of times)."""
    x = abs(sweep) / pieces
    x2 = x * x
    x_minus_sin = x * x2 / 6 * (1 - x2 / 20 * (1 - x2 / 42)) if x < 0.01 else x - math.sin(x)
    return pieces * radius * radius * x_minus_sin / 2


def _allocate(arcs: list[tuple[float, float]], pieces: list[int], budget: float) -> None:
    """Split the arcs (radius, sweep) further, in place in ``pieces``, until their chords cut off at
    most ``budget`` in all: greedily where one more piece saves the most (the loss is convex in
    the piece count, so this reaches the budget with the fewest pieces)."""
    loss = [_chord_loss(r, t, n) for (r, t), n in zip(arcs, pieces)]
    total = sum(loss)
    if total <= budget:  # within it as they are (a toothed outline at a fine tolerance)
        return
    heap = [
        (-(loss[i] - _chord_loss(r, t, pieces[i] + 1)), i)
        for i, (r, t) in enumerate(arcs)
        if abs(t) / (pieces[i] + 1) >= _MIN_SWEEP
    ]
    heapq.heapify(heap)
    while total > budget and heap:
        gain, i = heapq.heappop(heap)
        pieces[i] += 1
        total += gain
        r, t = arcs[i]
        loss[i] = _chord_loss(r, t, pieces[i])
        if abs(t) / (pieces[i] + 1) >= _MIN_SWEEP:
            heapq.heappush(heap, (-(loss[i] - _chord_loss(r, t, pieces[i] + 1)), i))


def _balance(arcs: list[tuple[float, float]], pieces: list[int], budget: float) -> None:
    """Split the arcs (radius, sweep) further, in place, until the area their chords change in
    all is at most ``budget``: a counter-clockwise arc's chord takes its segment away, a
    clockwise arc's adds it, so the net change is Σ sign(θ)·loss; split on the side that
    outweighs, where one more piece saves the most."""
    loss = [_chord_loss(r, t, n) for (r, t), n in zip(arcs, pieces)]
    net = sum(math.copysign(x, t) for x, (_, t) in zip(loss, arcs))
    if abs(net) <= budget:  # most parts: their rings, each within the budget, are within it together
        return
    heaps: dict[bool, list] = {True: [], False: []}
    for i, (r, t) in enumerate(arcs):
        if abs(t) / (pieces[i] + 1) >= _MIN_SWEEP:
            heaps[t > 0].append((-(loss[i] - _chord_loss(r, t, pieces[i] + 1)), i))
    for heap in heaps.values():
        heapq.heapify(heap)
    while abs(net) > budget and heaps[net > 0]:
        heap = heaps[net > 0]
        gain, i = heapq.heappop(heap)
        r, t = arcs[i]
        pieces[i] += 1
        net -= math.copysign(-gain, t)  # -gain: what this split saves
        loss[i] = _chord_loss(r, t, pieces[i])
        if abs(t) / (pieces[i] + 1) >= _MIN_SWEEP:
            heapq.heappush(heap, (-(loss[i] - _chord_loss(r, t, pieces[i] + 1)), i))


def _split(v: np.ndarray, bulges: np.ndarray, pieces: np.ndarray) -> ArcRing:
    """The ring with segment k cut into ``pieces[k]`` equal sub-arcs (same path, more vertices)."""
    pieces = np.maximum(np.asarray(pieces, dtype=int), 1)
    pieces = np.where(bulges != 0, pieces, 1)
    owner = np.repeat(np.arange(len(v)), pieces)  # the segment each new vertex lies on
    step = np.arange(len(owner)) - np.repeat(np.cumsum(pieces) - pieces, pieces)  # 0 … pieces − 1
    sweep = B.sweep(bulges)
    chord = np.roll(v, -1, axis=0) - v
    left = np.column_stack([-chord[:, 1], chord[:, 0]])
    turn = sweep[owner] * step / pieces[owner]
    c, s = np.cos(turn), np.sin(turn)
    with np.errstate(divide="ignore", invalid="ignore"):  # lines: no centre, and only their start is kept
        # the centre by cot(θ/2), as written since the first files (B.centres differs in the last bit)
        centre = (v + np.roll(v, -1, axis=0)) / 2 + left / 2 * (np.cos(sweep / 2) / np.sin(sweep / 2))[:, None]
        rel = (v - centre)[owner]
        rotated = centre[owner] + np.column_stack([c * rel[:, 0] - s * rel[:, 1], s * rel[:, 0] + c * rel[:, 1]])
    out_v = np.where((step > 0)[:, None], rotated, v[owner])
    out_b = np.where(pieces[owner] > 1, np.tan(sweep[owner] / (4 * pieces[owner])), bulges[owner])
    return ArcRing(out_v, out_b)


def _inside(point: np.ndarray, ring: np.ndarray) -> bool:
    """Whether a point lies inside a polygon (crossing number)."""
    x, y = point
    a, b = ring, np.roll(ring, -1, axis=0)
    straddle = (a[:, 1] > y) != (b[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross_x = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return bool(np.count_nonzero(straddle & (cross_x > x)) % 2)


def limit_sweep(rings: list, *, regions: bool, share: float = CHORD_AREA) -> list:
    """The rings with their arcs split so that a reader drawing every arc as its chord stays
    within ``share`` of each ring's area (the segments between arcs and chords summed) and, for
    ``regions`` (a cut layer: outer rings counter-clockwise, holes clockwise), of each part's
    net area (outer ring less the holes inside it).  No arc is cut into pieces under 1°.  Plain
    rings (no bulges) are returned as they are.

    Examples
    --------
    A circle of radius 1 written as two half-circle arcs, with share = 0.5 %: split into 18 and
    19 arcs, the 37-gon of their end points falls 0.48 % short of π (36 arcs would miss by more
    than 0.5 %: 1 − 36·sin(10°)/(2π) = 0.51 %).

    >>> circle = ArcRing(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 1.0]))
    >>> len(limit_sweep([circle], regions=False, share=0.005)[0].vertices)
    37
    """
    arrays = [B.segments(r) for r in rings]
    shapes = [_arc_shape(v, b) for v, b in arrays]
    pieces = [np.ones(len(v), dtype=int) for v, _ in arrays]
    areas = [ring_area_with_arcs(r) for r in rings]
    for k, ((radius, sweep), area) in enumerate(zip(shapes, areas)):
        arcs = np.nonzero(sweep)[0]
        counts = [1] * len(arcs)
        _allocate(list(zip(radius[arcs].tolist(), sweep[arcs].tolist())), counts, share * abs(area))
        pieces[k][arcs] = counts
    if regions:
        outers = [k for k, a in enumerate(areas) if a > 0]
        groups = {k: [k] for k in outers}
        # each outer ring as a polygon within 0.5 % of its radii (arcs of at most π/16) for the
        # containment test: its own vertices alone may be a triangle
        fences = {
            o: _split(*arrays[o], np.maximum(1, np.ceil(np.abs(shapes[o][1]) / (math.pi / 16)))).vertices
            for o in outers
        }
        for k, a in enumerate(areas):
            if a < 0:
                hosts = [o for o in outers if _inside(arrays[k][0][0], fences[o])]
                if hosts:
                    groups[min(hosts, key=lambda o: areas[o])].append(k)
        for members in groups.values():
            index = [(k, np.nonzero(shapes[k][1])[0]) for k in members]
            counts = [m for k, i in index for m in pieces[k][i].tolist()]
            arcs = [arc for k, i in index for arc in zip(shapes[k][0][i].tolist(), shapes[k][1][i].tolist())]
            _balance(arcs, counts, share * abs(sum(areas[k] for k in members)))
            for (k, i), m in zip(index, np.split(np.asarray(counts, dtype=int), np.cumsum([len(i) for _, i in index]))):
                pieces[k][i] = m
    return [ring if not np.any(p > 1) else _split(v, b, p) for ring, (v, b), p in zip(rings, arrays, pieces)]


def _arcs(a: np.ndarray, b: np.ndarray, bulges: np.ndarray) -> tuple[list, list, list, list]:
    """Centres, radii and start and end angles (degrees) of the ARCs (always counter-clockwise) from
    ``a`` to ``b`` ((m, 2) each) with these bulges, as lists for ezdxf: sines, cosines and angles
    in scalar floats (``math``), the rest element by element, the digits written since the first
    files (:func:`gearcad.geometry.bulge.centres` differs in the last bit or two)."""
    sweep = [4 * math.atan(x) for x in bulges.tolist()]
    sin = np.array([math.sin(t / 2) for t in sweep])
    cos = np.array([math.cos(t / 2) for t in sweep])
    sign = np.array([math.copysign(1.0, t) for t in sweep])
    chord = b - a
    length = np.hypot(chord[:, 0], chord[:, 1])
    radius = length / (2 * np.abs(sin))
    normal = np.column_stack([-chord[:, 1], chord[:, 0]]) / length[:, None]
    centre = (a + b) / 2 + normal * radius[:, None] * cos[:, None] * sign[:, None]
    counter = (np.array(sweep) > 0)[:, None]
    ends = (np.where(counter, a, b) - centre, np.where(counter, b, a) - centre)  # from the centre
    start, end = ([math.degrees(math.atan2(y, x)) for x, y in e.tolist()] for e in ends)
    return centre.tolist(), radius.tolist(), start, end


def _set_extents(doc, msp, bounds) -> None:
    """The drawing's extents, the view a reader opens with and how it prints with no options."""
    xmin, ymin, xmax, ymax = bounds
    msp.dxf.extmin = (xmin, ymin, 0.0)
    msp.dxf.extmax = (xmax, ymax, 0.0)
    doc.header["$EXTMIN"] = (xmin, ymin, 0.0)
    doc.header["$EXTMAX"] = (xmax, ymax, 0.0)
    # the view a reader opens with (LibreCAD, its dxf2pdf): the extents with a margin; as
    # high as the drawing is wide too, so any window of aspect >= 1 shows all of it
    view = 1.1 * max(xmax - xmin, ymax - ymin)
    doc.set_modelspace_vport(view, ((xmin + xmax) / 2, (ymin + ymax) / 2))
    # printing with no options (LibreCAD's dxf2pdf): at 1:1, the drawing's lower-left corner
    # PAPER_MARGIN_MM in from the paper's (without these the page came out blank)
    doc.header["$PSVPSCALE"] = 1.0
    doc.header["$PINSBASE"] = (PAPER_MARGIN_MM - xmin, PAPER_MARGIN_MM - ymin, 0.0)
    doc.header["$PLIMMIN"] = (0.0, 0.0)
    doc.header["$PLIMMAX"] = (xmax - xmin + 2 * PAPER_MARGIN_MM, ymax - ymin + 2 * PAPER_MARGIN_MM)


def write_dxf(path: Path, drawing: Drawing, *, flavour: str = "polyline", cut_layer: str | None = None) -> int:
    """Write the drawing; return the number of vertices (segment end points) written.

    ``cut_layer`` names the layer whose closed rings are the part (written as the flavour
    says); it defaults to the drawing's first layer of closed rings (``part_drawing`` and
    ``assembly_drawing`` put the cut layer first).  Every other ring and every stroke is
    engraving, written as POLYLINE entities.  No creation time or random id: the same drawing
    gives the same bytes in any process.
    """
    if flavour not in FLAVOURS:
        raise ValueError(f"unknown DXF flavour {flavour!r}")
    if cut_layer is None:
        cut_layer = next(iter(drawing.closed), None)
    with _reproducible():
        doc = ezdxf.new("R2010", setup=False)
        doc.units = units.MM
        doc.header["$MEASUREMENT"] = 1
        for name in _DROPPED_HEADER:
            if name in doc.header:
                del doc.header[name]
        for name in sorted({*drawing.closed, *drawing.strokes}):
            layer = doc.layers.add(name, color=_LAYER_COLOURS.get(name, 7))
            if name in drawing.descriptions:
                layer.description = drawing.descriptions[name]
        msp = doc.modelspace()
        marks = Marks(doc)
        count = 0
        for layer, rings in drawing.closed.items():
            cut = layer == cut_layer
            if flavour == "polyline-flat":
                if any(np.any(B.segments(r)[1]) for r in rings):
                    raise ValueError("the flat encoding takes plain rings sampled within the tolerance")
            else:
                rings = limit_sweep(list(rings), regions=cut, share=CHORD_AREA if cut else MARK_CHORD_AREA)
            for ring in rings:
                count += _ring(msp, ring, layer, flavour if cut else "engrave", marks)
        for layer, strokes in drawing.strokes.items():
            for stroke in strokes:
                if isinstance(stroke, ArcRing):  # an open path with arcs (dashes)
                    marks.add(msp, np.column_stack([stroke.vertices, stroke.bulges]).tolist(), layer)
                    count += len(stroke.vertices)
                    continue
                marks.add(msp, np.asarray(stroke, dtype=float).tolist(), layer)
                count += len(stroke)
        if any(drawing.closed.values()) or any(drawing.strokes.values()):
            _set_extents(doc, msp, drawing_bounds(drawing))
        for name in sorted(doc.entitydb.dxf_types_in_use()):  # before ezdxf adds them in set order
            doc.classes.add_class(name)
        marks.save(path)
    return count


def _ring(msp, ring, layer: str, flavour: str, marks: Marks) -> int:
    v, bulges = B.segments(ring)
    if flavour == "lines-arcs":
        n = len(v)
        arcs = np.nonzero(bulges)[0]
        arc = dict(zip(arcs.tolist(), zip(*_arcs(v[arcs], np.roll(v, -1, axis=0)[arcs], bulges[arcs]))))
        points = v.tolist()
        for k in range(n):
            if k in arc:
                centre, radius, start, end = arc[k]
                msp.add_arc(centre, radius, start, end, dxfattribs={"layer": layer})
            else:
                msp.add_line(points[k], points[(k + 1) % n], dxfattribs={"layer": layer})
        return n
    # (x, y, bulge) rows: the widths are 0 by default, and each column more is work per vertex
    points = np.column_stack([v, bulges]).tolist()
    if flavour == "engrave":
        marks.add(msp, points, layer, close=True)
    else:
        msp.add_lwpolyline(points, format="xyb", close=True, dxfattribs={"layer": layer})
    return len(v)
