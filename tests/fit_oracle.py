"""An independent check of a mesh's least play, from the written files alone (issue 33).

Nothing here imports gearcad: the parts are read from their DXF files with ezdxf (the CUT
layer; bulges turned into arcs by hand and flattened to a sagitta of ``SAGITTA``), placed as
``assembly.dxf`` shows them at driver angle 0 (each part's rigid motion fitted to its outline
there), turned by ``kinematics.csv`` (a gear pair) or by the tooth counts read off the outlines
(a carrier train's mesh, relative to the carrier), and made as the process's worst case makes
them: every edge at its largest (shapely's buffer; a laser's cut path inset by half the kerf at
its narrowest, a printer's outline grown by its XY error and elephant foot) and gear 2's pivot
moved by the centre-distance tolerance the tight way (closer for an external mesh, apart for an
internal one).

At each position gear 1 is held and gear 2 is turned about its pivot each way until it touches:
the first touch of a turn is where a vertex of one polygon, moving on its circle about gear 2's
pivot, meets an edge of the other — solved exactly for every vertex–edge pair within reach (the
reach is grown until the first touch found lies inside it, so none is missed).  The play is the
free turn both ways times gear 2's pitch radius at the contact (mm on its pitch curve), as
docs/fit.md defines it.  Where gear 2 overlaps as placed it is first turned to a free place
(sampled over a pitch, then the touch search from there); where no turn frees it the pair jams
there, and the play is −4ε/cos α for the least shrink ε of both parts that frees it (the
convention of docs/fit.md), found by bisection.  The least play is found over a dense grid of
driver angles and refined about each low grid minimum by golden section on the angle until the
bracket is under ``1e-7`` rad.
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

import ezdxf
import numpy as np
import shapely

SAGITTA = 2e-5
"""Largest distance (mm) of a flattened arc's chords from the arc."""
BUFFER_SEGMENTS = 64
"""Segments per quarter circle of the offset's round joins (chord error 2 nm at 0.025 mm)."""


# --- reading the files ------------------------------------------------------------------------


def _flatten(points: np.ndarray, bulges: np.ndarray, sagitta: float = SAGITTA) -> np.ndarray:
    """A closed LWPOLYLINE's vertices with each bulge segment replaced by points on its arc."""
    out = []
    n = len(points)
    for i in range(n):
        a, b, bulge = points[i], points[(i + 1) % n], bulges[i]
        out.append(a)
        if abs(bulge) < 1e-12:
            continue
        chord = float(np.hypot(*(b - a)))
        if chord == 0:
            continue
        sweep = 4 * math.atan(bulge)
        radius = chord / (2 * abs(math.sin(sweep / 2)))
        left = np.array([a[1] - b[1], b[0] - a[0]]) / chord
        centre = (a + b) / 2 + left * radius * math.cos(sweep / 2) * math.copysign(1, sweep)
        step = 2 * math.acos(max(1 - sagitta / radius, -1.0))
        k = max(1, math.ceil(abs(sweep) / step))
        start = math.atan2(a[1] - centre[1], a[0] - centre[0])
        t = start + sweep * np.arange(1, k) / k
        out.extend(np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)]))
    return np.asarray(out)


def read_loops(path: Path, raw: bool = False) -> list[np.ndarray]:
    """The closed CUT-layer loops of a DXF file (flattened; ``raw``: the vertices as written)."""
    doc = ezdxf.readfile(path)
    loops = []
    for e in doc.modelspace().query("LWPOLYLINE"):
        if e.dxf.layer.upper() != "CUT":
            continue
        xyb = np.asarray(e.get_points("xyb"), dtype=float)
        loops.append(xyb[:, :2] if raw else _flatten(xyb[:, :2], xyb[:, 2]))
    return loops


def part_shape(path: Path) -> shapely.Polygon:
    """A part as a polygon: its largest CUT loop the shell, the loops inside it its holes."""
    loops = read_loops(path)
    polys = sorted((shapely.Polygon(p) for p in loops), key=lambda p: -p.area)
    shell = polys[0]
    holes = [p.exterior.coords for p in polys[1:] if shell.contains(p.representative_point())]
    return shapely.make_valid(shapely.Polygon(shell.exterior.coords, holes))


def _marks(path: Path) -> list[np.ndarray]:
    """The MARK layer's polylines (engraved, never offset by a kerf), as vertex arrays."""
    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxf.layer.upper() != "MARK":
            continue
        if e.dxftype() == "POLYLINE":
            out.append(np.array([[v[0], v[1]] for v in e.points()]))
        elif e.dxftype() == "LWPOLYLINE":
            out.append(np.asarray(e.get_points("xy"), dtype=float))
        elif e.dxftype() == "LINE":
            out.append(np.array([e.dxf.start[:2], e.dxf.end[:2]]))
    return out


def _kabsch(mine: np.ndarray, other: np.ndarray) -> tuple[float, np.ndarray]:
    a, b = mine - mine.mean(0), other - other.mean(0)
    angle = math.atan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b))
    return angle, other.mean(0) - _turn(mine.mean(0), angle)


def _crosses(marks: list[np.ndarray]) -> list[tuple[int, int]]:
    """The pivot crosses among ``marks``: pairs of straight two-point strokes of one length that
    share their middle at right angles.  Each file draws them square to its own axes, so a part
    turned into the assembly does not lay its cross onto the assembly's, only its centre."""
    lines = [i for i, m in enumerate(marks) if len(m) == 2]
    out = []
    for n, i in enumerate(lines):
        for j in lines[n + 1 :]:
            a, b = marks[i], marks[j]
            da, db = a[1] - a[0], b[1] - b[0]
            same = abs(np.hypot(*da) - np.hypot(*db)) < 1e-9 * max(1.0, np.hypot(*da))
            if same and np.hypot(*(a.mean(0) - b.mean(0))) < 1e-9 and abs(np.dot(da, db)) < 1e-9 * np.dot(da, da):
                out.append((i, j))
    return out


