"""SVG for laser software, read back by an independent reader (svgelements)."""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from svgelements import SVG, Arc, Close, Color, Group, Length, Line, Matrix, Move
from svgelements import Path as SvgPath

from gearcad.export.bounds import drawing_bounds, ring_bounds
from gearcad.export.drawing import Drawing, cross
from gearcad.export.svg import write_svg
from gearcad.geometry.arcfit import ArcRing, arc_points, fit_arcs

CUT, MARK = "CUT", "MARK"
ARC_SAMPLES = 4001  # per arc: chord-area error (Δφ)²/6 relative ≈ 1e-7 for a half turn


def exact_area(ring) -> float:
    """Signed area of a ring with bulges: shoelace of the vertices plus each arc's circular
    segment r²(θ − sin θ)/2 (θ signed, so it adds for counter-clockwise arcs).  With
    r = chord / (2 sin(θ/2)) that is chord² (θ − sin θ) / (8 sin²(θ/2)), whose last factor
    tends to 2θ/3 (1 + θ²/30) for small θ: used there, where both parts underflow."""
    v, b = (ring.vertices, ring.bulges) if isinstance(ring, ArcRing) else (np.asarray(ring), np.zeros(len(ring)))
    w = np.roll(v, -1, axis=0)
    polygon = 0.5 * float(np.sum(v[:, 0] * w[:, 1] - v[:, 1] * w[:, 0]))
    theta = 4 * np.arctan(b)
    chord2 = ((w - v) ** 2).sum(axis=1)
    small = np.abs(theta) < 1e-3
    safe = np.where(small, 1.0, theta)
    factor = np.where(small, 2 * theta / 3 * (1 + theta**2 / 30), (safe - np.sin(safe)) / np.sin(safe / 2) ** 2)
    return polygon + float(np.sum(chord2 * factor / 8))


def drawn_segments(path: SvgPath) -> int:
    """Lines and arcs svgelements reads, with the closing line when Z draws one."""
    return sum(
        isinstance(s, (Line, Arc)) or (isinstance(s, Close) and s.start != s.end)
        for s in path.segments(transformed=False)
    )


def signed_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def read(path):
    """The parsed document and its groups.  Not reified: the paths keep their user units, which
    ``check_document`` shows are mm (svgelements' viewBox transform maps them onto the page)."""
    svg = SVG.parse(str(path), reify=False)
    groups = {g.id: g for g in svg.elements() if isinstance(g, Group) and g.id in ("cut", "mark")}
    return svg, groups


def points_of(path: SvgPath) -> np.ndarray:
    """The path sampled with svgelements' own ``npoint()`` (``point()`` over an array): every
    vertex, arcs finely; in user units (mm) with y un-flipped: the drawing's own coordinates."""
    out = []
    for seg in path.segments(transformed=False):
        if isinstance(seg, Arc):
            out.append(np.asarray(seg.npoint(np.linspace(0, 1, ARC_SAMPLES)[:-1]), dtype=float))
        elif isinstance(seg, (Line, Close)):
            out.append(np.array([[seg.start.x, seg.start.y]]))
    xy = np.vstack(out)
    return np.column_stack([xy[:, 0], -xy[:, 1]])


def paths_in(group: Group) -> list[SvgPath]:
    return [e for e in group if isinstance(e, SvgPath)]


