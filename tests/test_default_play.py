"""Parts that fit when made, by default: with no process the written outlines of every toothed
gear pair keep apart (read back from the DXFs, placed by an own conjugate-angle search, not the
code's mesh proof), and under a process the chosen backlash is the smallest that keeps the
band's worst case free (against a bisection over fixed backlashes)."""

import csv
import json
import math

import ezdxf
import numpy as np
import pytest
import shapely

from .conftest import EXAMPLES

TOUCH = 1e-9
"""mm²: an overlap of the written outlines above this is a bite (a 1 µm tolerance's sliver is ~1e-4)."""
SAG = 2e-5
"""mm: how far the flattened arcs of a written path may lie inside them (50 times under a tolerance)."""


def _cut(path, sag: float = SAG) -> list[shapely.Polygon]:
    doc = ezdxf.readfile(path)
    cut = [e for e in doc.modelspace() if e.dxf.layer == "CUT" and e.dxftype() in ("LWPOLYLINE", "POLYLINE")]
    return [shapely.Polygon([(v.x, v.y) for v in ezdxf.path.make_path(e).flattening(sag)]) for e in cut]


def _outer(path, sag: float = SAG) -> shapely.Polygon:
    return max(_cut(path, sag), key=lambda p: p.area)


def _turn(xy, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]])


class Written:
    """A written pair: gear 1 (the first part, pivot at the origin) turned by −φ1, gear 2 at
    (E, 0) turned by +φ2, φ2(φ1) read from kinematics.csv (its period repeated) as the place to
    search from; windows of both outlines about the pitch point on the line of centres."""

    def __init__(self, folder, positions: int):
        report = json.loads((folder / "report.json").read_text())
        (p1, p2), driver = report["parts"][:2], report["kinematics"]["driver"]
        self.e = p2["placement"]["offset"][0]
        self.m = report["gears"][0]["teeth"]["module"]
        g1, g2 = _outer(folder / f"{p1['name']}.dxf"), _outer(folder / f"{p2['name']}.dxf")
        with open(folder / "kinematics.csv") as f:
            a, b, ratio = np.array([[float(x) for x in row[:3]] for row in list(csv.reader(f))[1:]]).T
        if driver != p1["name"]:
            a, b, ratio = b, a, 1 / ratio  # gear 1's angle, gear 2's, dφ2/dφ1
        rng = np.random.default_rng(20)
        self.phi1 = (np.arange(positions) + rng.random(positions)) * 2 * np.pi / positions
        q = np.floor((self.phi1 - a[0]) / (a[-1] - a[0]))
        at = self.phi1 - q * (a[-1] - a[0])
        self.phi2 = np.interp(at, a, b) + q * (b[-1] - b[0])
        k = np.interp(at, a, ratio)
        self.r1 = self.e * k / (1 + k)  # the pitch point: r1·dφ1 = r2·dφ2, r1 + r2 = E
        c1 = _turn(np.column_stack([self.r1, 0 * self.r1]), self.phi1)
        c2 = _turn(np.column_stack([self.r1 - self.e, 0 * self.r1]), -self.phi2)
        w1 = shapely.intersection(g1, shapely.buffer(shapely.points(c1), 2.5 * self.m))
        self.w2 = shapely.intersection(g2, shapely.buffer(shapely.points(c2), 3.0 * self.m))
        xy, i = shapely.get_coordinates(w1, return_index=True)
        self.w1 = shapely.set_coordinates(w1.copy(), _turn(xy, -self.phi1[i]))

    def overlap(self, turn, at=None) -> np.ndarray:
        """Overlap (mm²) at positions ``at`` (all) with gear 2 turned ``turn`` (rad) beyond φ2."""
        at = np.arange(len(self.phi1)) if at is None else at
        w2 = self.w2[at]
        xy, i = shapely.get_coordinates(w2, return_index=True)
        placed = shapely.set_coordinates(w2.copy(), _turn(xy, (self.phi2[at] + turn)[i]) + [self.e, 0])
        return shapely.area(shapely.intersection(self.w1[at], placed))

    def least(self, iterations: int = 24):
        """The least overlap over gear 2's turns within ±0.5 module of arc (golden section where
        it overlaps as placed), and how deep it is (µm: the deepest vertex of one outline inside
        the other, to the other's edge)."""
        area = self.overlap(np.zeros_like(self.phi1))
        bad = np.flatnonzero(area > TOUCH)
        best = np.zeros_like(self.phi1)
        if len(bad):
            g = (math.sqrt(5) - 1) / 2
            hi = 0.5 * self.m / (self.e - self.r1[bad])
            lo = -hi
            a, b = hi - g * (hi - lo), lo + g * (hi - lo)
            fa, fb = self.overlap(a, bad), self.overlap(b, bad)
            for _ in range(iterations):
                left = fa <= fb
                hi, lo = np.where(left, b, hi), np.where(left, lo, a)
                a, b = np.where(left, hi - g * (hi - lo), b), np.where(left, a, lo + g * (hi - lo))
                fresh = self.overlap(np.where(left, a, b), bad)
                fa, fb = np.where(left, fresh, fb), np.where(left, fa, fresh)
            best[bad], area[bad] = np.where(fa <= fb, a, b), np.minimum(fa, fb)
        return area, best