def _not_crosses(marks: list[np.ndarray]) -> list[np.ndarray]:
    used = {k for pair in _crosses(marks) for k in pair}
    return [m for k, m in enumerate(marks) if k not in used]


def _cross_centres(marks: list[np.ndarray]) -> list[np.ndarray]:
    return [marks[i].mean(0) for i, _ in _crosses(marks)]


def placement(part: Path, assembly: Path) -> tuple[float, np.ndarray, float]:
    """The rigid motion (turn rad, shift) that lays the part's engraved marks onto theirs in
    ``assembly.dxf`` (the assembly is drawn without a kerf, the marks never have one), and the
    largest distance (mm) of any of the part's mark vertices from the assembly's so moved."""
    from scipy.spatial import cKDTree

    cut = max(read_loops(part, raw=True), key=len)  # without a kerf, the outline itself is there
    exact = []
    for other in read_loops(assembly, raw=True):
        if len(other) == len(cut):
            angle, shift = _kabsch(cut, other)
            err = float(np.max(np.hypot(*(_turn(cut, angle) + shift - other).T)))
            if err < 1e-9:
                exact.append((angle, shift, err))
    if len(exact) == 1:  # one part of that outline (two identical gears: their marks tell them apart)
        return exact[0]
    mine, theirs = _marks(part), _marks(assembly)
    tree = cKDTree(np.concatenate(_not_crosses(theirs) + [c[None] for c in _cross_centres(theirs)]))
    everything = np.concatenate(_not_crosses(mine) + [c[None] for c in _cross_centres(mine)])
    key = max(_not_crosses(mine), key=len)
    best, laid = None, []
    for other in theirs:
        if len(other) != len(key):
            continue
        angle, shift = _kabsch(key, other)
        if float(np.max(np.hypot(*(_turn(key, angle) + shift - other).T))) > 1e-6:
            continue
        err = float(np.max(tree.query(_turn(everything, angle) + shift)[0]))  # (a cross: by its centre)
        if err < 1e-6:
            laid.append((angle, shift, err))
        if best is None or err < best[2]:
            best = (angle, shift, err)
    if len(laid) > 1:  # marks alike every few degrees (a dashed pitch circle): the outline decides
        best = max(laid, key=lambda c: _parallel(cut, c, assembly))
    if best is None or best[2] >= 1e-6:  # the writer split the arcs of the turned copy elsewhere
        best = _by_curve(part, assembly, best)
    if best is None:
        raise ValueError(f"{part.name}: not found in {assembly.name}")
    return best


def _parallel(cut: np.ndarray, motion, assembly: Path) -> float:
    """How much of a part's cut path, moved by ``motion`` (turn, shift, …), runs at one distance
    from the assembly's outlines: the share of its vertices within 2 µm of their median distance.
    A cut path is its outline offset by half the kerf (or the tool's radius), so laid on its own
    outline nearly all of it is; turned a dash of its pitch circle out of place, little is."""
    lines = shapely.MultiLineString([np.vstack([o, o[:1]]) for o in read_loops(assembly, raw=True)])
    gap = shapely.distance(shapely.points(_turn(cut, motion[0]) + motion[1]), lines)
    return float(np.mean(np.abs(gap - np.median(gap)) < 2e-3))


def _by_curve(part: Path, assembly: Path, best):
    """The placement laying the part's outline onto a loop of the assembly as curves: the DXF
    writer splits arcs into equal sub-arcs where their chords would lose area, and which of a
    gear's like arcs it splits turns on the last bits of their radii, so a turned copy may carry
    its extra vertices on other teeth (the same curve, other vertices; the engraved dashes
    alike).  Centroid onto centroid, then each turn that lays the part's farthest vertex onto
    one of the loop's as far out; the error is the largest distance of either's written vertices
    from the other's flattened curve (every written vertex lies on the curve)."""
    mine_raw = max(read_loops(part, raw=True), key=len)
    mine = shapely.Polygon(max(read_loops(part), key=len))
    c_mine = np.array(mine.centroid.coords[0])
    r_mine = np.hypot(*(mine_raw - c_mine).T)
    far = mine_raw[int(np.argmax(r_mine))] - c_mine
    for other_raw, other in zip(read_loops(assembly, raw=True), read_loops(assembly)):
        theirs = shapely.Polygon(other)
        if abs(theirs.area - mine.area) > 1e-6 * mine.area or abs(theirs.length - mine.length) > 1e-6 * mine.length:
            continue
        c_theirs = np.array(theirs.centroid.coords[0])
        r_theirs = np.hypot(*(other_raw - c_theirs).T)
        for w in other_raw[np.abs(r_theirs - r_mine.max()) < 1e-6] - c_theirs:
            angle = math.atan2(w[1], w[0]) - math.atan2(far[1], far[0])
            shift = c_theirs - _turn(c_mine, angle)
            placed = _turn(mine_raw, angle) + shift
            err = max(
                float(np.max(shapely.distance(shapely.points(placed), theirs.exterior))),
                float(
                    np.max(
                        shapely.distance(
                            shapely.points(other_raw),
                            shapely.LinearRing(_turn(np.asarray(mine.exterior.coords), angle) + shift),
                        )
                    )
                ),
            )
            if best is None or err < best[2]:
                best = (angle, shift, err)
    return best