def check_document(path, drawing: Drawing) -> tuple[SVG, dict]:
    """What every written file must satisfy; returns the parsed document and its groups."""
    root = ET.parse(path).getroot()
    width, height = root.get("width"), root.get("height")
    assert width.endswith("mm") and height.endswith("mm")
    box = [float(t) for t in root.get("viewBox").split()]
    assert [float(width[:-2]), float(height[:-2])] == box[2:]  # 1 user unit = 1 mm
    xmin, ymin, xmax, ymax = drawing_bounds(drawing)
    assert box == pytest.approx([xmin - 1, -ymax - 1, xmax - xmin + 2, ymax - ymin + 2], abs=1e-6)
    svg, groups = read(path)
    page = Matrix(svg.viewbox.transform(svg))  # user units onto the page, in px
    mm = Length("1mm").value(ppi=96)  # svgelements' px per mm
    corner = page.point_in_matrix_space((box[0], box[1]))
    far = page.point_in_matrix_space((box[0] + box[2], box[1] + box[3]))
    assert (corner.x, corner.y) == pytest.approx((0, 0), abs=1e-9)
    assert (far.x, far.y) == pytest.approx((svg.width, svg.height), rel=1e-12)
    assert (svg.width, svg.height) == pytest.approx((box[2] * mm, box[3] * mm), rel=1e-12)
    assert groups["cut"].values["stroke"] == "#ff0000" and groups["mark"].values["stroke"] == "#0000ff"
    inkscape = "{http://www.inkscape.org/namespaces/inkscape}"
    layers = {g.get("id"): g for g in root.iter("{http://www.w3.org/2000/svg}g")}
    assert layers["cut"].get(inkscape + "groupmode") == "layer" and layers["cut"].get(inkscape + "label") == CUT
    assert layers["mark"].get(inkscape + "label") == MARK
    for name, layer in (("cut", CUT), ("mark", MARK)):
        paths = paths_in(groups[name])
        rings, strokes = drawing.closed.get(layer, []), drawing.strokes.get(layer, [])
        assert len(paths) == len(rings) + len(strokes)
        for p in paths:
            assert p.stroke == Color("#ff0000" if name == "cut" else "#0000ff") and p.fill.value is None
        for p, ring in zip(paths, rings):  # one closed path per ring
            segs = list(p.segments(transformed=False))
            assert isinstance(segs[0], Move) and isinstance(segs[-1], Close)
            assert sum(isinstance(s, Move) for s in segs) == 1
            area = signed_area(points_of(p))
            assert area == pytest.approx(exact_area(ring), rel=1e-4)
        for p, stroke in zip(paths[len(rings) :], strokes):  # strokes stay open
            segs = list(p.segments(transformed=False))
            assert not any(isinstance(s, Close) for s in segs)
            xy = np.array([(s.end.x, -s.end.y) for s in segs])
            if isinstance(stroke, ArcRing):  # a dash with arcs: from its first vertex to its last
                assert np.allclose(xy[[0, -1]], stroke.vertices[[0, -1]], atol=1e-6)
                continue
            assert np.allclose(xy, stroke, atol=1e-6)
    again = path.with_name("again.svg")
    count = write_svg(again, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    assert again.read_bytes() == path.read_bytes()
    assert count == sum(drawn_segments(p) for g in groups.values() for p in paths_in(g))
    return svg, groups


def relative_area_error(group, ring) -> float:
    return abs(signed_area(points_of(paths_in(group)[0])) / exact_area(ring) - 1)


def test_bounds_use_the_arc_extremes_not_only_the_vertices():
    # a quarter-circle bulge from (10, 0) to (0, 10) reaches radius 10 at 45°: x and y up to 10,
    # and a half circle below the chord from (-10, 0) to (10, 0) reaches y = -10
    ring = ArcRing(np.array([[-10.0, 0.0], [10.0, 0.0], [0.0, 10.0]]), np.array([1.0, math.tan(math.pi / 8), 0.0]))
    assert ring_bounds(ring) == pytest.approx([-10, -10, 10, 10], abs=1e-12)
    assert ring_bounds(ring.vertices) == pytest.approx([-10, 0, 10, 10], abs=1e-12)
    dense = arc_points(ring, 1e-9)
    box = [*dense.min(axis=0), *dense.max(axis=0)]
    assert ring_bounds(ring) == pytest.approx(box, abs=1e-8)


def test_drawing_bounds_close_each_ring_on_its_own_first_vertex():
    # all rings are bounded in one pass over their joined vertices: the half circle's closing
    # arc, (-1, 0) back to (1, 0) through (0, -1), must not run on to the next ring's first
    # vertex (10, 10), which would reach far past both
    half = ArcRing(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([0.0, 1.0]))
    triangle = np.array([[10.0, 10.0], [11.0, 10.0], [10.0, 11.0]])
    dash = ArcRing(np.array([[0.0, 5.0], [2.0, 5.0]]), np.array([-1.0, 0.0]))  # above its chord, to y = 6
    drawing = Drawing({CUT: [half, triangle]}, {MARK: [dash, cross((20.0, 0.0), 1.0)[0]]}, {})
    assert drawing_bounds(drawing) == (-1.0, -1.0, 21.0, 11.0)
    boxes = np.array([ring_bounds(r) for r in (half, triangle, dash)])
    assert ring_bounds(half).tolist() == [-1.0, -1.0, 1.0, 0.0]
    assert drawing_bounds(Drawing({CUT: [half, triangle, dash]}, {}, {})) == (
        *boxes[:, :2].min(axis=0),
        *boxes[:, 2:].max(axis=0),
    )


def test_circle_of_four_arcs(tmp_path):
    square = 10 * np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])
    ring = ArcRing(square, np.full(4, math.tan(math.pi / 8)))
    drawing = Drawing({CUT: [ring], MARK: []}, {MARK: cross((0.0, 0.0), 1.0)}, {})
    path = tmp_path / "circle.svg"
    assert write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear") == 4 + 2
    _, groups = check_document(path, drawing)
    assert exact_area(ring) == pytest.approx(100 * math.pi, rel=1e-15)
    assert relative_area_error(groups["cut"], ring) < 1e-6
    assert [float(t) for t in ET.parse(path).getroot().get("viewBox").split()] == [-11, -11, 22, 22]
    assert path.read_text(encoding="utf-8").count(" A 10 10 0 0 0 ") == 4  # counter-clockwise: sweep 0