@pytest.mark.parametrize("name, positions", [("elliptic_focus", 240), ("walker", 240), ("spur_pair", 80)])
def test_the_written_pair_keeps_apart_with_no_process(built, name, positions):
    """Before the default play: the focus pair's written outlines overlapped at 2913 of 4100
    positions (1.1 µm deep, 1.5e-4 mm²), the walker's at 484 of 800 (9.4e-5 mm²); now nowhere above
    1e-9 mm²; and the
    search can fail: gear 2 turned 0.2 module of arc either way bites at every position."""
    pair = Written(built / name, positions)
    area, _ = pair.least()
    assert area.max() <= TOUCH, (name, int((area > TOUCH).sum()), float(area.max()))
    some = np.arange(0, positions, 4)
    nudge = 0.2 * pair.m / (pair.e - pair.r1[some])
    assert np.all(np.minimum(pair.overlap(nudge, some), pair.overlap(-nudge, some)) > 1e-4)
    report = json.loads((built / name / "report.json").read_text())
    teeth = report["pair"]["teeth"]
    writing = 4 * report["tolerance"] / math.cos(report["gears"][0]["teeth"]["pressure_angle"])
    assert teeth["backlash_design"] == pytest.approx(1.5 * writing)  # the default, documented
    # the band's least play, certified between positions, keeps the exact parts' margin (the mesh
    # proof's allowance, −4·tol/cos α); the walker's concave seam closes to under a micron whatever
    # the backlash (a sampled band said 5.85 µm, the dense independent sweep 0.19 µm)
    assert report["bands"][0]["min"] >= -writing and report["bands"][0]["verdict"] == "fits"


def _rack_room(m, backlash, dedendum=1.25, alpha=0.3490658503988659):  # 20°
    """The largest fillet a rack tooth's tip takes (mm): its half width at the tip line, over
    (1 − sin α)/cos α (a circle tangent to both flanks and the tip line)."""
    room = math.pi * m / 4 + backlash / 4 - dedendum * m * math.tan(alpha)
    return room * math.cos(alpha) / (1 - math.sin(alpha))


def test_a_router_cuts_the_roots_with_its_own_radius(tmp_path, capsys):
    """CNC: a tool wider than the rack tip's room is refused in one line (key, value, the largest
    tool, by the closed form within 1 %; before: "output.kerf = …: the beam fills a tooth space"
    or, between the rack's 0.38·m tip and its room, accepted unsaid); one that fits cuts what is
    drawn: the part its written path leaves (the path eroded by the tool's radius) lies within
    two tolerances of the drawn part in assembly.dxf."""
    from gearcad.cli import main

    spur = str(EXAMPLES / "spur_pair.toml")
    sets = ["--set", "process.kind=cnc", "--set", "teeth.backlash=0.2", "--set", "output.tolerance=0.01"]
    sets += ["--set", "output.charts=false", "--set", "output.animation=false", "--set", 'output.formats=["dxf"]']
    largest = 2 * _rack_room(2.0, 0.2)  # 2.030 mm
    assert main(["check", spur, *sets, "--set", f"process.tool_diameter={1.02 * largest:.4f}"]) == 2
    line = capsys.readouterr().err.strip()
    assert line.count("\n") == 0 and "process.tool_diameter = " in line
    said = float(line.split("at most ")[1].split(" mm")[0])
    assert said == pytest.approx(largest, rel=0.01)
    tool = 2.0
    # the files are what is looked at: the band bounded by the estimate (half the build's CPU),
    # which writes the same paths
    sets += ["--set", 'output.certificate="estimate"']
    assert main(["build", spur, *sets, "--set", f"process.tool_diameter={tool}", "--out", str(tmp_path)]) == 0
    folder = tmp_path / "spur_pair"
    path = _outer(folder / "pinion.dxf", 1e-3)  # the tool's centre runs here
    made = path.buffer(-tool / 2, quad_segs=32)
    # the parts as drawn, placed (assembly.dxf): the pinion is the one about the origin
    drawn = [p for p in _cut(folder / "assembly.dxf", 1e-3) if p.contains(shapely.Point(0, 0))]
    pinion = min(drawn, key=lambda p: p.area).exterior
    points = shapely.points(shapely.get_coordinates(shapely.segmentize(made.exterior, 0.05)))
    edges = shapely.STRtree(shapely.linestrings(np.stack([pinion.coords[:-1], pinion.coords[1:]], axis=1)))
    _, gap = edges.query_nearest(points, return_distance=True, all_matches=False)
    assert gap.max() <= 2 * 0.01, gap.max()
    capsys.readouterr()