def tooth_count(shape: shapely.Polygon, ring: str = "exterior") -> int:
    """The teeth of a loop (its exterior, or its largest hole's): the strongest harmonic of its
    radius's derivative about the origin (the pivot), below the 600th: a noncircular pitch
    curve's own harmonics fall off geometrically, the teeth's stand out once weighted by k."""
    loop = shape.exterior if ring == "exterior" else max(shape.interiors, key=lambda r: shapely.Polygon(r).area)
    xy = np.asarray(loop.coords)
    angle = np.unwrap(np.arctan2(xy[:, 1], xy[:, 0]))
    order = np.argsort(np.mod(angle, 2 * np.pi))
    theta, radius = np.mod(angle, 2 * np.pi)[order], np.hypot(xy[:, 0], xy[:, 1])[order]
    grid = np.linspace(0, 2 * np.pi, 4096, endpoint=False)
    r = np.interp(grid, theta, radius, period=2 * np.pi)
    k = np.arange(len(grid) // 2 + 1)
    spectrum = (np.abs(np.fft.rfft(r - r.mean())) * k)[:600]  # of r': the teeth stand out
    return int(np.argmax(spectrum[3:]) + 3)


# --- the mesh ---------------------------------------------------------------------------------


def _turn(xy: np.ndarray, angle, centre=(0.0, 0.0)) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    x, y = xy[..., 0] - centre[0], xy[..., 1] - centre[1]
    return np.stack([c * x - s * y + centre[0], s * x + c * y + centre[1]], axis=-1)


@dataclass
class Mesh:
    """Two parts (polygons about their pivots) and how they are placed at a driver angle."""

    shapes: tuple[shapely.Polygon, shapely.Polygon]
    pose0: tuple[tuple[float, np.ndarray], tuple[float, np.ndarray]]
    """Each part's turn (rad) and pivot at driver angle 0 (from assembly.dxf)."""
    turns: callable
    """driver angle (rad) -> (gear 1's turn, gear 2's turn) from the assembled pose (rad)."""
    arm: callable
    """driver angle (rad) -> gear 2's pitch radius at the contact (mm)."""
    contact_radius1: callable
    """driver angle (rad) -> gear 1's pitch radius at the contact (mm)."""
    internal: bool
    pressure_angle: float
    module: float
    period: float
    """Driver angle over which the mesh repeats (rad)."""
    pitch2: float
    """Gear 2's angular pitch (rad) where its pitch radius is least: no free turn is sought
    beyond its pitch at the contact, π·m over its pitch radius there (:meth:`pitch_at`)."""

    def pitch_at(self, phi):
        """Gear 2's angular pitch at the contact at driver angle ``phi`` (rad): π·m / r2."""
        return math.pi * self.module / np.asarray(self.arm(phi), dtype=float)

    @property
    def center_distance(self) -> float:
        return float(np.hypot(*(self.pose0[1][1] - self.pose0[0][1])))


def _kinematics(folder: Path):
    with (folder / "kinematics.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    d = np.array([float(r["driver_angle_rad"]) for r in rows])
    f = np.array([float(r["follower_angle_rad"]) for r in rows])
    i = np.array([float(r["ratio"]) for r in rows])
    return d, f, i


def _cubic(x: np.ndarray, y: np.ndarray):
    from scipy.interpolate import CubicSpline

    return CubicSpline(x, y)


def pair_mesh(folder: Path, gear1: str, gear2: str, driver: str, pressure_angle_deg: float, module: float) -> Mesh:
    """A gear pair's mesh from its build folder: gear ``gear1`` held, ``gear2`` turned."""
    shapes = (part_shape(folder / f"{gear1}.dxf"), part_shape(folder / f"{gear2}.dxf"))
    poses = []
    for name in (gear1, gear2):
        angle, shift, err = placement(folder / f"{name}.dxf", folder / "assembly.dxf")
        assert err < 3e-5, (name, err)  # (laid on as curves: to the flattening's 20 nm, see _by_curve)
        poses.append((angle, shift))
    d, f, ratio = _kinematics(folder)
    e = float(np.hypot(*(poses[1][1] - poses[0][1])))
    # kinematics.csv covers one driver turn; the follower may turn a whole fraction of its turn
    # in it (the walker's wheel a quarter), and the mesh repeats when both have turned whole
    turns = round(2 * math.pi / abs(f[-1] - f[0]))
    span, cycle = f[-1] - f[0], d[-1] - d[0]
    spline_f, spline_i = _cubic(d, f), _cubic(d, ratio)

    def follower(phi):
        k = np.floor(np.asarray(phi, dtype=float) / cycle)
        return spline_f(phi - k * cycle) + k * span

    def ratio_at(phi):
        return spline_i(np.mod(phi, cycle))

    def r_driver(phi):
        i = ratio_at(phi)
        return e * i / (1 + i)

    def r_follower(phi):
        return e / (1 + ratio_at(phi))

    period = float(turns * cycle)
    first_is_driver = gear1 == driver
    pitch2 = 0.0  # set below, from the pitch radius
    mesh = Mesh(shapes, tuple(poses), None, None, None, False, math.radians(pressure_angle_deg), module, period, pitch2)
    # the turning senses: the ones under which the parts stay apart as they roll
    best = None
    for s_d in (1, -1):
        for s_f in (1, -1):

            def turns(phi, s_d=s_d, s_f=s_f):
                dv, fv = s_d * np.asarray(phi), s_f * follower(phi)
                return (dv, fv) if first_is_driver else (fv, dv)

            mesh.turns = turns
            probe = np.linspace(0, period, 7, endpoint=False)[1:]
            area = sum(_placed(mesh, p, 0.0, 0.0)[0].intersection(_placed(mesh, p, 0.0, 0.0)[1]).area for p in probe)
            if best is None or area < best[0]:
                best = (area, turns)
    mesh.turns = best[1]
    mesh.arm = r_driver if not first_is_driver else r_follower
    mesh.pitch2 = float(np.max(mesh.pitch_at(np.linspace(0, period, 721))))
    mesh.contact_radius1 = r_driver if first_is_driver else r_follower
    return mesh


def train_mesh(folder: Path, gear1: str, gear2: str, pressure_angle_deg: float, module: float) -> Mesh:
    """A carrier train's mesh (relative to the carrier): ``gear1`` turned by the driver angle,
    ``gear2`` by the tooth ratio, the same way for an internal mesh, the other way for an external."""
    shapes = (part_shape(folder / f"{gear1}.dxf"), part_shape(folder / f"{gear2}.dxf"))
    poses = []
    for name in (gear1, gear2):
        angle, shift, err = placement(folder / f"{name}.dxf", folder / "assembly.dxf")
        assert err < 3e-5, (name, err)  # (laid on as curves: to the flattening's 20 nm, see _by_curve)
        poses.append((angle, shift))

    # internal: one part's largest hole holds the other's pivot (a compound ring's outer teeth
    # mesh externally though its hole is larger than the gear: by area alone the gear1/ring mesh
    # was taken as internal, its inner teeth counted, and its play came out as the 3π mm cap)
    def holds(ring: int) -> bool:
        holes = [np.asarray(r.coords) for r in shapes[ring].interiors]
        if not holes:
            return False
        hole = max(holes, key=lambda xy: shapely.Polygon(xy).area)
        inner = float(np.min(np.hypot(*hole.T)))  # the hole's least radius about the part's pivot (its origin)
        return float(np.hypot(*(poses[1 - ring][1] - poses[ring][1]))) < inner

    ring1, ring2 = holds(0), holds(1)
    internal = ring1 or ring2
    z1 = tooth_count(shapes[0], "interior" if ring1 else "exterior")
    z2 = tooth_count(shapes[1], "interior" if ring2 else "exterior")
    r1, r2 = module * z1 / 2, module * z2 / 2
    sign = 1.0 if internal else -1.0

    def turns(phi):
        phi = np.asarray(phi, dtype=float)
        return phi, sign * phi * z1 / z2

    return Mesh(
        shapes,
        tuple(poses),
        turns,
        lambda phi: r2 + 0 * np.asarray(phi, dtype=float),
        lambda phi: r1 + 0 * np.asarray(phi, dtype=float),
        internal,
        math.radians(pressure_angle_deg),
        module,
        2 * math.pi,
        2 * math.pi / z2,
    )


# --- placing and the free turn ----------------------------------------------------------------


@dataclass
class Made:
    """The mesh's parts as made: each grown by ``edge`` mm (less ``cut`` of a cut path) and gear 2's
    pivot moved by ``shift`` mm (positive: the tight way)."""

    mesh: Mesh
    edge: float
    cut: float
    shift: float

    def __post_init__(self):
        grow = self.edge - self.cut / 2
        self.parts = tuple(
            s if abs(grow) < 1e-15 else s.buffer(grow, quad_segs=BUFFER_SEGMENTS, join_style="round")
            for s in self.mesh.shapes
        )


def _placed(mesh: Mesh, phi: float, extra: float, shift: float, parts=None):
    """Both parts placed at driver angle ``phi``, gear 2 turned ``extra`` more, its pivot moved
    ``shift`` the tight way: (part 1, part 2, pivot 2) in the global frame."""
    parts = parts or mesh.shapes
    t1, t2 = mesh.turns(phi)
    (a1, c1), (a2, c2) = mesh.pose0
    way = (c2 - c1) / np.hypot(*(c2 - c1))
    pivot = c2 + (shift if mesh.internal else -shift) * way
    p1 = shapely.transform(parts[0], lambda xy: _turn(xy, a1 + float(t1)) + c1)
    p2 = shapely.transform(parts[1], lambda xy: _turn(xy, a2 + float(t2) + extra) + pivot)
    return p1, p2, pivot


def _segments(poly) -> tuple[np.ndarray, np.ndarray]:
    """Every edge of a polygon's rings: (starts, ends)."""
    a, b = [], []
    for ring in (
        [poly.exterior, *poly.interiors]
        if isinstance(poly, shapely.Polygon)
        else [r for g in poly.geoms for r in (g.exterior, *g.interiors)]
    ):
        xy = np.asarray(ring.coords)
        a.append(xy[:-1])
        b.append(xy[1:])
    return np.concatenate(a), np.concatenate(b)


def _touch(points: np.ndarray, starts: np.ndarray, ends: np.ndarray, centres: np.ndarray, sense: float) -> np.ndarray:
    """For each pair (``points[k]``, segment ``starts[k]``–``ends[k]``, turned about
    ``centres[k]``), the least positive turn (rad; ``sense`` +1 counter-clockwise, −1 clockwise)
    at which the point meets the segment, inf where it never does: where the segment crosses
    the circle of the point's radius about the centre."""
    p = points - centres
    u, d = starts - centres, ends - starts
    rho2 = np.sum(p * p, axis=1)
    aa = np.maximum(np.sum(d * d, axis=1), 1e-300)
    bb = 2 * np.sum(u * d, axis=1)
    cc = np.sum(u * u, axis=1) - rho2
    disc = bb * bb - 4 * aa * cc
    beta = np.arctan2(p[:, 1], p[:, 0])
    ok = disc >= 0
    root = np.sqrt(np.where(ok, disc, 0.0))
    best = np.full(len(points), np.inf)
    for sgn in (-1.0, 1.0):
        s = (-bb + sgn * root) / (2 * aa)
        hit = ok & (s >= 0) & (s <= 1)
        q = u + s[:, None] * d
        t = np.mod(sense * (np.arctan2(q[:, 1], q[:, 0]) - beta), 2 * np.pi)
        t = np.where(t > 2 * np.pi - 1e-12, 0.0, t)
        best = np.minimum(best, np.where(hit, t, np.inf))
    return best


def _first_touch(points, starts, ends, centre, sense) -> float:
    """The least of :func:`_touch` over the pairs, about one centre."""
    if not len(points):
        return np.inf
    return float(np.min(_touch(points, starts, ends, np.broadcast_to(centre, points.shape), sense)))


def free_turns(p1, p2, pivot: np.ndarray, near: np.ndarray, reach: float, cap: float) -> tuple[float, float]:
    """How far gear 2 (placed, free of gear 1) turns counter-clockwise and clockwise about
    ``pivot`` before it touches gear 1 (rad, each at most ``cap``); only parts within ``reach`` mm
    of ``near`` (the contact) take part.  A point turned by t moves at most t times its radius
    about the pivot, so a touch at t involves a vertex and an edge that were that close: the
    pairs within ``grow`` of each other (an R-tree query) are solved, and ``grow`` is widened
    until the first touch found moves no point farther than it."""
    window = shapely.Point(near).buffer(reach, quad_segs=32)
    w1, w2 = p1.intersection(window), p2.intersection(window)
    if w1.is_empty or w2.is_empty:
        return cap, cap
    s1, e1 = _segments(w1)
    s2, e2 = _segments(w2)
    tree1 = shapely.STRtree(shapely.linestrings(np.stack([s1, e1], axis=1)))
    tree2 = shapely.STRtree(shapely.linestrings(np.stack([s2, e2], axis=1)))
    pts1, pts2 = shapely.points(s1), shapely.points(s2)
    far = float(max(np.max(np.hypot(*(s2 - pivot).T)), np.max(np.hypot(*(s1 - pivot).T))))
    out = []
    for sense in (1.0, -1.0):
        grow = max(2e-3, 0.01 * far * cap)
        while True:
            t = cap
            i2, j1 = tree1.query(pts2, predicate="dwithin", distance=grow)
            if len(i2):
                t = min(t, _first_touch(s2[i2], s1[j1], e1[j1], pivot, sense))
            i1, j2 = tree2.query(pts1, predicate="dwithin", distance=grow)
            if len(i1):
                t = min(t, _first_touch(s1[i1], s2[j2], e2[j2], pivot, -sense))
            if t * far <= grow or grow >= far * cap:
                out.append(min(t, cap))
                break
            grow *= 4
    return out[0], out[1]


def _overlap(p1, p2, window) -> float:
    return p1.intersection(window).intersection(p2.intersection(window)).area


def _contact(mesh: Mesh, phi: float, pivot: np.ndarray) -> np.ndarray:
    """The pitch point at driver angle ``phi`` (global): on the line of centres, gear 1's pitch
    radius from its pivot (towards gear 2's; away from it when gear 2 is the ring)."""
    c1 = mesh.pose0[0][1]
    way = (pivot - c1) / np.hypot(*(pivot - c1))
    r1 = float(mesh.contact_radius1(phi))
    if mesh.internal and mesh.shapes[1].exterior.length > mesh.shapes[0].exterior.length:
        return c1 - r1 * way
    return c1 + r1 * way


def play_at(made: Made, phi: float, samples: int = 41) -> tuple[float, float]:
    """Free play at driver angle ``phi`` (mm on gear 2's pitch curve; negative: jammed, as the
    shrink that frees it) and the turn of gear 2 it was measured from (rad)."""
    mesh = made.mesh
    _, _, pivot = _placed(mesh, phi, 0.0, made.shift, (shapely.Point(0, 0), shapely.Point(0, 0)))
    near = _contact(mesh, phi, pivot)
    reach = 5.0 * mesh.module
    window = shapely.Point(near).buffer(reach, quad_segs=32)
    # each part cut about the contact in its own frame, wide enough for gear 2 turned half a pitch
    t1, t2 = mesh.turns(phi)
    (a1, c1), (a2, _) = mesh.pose0
    own = (_turn(near - c1, -(a1 + float(t1))), _turn(near - pivot, -(a2 + float(t2))))
    pieces = tuple(
        part.intersection(shapely.Point(*o).buffer(reach + 2.5 * mesh.module, quad_segs=32))
        for part, o in zip(made.parts, own)
    )
    cut = Made.__new__(Made)
    cut.mesh, cut.edge, cut.cut, cut.shift, cut.parts = mesh, made.edge, made.cut, made.shift, pieces
    p1, p2, pivot = _placed(mesh, phi, 0.0, made.shift, pieces)
    arm = float(mesh.arm(phi))
    cap = float(mesh.pitch_at(phi))
    start = 0.0
    if _overlap(p1, p2, window) > 1e-14:
        start = _free_start(mesh, phi, pieces, made.shift, window, samples)
        if start is None:
            return -_jam_shrink(cut, phi, window, samples) * 4 / math.cos(mesh.pressure_angle), float("nan")
        p1, p2, pivot = _placed(mesh, phi, start, made.shift, pieces)
    plus, minus = free_turns(p1, p2, pivot, near, reach, cap)
    return (plus + minus) * arm, start


def _free_start(mesh, phi, parts, shift, window, samples):
    """A turn of gear 2 within a pitch where it overlaps gear 1 not at all, nearest the assembled one."""
    half = float(mesh.pitch_at(phi)) / 2
    turns = np.linspace(-half, half, samples)
    areas = []
    for t in turns:
        p1, p2, _ = _placed(mesh, phi, float(t), shift, parts)
        areas.append(_overlap(p1, p2, window))
    areas = np.asarray(areas)
    free = np.flatnonzero(areas <= 1e-14)
    if len(free):
        return float(turns[free[np.argmin(np.abs(turns[free]))]])
    # golden section on the overlap about the least sample
    k = int(np.argmin(areas))
    f = lambda t: _overlap(*_placed(mesh, phi, float(t), shift, parts)[:2], window)  # noqa: E731
    a, fa, b, fb = _golden(f, turns[max(k - 1, 0)], turns[min(k + 1, samples - 1)], 1e-12, 60, 1e-14)
    return float(a if fa <= fb else b) if min(fa, fb) <= 1e-14 else None


def _golden(f, lo: float, hi: float, width: float, steps: int = 10**6, enough: float = -math.inf):
    """Golden sections of ``f`` on [lo, hi] until the bracket is under ``width``, ``steps`` are
    taken or either probe is at most ``enough``: (a, f(a), b, f(b)), the last probes."""
    g = (math.sqrt(5) - 1) / 2
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = f(a), f(b)
    for _ in range(steps):
        if min(fa, fb) <= enough or hi - lo <= width:
            break
        if fa <= fb:
            hi, b, fb = b, a, fa
            a = hi - g * (hi - lo)
            fa = f(a)
        else:
            lo, a, fa = a, b, fb
            b = lo + g * (hi - lo)
            fb = f(b)
    return a, fa, b, fb


def depth(overlap, tol: float = 1e-9, below: float = math.inf) -> float:
    """The least shrink ε (mm) of both parts' edges under which their ``overlap`` (the parts'
    intersection) is gone: its inradius.  A point of the overlap keeps ε from both outlines
    exactly when it keeps ε from the overlap's boundary (which lies on one outline or the other,
    and any way out of the overlap crosses it), so the shrunk parts share a point exactly while
    the overlap shrunk by ε is not empty: bisected to ``tol`` from πr² ≤ its area (the overlap
    is a sliver: shrinking it, not the parts, is cheap); ``below``: where it is not, ``below``
    (it is at least that: all a search for the least needs)."""
    if overlap.is_empty or overlap.area <= 0.0:
        return 0.0
    lo, hi = 0.0, math.sqrt(overlap.area / math.pi) * (1 + 1e-6) + 1e-12
    if below < hi:
        if not overlap.buffer(-below, quad_segs=BUFFER_SEGMENTS).is_empty:
            return below
        hi = below
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if overlap.buffer(-mid, quad_segs=BUFFER_SEGMENTS).is_empty else (mid, hi)
    return hi


def _jam_shrink(made: Made, phi, window, samples) -> float:
    """The least shrink ε (mm) of both parts' edges under which gear 2 turns free at ``phi``: the
    least :func:`depth` of their overlap over gear 2's turns within a pitch (a grid of
    ``samples``, each measured only where it is less than the least so far, then golden sections
    about the least to 1e-10 rad)."""
    mesh = made.mesh
    half = float(mesh.pitch_at(phi)) / 2
    fixed = _placed(mesh, phi, 0.0, made.shift, made.parts)[0].intersection(window)
    shapely.prepare(fixed)

    def f(t, below=math.inf):
        placed = _placed(mesh, phi, float(t), made.shift, made.parts)[1]
        return depth(fixed.intersection(placed.intersection(window)), below=below)

    turns = np.linspace(-half, half, samples)
    depths = np.full(samples, math.inf)
    for k in np.argsort(np.abs(turns)):  # from the assembled turn out, each only if it is less
        least = float(np.min(depths))
        found = f(turns[k], least)
        depths[k] = found if found < least else math.inf
    k = int(np.argmin(depths))
    _, fa, _, fb = _golden(f, turns[max(k - 1, 0)], turns[min(k + 1, samples - 1)], 1e-10)
    return float(min(depths[k], fa, fb))


def least_play(
    made: Made, positions: int = 360, refine: int = 3, span: tuple[float, float] | None = None, tol: float = 1e-7
):
    """The least play over the driver's cycle (or ``span``): a grid of ``positions`` driver angles,
    then golden section on the angle about the ``refine`` lowest grid minima until the bracket is
    under ``tol`` rad.  Returns (least play mm, driver angle rad, grid angles, grid plays)."""
    lo, hi = span if span else (0.0, made.mesh.period)
    grid = np.linspace(lo, hi, positions, endpoint=span is not None)
    plays = np.array([play_at(made, float(p))[0] for p in grid])
    n = len(grid)
    minima = [k for k in range(n) if plays[k] <= plays[(k - 1) % n] and plays[k] <= plays[(k + 1) % n]]
    minima = sorted(minima, key=lambda k: plays[k])[:refine]
    step = grid[1] - grid[0]
    best = (float(plays.min()), float(grid[int(np.argmin(plays))]))
    g = (math.sqrt(5) - 1) / 2
    for k in minima:
        a0, b0 = grid[k] - step, grid[k] + step
        f = lambda p: play_at(made, float(p))[0]  # noqa: E731
        a, b = b0 - g * (b0 - a0), a0 + g * (b0 - a0)
        fa, fb = f(a), f(b)
        while b0 - a0 > tol:
            if fa <= fb:
                b0, b, fb = b, a, fa
                a = b0 - g * (b0 - a0)
                fa = f(a)
            else:
                a0, a, fa = a, b, fb
                b = a0 + g * (b0 - a0)
                fb = f(b)
        for v, p in ((fa, a), (fb, b)):
            if v < best[0]:
                best = (float(v), float(p))
    return best[0], best[1], grid, plays


class Sweep:
    """The free play at many driver angles at once (the same solution as :func:`play_at`, in
    gear 1's frame for all positions together).  Each gear's vertices near the contact are
    picked by their polar angle (sorted once), moved into the other gear's frame, paired with
    the other's edges within reach (a k-d tree of edge midpoints, built once), and each pair's
    first touch solved.  Where gear 2 overlaps gear 1 as placed, it is turned by ±δ·2^k until
    it is free (δ = 1e-6 rad, k = 0, 2, 4, 6, 8); positions still overlapping go
    to :func:`play_at` (which turns gear 2 free over its pitch, or measures the jam)."""

    def __init__(self, made: Made, reach: float = 3.5):
        from scipy.spatial import cKDTree

        self.made = made
        self.reach = reach * made.mesh.module
        self.gears = []
        for part in made.parts:
            a, b = _segments(part)
            # long edges cut into pieces of at most 0.02 mm: the same outline, edges found near
            pieces = np.maximum(1, np.ceil(np.hypot(*(b - a).T) / 0.02)).astype(int)
            k = np.repeat(np.arange(len(a)), pieces)
            f = (np.arange(int(pieces.sum())) - np.repeat(np.cumsum(pieces) - pieces, pieces)) / pieces[k]
            a, b = a[k] + f[:, None] * (b[k] - a[k]), a[k] + (f + 1 / pieces[k])[:, None] * (b[k] - a[k])
            angle = np.arctan2(a[:, 1], a[:, 0])
            order = np.argsort(angle)
            mids = (a + b) / 2
            half = float(np.max(np.hypot(*(b - a).T))) / 2
            self.gears.append((a, b, angle[order], order, cKDTree(mids), half))
            shapely.prepare(part)

    def _near(self, gear: int, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(position, vertex) of each of the gear's vertices within reach of each centre (own frame)."""
        a, _, sorted_angle, order, _, _ = self.gears[gear]
        rho = np.hypot(centres[:, 0], centres[:, 1])
        half = np.where(rho > self.reach, np.arcsin(np.minimum(self.reach / np.maximum(rho, 1e-12), 1.0)), np.pi)
        mid = np.arctan2(centres[:, 1], centres[:, 0])
        ks, vs = [], []
        for shift in (-2 * np.pi, 0.0, 2 * np.pi):
            lo = np.searchsorted(sorted_angle, mid - half + shift)
            hi = np.searchsorted(sorted_angle, mid + half + shift)
            count = hi - lo
            k = np.repeat(np.arange(len(centres)), count)
            v = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(int(count.sum()))
            ks.append(k)
            vs.append(order[v])
        k, v = np.concatenate(ks), np.concatenate(vs)
        keep = np.hypot(*(a[v] - centres[k]).T) <= self.reach
        return k[keep], v[keep]

    def _pairs(self, gear: int, points: np.ndarray, grow: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(point, edge of ``gear``) for every edge whose midpoint lies within grow + half the
        longest edge of the point: every edge within ``grow`` of it, and a few more."""
        from scipy.spatial import cKDTree

        _, _, _, _, tree, half = self.gears[gear]
        out_i, out_j = [np.zeros(0, np.int64)], [np.zeros(0, np.int64)]
        for g in np.unique(grow):  # each reach alone (a few powers of 4): memory as the pairs need
            rows = np.flatnonzero(grow == g)
            pairs = cKDTree(points[rows]).sparse_distance_matrix(tree, float(g) + half, output_type="ndarray")
            out_i.append(rows[pairs["i"].astype(np.int64)])
            out_j.append(pairs["j"].astype(np.int64))
        return np.concatenate(out_i), np.concatenate(out_j)

    def plays(self, phis: np.ndarray, chunk: int = 96) -> np.ndarray:
        phis = np.atleast_1d(np.asarray(phis, dtype=float))
        if len(phis) > chunk:  # a few positions at a time: a wide free turn pairs many edges
            return np.concatenate([self.plays(phis[k : k + chunk], chunk) for k in range(0, len(phis), chunk)])
        made = self.made
        n = len(phis)
        out = np.full(n, np.nan)
        extra = np.zeros(n)
        todo = np.ones(n, bool)
        tries = [0.0] + [s * t for t in (1e-6, 4e-6, 1.6e-5, 6.4e-5, 2.56e-4) for s in (1, -1)]
        for turn in tries:
            idx = np.flatnonzero(todo)
            if not len(idx):
                break
            extra[idx] = turn
            play, bad = self._at(phis[idx], extra[idx])
            out[idx[~bad]] = play[~bad]
            todo[idx[~bad]] = False
        for k in np.flatnonzero(todo):
            out[k] = play_at(made, float(phis[k]))[0]
        return out

    def _at(self, phis: np.ndarray, extra: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Play at each position with gear 2 turned ``extra`` more, and whether it overlaps there."""
        made, mesh = self.made, self.made.mesh
        n = len(phis)
        t1, t2 = mesh.turns(phis)
        (a1, c1), (a2, c2) = mesh.pose0
        way = (c2 - c1) / np.hypot(*(c2 - c1))
        pivot = c2 + (made.shift if mesh.internal else -made.shift) * way
        big1, big2 = a1 + t1, a2 + t2 + extra
        r1 = np.asarray(mesh.contact_radius1(phis), dtype=float)
        line = (pivot - c1) / np.hypot(*(pivot - c1))
        ring2 = mesh.internal and mesh.shapes[1].exterior.length > mesh.shapes[0].exterior.length
        contact = c1 + (-r1 if ring2 else r1)[:, None] * line
        own1 = _turn(contact - c1, -big1)  # the contact in each gear's own frame
        own2 = _turn(contact - pivot, -big2)
        (s1, e1, *_), (s2, e2, *_) = self.gears
        k2, i2 = self._near(1, own2)
        x2 = _turn(_turn(s2[i2], big2[k2]) + pivot - c1, -big1[k2])  # gear 2's vertices in gear 1's frame
        k1, i1 = self._near(0, own1)
        y1 = _turn(_turn(s1[i1], big1[k1]) + c1 - pivot, -big2[k1])  # gear 1's vertices in gear 2's frame
        pivot1 = _turn(np.broadcast_to(pivot - c1, (n, 2)), -big1)  # gear 2's pivot in gear 1's frame
        far = np.hypot(own2[:, 0], own2[:, 1]) + self.reach
        cap = mesh.pitch_at(phis)
        best = np.full((2, n), cap)
        todo = np.ones(n, bool)
        grow = np.full(n, 5e-3)
        bad = np.zeros(n, bool)
        first = True
        while todo.any():
            for k, pts, gear, centres, turn in ((k2, x2, 0, pivot1[k2], 1.0), (k1, y1, 1, None, -1.0)):
                rows = np.flatnonzero(todo[k])
                if not len(rows):
                    continue
                i, seg = self._pairs(gear, pts[rows], grow[k[rows]])
                rows = rows[i]
                a, b = self.gears[gear][0][seg], self.gears[gear][1][seg]
                c = np.zeros((len(rows), 2)) if centres is None else centres[rows]
                if first:  # overlapping as placed: a vertex (near the other part) inside it
                    near = np.unique(rows)
                    inside = shapely.contains_xy(made.parts[gear], pts[near, 0], pts[near, 1])
                    bad[k[near[inside]]] = True
                for side, sense in ((0, turn), (1, -turn)):
                    np.minimum.at(best[side], k[rows], _touch(pts[rows], a, b, c, sense))
            first = False
            todo &= ~bad
            done = (np.max(best, axis=0) * far <= grow) | (grow >= far * cap)
            todo &= ~done
            grow = np.where(todo, grow * 4, grow)
        return (best[0] + best[1]) * np.asarray(mesh.arm(phis), dtype=float), bad


def least_play_fast(made: Made, positions: int, refine: int = 3, tol: float = 1e-7, sweep: Sweep | None = None):
    """:func:`least_play` with the grid and the golden sections evaluated by :class:`Sweep`
    (every bracket's probes in one call)."""
    sweep = sweep or Sweep(made)
    period = made.mesh.period
    grid = np.linspace(0.0, period, positions, endpoint=False)
    plays = sweep.plays(grid)
    low = np.flatnonzero((plays <= np.roll(plays, 1)) & (plays <= np.roll(plays, -1)))
    low = low[np.argsort(plays[low])][:refine]
    step = period / positions
    lo, hi = grid[low] - step, grid[low] + step
    g = (math.sqrt(5) - 1) / 2
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = sweep.plays(a), sweep.plays(b)
    while np.max(hi - lo) > tol:
        left = fa <= fb
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
        a2, b2 = hi - g * (hi - lo), lo + g * (hi - lo)
        a, b = np.where(left, a2, b), np.where(left, a, b2)
        fresh = sweep.plays(np.where(left, a, b))
        fa, fb = np.where(left, fresh, fb), np.where(left, fa, fresh)
    cands = np.concatenate([[plays.min()], fa, fb])
    where = np.concatenate([[grid[int(np.argmin(plays))]], a, b])
    k = int(np.argmin(cands))
    return float(cands[k]), float(where[k] % period), grid, plays


def process_offsets(report: dict, internal: bool = False) -> tuple[float, float, float]:
    """(edge at its largest, cut width, centre shift the tight way) from report.json's
    ``process`` and ``output`` blocks, read as docs/fit.md defines them."""
    proc = report.get("process") or {"kind": "none"}
    kind = proc.get("kind", "none")
    out = report.get("output", {})
    if kind == "laser":
        return proc["kerf_variation"] / 2, out.get("kerf", 0.0), proc["center_distance_tolerance"] + proc["bore_play"]
    if kind in ("fdm", "cnc"):
        foot = max(0.0, proc["elephant_foot"] - out.get("chamfer", 0.0)) if kind == "fdm" else 0.0
        cut = proc["tool_diameter"] if kind == "cnc" else out.get("kerf", 0.0)
        return (
            proc["xy_compensation"] + proc["xy_variation"] + foot,
            cut,
            proc["center_distance_tolerance"] + proc["bore_play"],
        )
    return 0.0, out.get("kerf", 0.0), 0.0


def report(folder: Path) -> dict:
    return json.loads((folder / "report.json").read_text(encoding="utf-8"))


def turns_free(fixed, pieces: np.ndarray, place, limit: float, steps: int = 13) -> tuple[np.ndarray, np.ndarray]:
    """How far each of ``pieces`` (polygons in their own coordinates, one a position, free of
    ``fixed`` at turn 0) turns each way before it meets ``fixed`` (rad, counter-clockwise and
    clockwise, to ``limit``/2**``steps``): ``place(which, xy, turn)`` puts the points ``xy`` of
    the pieces ``which`` at their positions, turned ``turn`` more.  Bisection on whether the
    placed piece meets the prepared ``fixed`` (shapely, exact on the polygons); ``limit`` must turn
    no point farther than a tooth is thick (then the first touch is the only one before it)."""
    shapely.prepare(fixed)
    coords, which = shapely.get_coordinates(pieces, return_index=True)

    def meets(turn: np.ndarray) -> np.ndarray:
        return shapely.intersects(fixed, shapely.set_coordinates(pieces.copy(), place(which, coords, turn[which])))

    out = []
    for sense in (1.0, -1.0):
        lo, hi = np.zeros(len(pieces)), np.full(len(pieces), limit)
        assert meets(sense * hi).all() and not meets(lo).any()
        for _ in range(steps):
            mid = 0.5 * (lo + hi)
            hit = meets(sense * mid)
            lo, hi = np.where(hit, lo, mid), np.where(hit, mid, hi)
        out.append(lo)
    return out[0], out[1]
