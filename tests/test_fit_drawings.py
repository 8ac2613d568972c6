"""Drawings to check the fit show the parts as drawn (the beam paths only in the cut files), and
each gear of a pair carries an engraved dot where the two meet in the assembly's phase."""

import json
from pathlib import Path

import numpy as np
import pytest
import shapely

import gearcad
from gearcad.export.drawing import assembly_drawing, part_drawing
from gearcad.export.write import write_design
from gearcad.geometry.arcfit import arc_points

ROOT = Path(__file__).parent.parent
SPUR = str(ROOT / "profiles" / "spur_pair.toml")


def _polygons(rings, tol):
    outer = [arc_points(r, tol) for r in rings]
    return [shapely.Polygon(r).buffer(0) for r in outer]


@pytest.fixture(scope="module")
def spur():
    """The spur pair at 0.01 mm with a 0.2 mm kerf, its SVGs only: one design for both tests
    (the kerf moves the beam paths, not the drawn parts the dots sit on)."""
    over = {"output.kerf": 0.2, "output.tolerance": 0.01, "output.charts": False, "output.animation": False}
    return gearcad.design(gearcad.load_profile(SPUR, {**over, "output.formats": ["svg"]}))


def test_the_assembly_is_drawn_without_kerf_and_the_cut_files_with_it(tmp_path, spur):
    d = spur
    assert d.ok, d.failures()
    files = write_design(d, tmp_path)  # the build's own writer (a build is this call, then publish)
    assert {"assembly.svg", "pinion.svg"} <= set(files)
    assert "no kerf" in (tmp_path / "assembly.svg").read_text(encoding="utf-8")
    assert "kerf compensation" in (tmp_path / "pinion.svg").read_text(encoding="utf-8")
    cut = d.params.output.cut_layer
    drawn = assembly_drawing(d).closed[cut]
    beams = assembly_drawing(d, cut=True).closed[cut]
    # outer rings of the two gears: as drawn they touch (overlap at the tolerance), the beam
    # paths overlap by about the kerf along the working depth
    a, b = _polygons([drawn[0], drawn[2]], 0.001)
    assert a.intersection(b).area < 0.01
    a, b = _polygons([beams[0], beams[2]], 0.001)
    assert a.intersection(b).area > 0.1


def test_each_gear_carries_the_assembly_dot_facing_its_mate(spur):
    d = spur
    m = d.detail.teeth.plan.module
    mark = d.params.output.mark_layer
    dots = []
    for part, placement in zip(d.parts(), d.placements):
        drawing = part_drawing(d, part)
        assert not drawing.closed[mark], part.name  # nothing closed to engrave: a fill has nothing to fill
        # the dot: a diamond drawn round, four straight strokes back to its start
        dot = [
            r
            for r in drawing.strokes[mark]
            if hasattr(r, "bulges")
            and len(r.vertices) == 5
            and np.allclose(r.vertices[0], r.vertices[-1])
            and np.all(r.bulges == 0)
        ]
        assert len(dot) == 1, part.name  # one dot per gear, besides the pitch curve's dashes
        dots.append(dot[0].vertices[:4].mean(axis=0) + np.asarray(placement.offset))
    # on the line of centres, two modules either side of the pitch point (20·2/2 = 20 mm)
    assert np.allclose([dots[0][1], dots[1][1]], 0.0, atol=1e-9)
    assert np.allclose([dots[0][0], dots[1][0]], [20 - 2 * m, 20 + 2 * m], atol=1e-9)
    report = json.dumps(d.report())
    assert '"ok": true' in report