def test_asymmetric_polygon_with_a_hole_is_not_mirrored(tmp_path):
    outer = np.array([[0.0, 0.0], [30.0, 0.0], [30.0, 5.0], [8.0, 5.0], [8.0, 20.0], [0.0, 20.0]])  # an L
    hole = ArcRing(np.array([[2.0, 14.0], [6.0, 14.0]]), np.array([-1.0, -1.0]))  # clockwise circle r 2
    marks = [np.array([[25.0, 2.0], [28.0, 4.0]])]
    drawing = Drawing({CUT: [ArcRing(outer, np.zeros(6)), hole], MARK: [outer[::-1] + [40, 0]]}, {MARK: marks}, {})
    path = tmp_path / "l.svg"
    write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    _, groups = check_document(path, drawing)
    cut = [points_of(p) for p in paths_in(groups["cut"])]
    assert signed_area(cut[0]) == pytest.approx(30 * 5 + 8 * 15) and signed_area(cut[1]) < 0
    assert signed_area(cut[1]) == pytest.approx(-4 * math.pi, rel=1e-6)
    # the foot of the L runs to +x and the hole sits in its upright at upper left, as drawn
    read_back = shapely.Polygon(cut[0], [cut[1]])
    drawn = shapely.Polygon(outer, [arc_points(hole, 1e-6)])
    mirrored = shapely.Polygon(outer * [1, -1])
    assert read_back.symmetric_difference(drawn).area < 1e-3
    assert read_back.symmetric_difference(mirrored).area > 100  # the check can fail
    assert read_back.contains(shapely.Point(25, 2)) and not read_back.contains(shapely.Point(25, 18))
    assert not read_back.contains(shapely.Point(4, 14)) and read_back.contains(shapely.Point(4, 6))


def _gear_drawing():
    """A real part: the toothed elliptic gear of the export tests, cut outline with its bore
    and pitch curve fitted with arcs, and the pivot cross (``export.drawing.part_drawing``)."""
    from gearcad.export.drawing import part_drawing
    from gearcad.profiles import parse_profile

    from .conftest import drawn

    params = parse_profile(
        {
            "name": "small",
            "gear1": {"name": "a", "curve": "ellipse", "pivot": "focus", "a": 20.0, "b": 16.0},
            "gear2": {"name": "b", "lobes": 1},
            "teeth": {"count": 25},
            "output": {"tolerance": 0.01, "kerf": 0.1, "charts": False, "animation": False},
            "bore": {"diameter": 3.0},
        }
    )
    d = drawn(params)  # (the drawing is tested here: no fit, no band)
    return part_drawing(d, d.parts()[0]), params.output


def test_toothed_gear_with_arcs(tmp_path):
    drawing, out = _gear_drawing()
    assert (out.cut_layer, out.mark_layer) == (CUT, MARK)
    outline = drawing.closed[CUT][0]
    assert isinstance(outline, ArcRing) and outline.arcs > 50
    path = tmp_path / "gear.svg"
    n = write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    edges = sum(len(r.vertices) for rings in drawing.closed.values() for r in rings)
    wide = sum(int(np.count_nonzero(np.abs(r.bulges) > math.tan(math.pi / 8))) for r in drawing.closed[CUT])
    assert n >= edges + 2 + wide  # every edge, the cross, and arcs of more than a quarter turn in pieces
    _, groups = check_document(path, drawing)
    assert "<desc>kerf compensation" in path.read_text(encoding="utf-8")
    assert relative_area_error(groups["cut"], outline) < 1e-6
    # un-flipped, the outline passes through every vertex of the drawing in order
    first = points_of(paths_in(groups["cut"])[0])
    assert np.abs(first[0] - outline.vertices[0]).max() < 1e-6
    assert shapely.Polygon(first).buffer(1e-5).contains(shapely.MultiPoint(outline.vertices))


def test_a_fitted_ellipse_and_circle(tmp_path):
    t = np.linspace(0, 2 * math.pi, 3000, endpoint=False)
    ellipse = fit_arcs(np.column_stack([25 * np.cos(t), 12 * np.sin(t)]), 1e-3)
    circle = fit_arcs(5 * np.column_stack([np.cos(t), -np.sin(t)]) + [10, 3], 1e-3)  # a clockwise hole
    drawing = Drawing({CUT: [ellipse, circle], MARK: []}, {}, {})
    path = tmp_path / "ellipse.svg"
    write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    _, groups = check_document(path, drawing)
    paths = paths_in(groups["cut"])
    assert signed_area(points_of(paths[0])) > 0 > signed_area(points_of(paths[1]))


@pytest.mark.parametrize("bulge", [0.999, 1.0, 1.5, 3.0, -2.0, 50.0])
def test_half_turns_and_large_arcs(tmp_path, bulge):
    # a circular segment on the chord (0, 0)–(8, 0): near a half turn an SVG radius is
    # ill-conditioned, past it the arc is the large one; both must read back at the exact area
    ring = ArcRing(np.array([[0.0, 0.0], [8.0, 0.0]]), np.array([0.0, bulge]))
    drawing = Drawing({CUT: [ring], MARK: []}, {}, {})
    path = tmp_path / "segment.svg"
    n = write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    _, groups = check_document(path, drawing)
    assert n == 1 + math.ceil(abs(4 * math.atan(bulge)) / (math.pi / 2) - 1e-9)
    assert relative_area_error(groups["cut"], ring) < 1e-6


@pytest.mark.parametrize("sweep", [5e-6, 2e-5])
def test_arcs_of_tiny_sweep(tmp_path, sweep):
    # on a 60 mm chord: below 1e-5 rad the arc is written as its chord (straying by the sagitta,
    # 60 mm × θ/8 ≤ 75 nm); above, as an arc that svgelements reads back at its sagitta
    ring = ArcRing(np.array([[0.0, 0.0], [60.0, 0.0], [30.0, 20.0]]), np.array([math.tan(sweep / 4), 0.0, 0.0]))
    path = tmp_path / "flat.svg"
    write_svg(path, Drawing({CUT: [ring]}, {}, {}), cut_layer=CUT, mark_layer=MARK)
    data = path.read_text(encoding="utf-8")
    assert (" A " in data) == (sweep > 1e-5)
    _, groups = read(path)
    lowest = points_of(paths_in(groups["cut"])[0])[:, 1].min()
    sagitta = 60 * sweep / 8
    assert lowest == pytest.approx(0 if sweep < 1e-5 else -sagitta, abs=1.25e-6 * 60 * 0.1)
    assert abs(lowest + sagitta) <= 1.25e-6 * 60


def test_layers_other_than_cut_and_mark_are_refused(tmp_path):
    drawing = Drawing({CUT: [np.eye(3)[:, :2]], "ENGRAVE": []}, {}, {})
    with pytest.raises(ValueError, match="ENGRAVE"):
        write_svg(tmp_path / "x.svg", drawing, cut_layer=CUT, mark_layer=MARK)


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(3, 9),
    radius=st.floats(1.0, 100.0),
    data=st.data(),
)
def test_random_bulges_read_back_at_the_closed_form_area(tmp_path_factory, n, radius, data):
    gaps = np.array(data.draw(st.lists(st.floats(0.2, 1.0), min_size=n, max_size=n)))
    angles = np.cumsum(gaps) / gaps.sum() * 2 * math.pi  # a convex polygon on a circle
    polygon = radius * np.column_stack([np.cos(angles), np.sin(angles)])
    open_unit = st.floats(-1.0, 1.0, exclude_min=True, exclude_max=True)
    bulges = np.array(data.draw(st.lists(open_unit, min_size=n, max_size=n)))
    ring = ArcRing(polygon, bulges)
    drawing = Drawing({CUT: [ring]}, {}, {})
    path = tmp_path_factory.mktemp("svg") / "random.svg"
    write_svg(path, drawing, cut_layer=CUT, mark_layer=MARK, title="gear")
    _, groups = read(path)
    points = points_of(paths_in(groups["cut"])[0])
    # coordinates are written to 1e-6 mm: the area may move by the perimeter (≤ 4πr) × 5e-7
    assert signed_area(points) == pytest.approx(exact_area(ring), rel=1e-4, abs=1e-5 * radius)
    # the viewBox is the read-back outline's own box plus the margin (arc extremes included),
    # within the written precision (coordinates to 1e-6 mm) and 1.25e-6 of a chord (≤ 2r): an
    # arc of sweep below 1e-5 rad is written as its chord, and svgelements' arccos misreads
    # the sweeps just above that by as much
    x0, y0, w, h = (float(t) for t in ET.parse(path).getroot().get("viewBox").split())
    box = [x0 + 1, -(y0 + h) + 1, x0 + w - 1, -y0 - 1]
    assert box == pytest.approx([*points.min(axis=0), *points.max(axis=0)], abs=5e-6 + 2.5e-6 * radius)


def _arc_samples(ring: ArcRing, short: float) -> np.ndarray:
    """Every vertex and points on each arc from its centre (an independent closed form), spaced
    Δφ = √(8·short/r) apart: a sample next to an extreme falls short of it by at most
    r(1 − cos(Δφ/2)) ≤ r(Δφ)²/8 = ``short``."""
    v, out = ring.vertices, [ring.vertices]
    for k, bulge in enumerate(ring.bulges):
        if bulge == 0:
            continue
        a, b = v[k], v[(k + 1) % len(v)]
        theta = 4 * math.atan(bulge)
        half = np.hypot(*(b - a)) / 2
        radius = half / abs(math.sin(theta / 2))
        normal = np.array([-(b - a)[1], (b - a)[0]]) / (2 * half)
        centre = (a + b) / 2 + normal * radius * math.cos(theta / 2) * math.copysign(1, theta)
        count = math.ceil(abs(theta) / math.sqrt(8 * short / radius)) + 1
        t = math.atan2(*(a - centre)[::-1]) + theta * np.linspace(0, 1, count)
        out.append(centre + radius * np.column_stack([np.cos(t), np.sin(t)]))
    return np.vstack(out)


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(2, 7),
    data=st.data(),
)
def test_ring_bounds_are_the_arcs_extremes(n, data):
    coordinate = st.floats(-50, 50)
    vertices = np.array(data.draw(st.lists(st.tuples(coordinate, coordinate), min_size=n, max_size=n, unique=True)))
    bulge = st.one_of(st.just(0.0), st.floats(1e-3, 5.0), st.floats(-5.0, -1e-3))
    ring = ArcRing(vertices, np.array(data.draw(st.lists(bulge, min_size=n, max_size=n))))
    dense = _arc_samples(ring, 1e-7)  # short of the true extremes by at most 1e-7
    assert ring_bounds(ring) == pytest.approx([*dense.min(axis=0), *dense.max(axis=0)], abs=1e-6)
