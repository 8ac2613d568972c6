"""The internal conjugate (gearcad.pitch.internal): a pinion rolling inside a ring about fixed
centres, against closed forms — circles, and the focus ellipse in a two-lobe ring."""

import math
from dataclasses import replace

import numpy as np
import pytest

from gearcad.errors import DesignError
from gearcad.mechanisms import nc_internal
from gearcad.pitch import shapes
from gearcad.pitch.internal import internal_pair


def test_circles_are_an_internal_spur_pair():
    """A circle of radius 10 as 2 "lobes" in a ring of 3: ring radius 15, E = 5, ratio 2/3; the
    curvature margin 1/10 − 1/15."""
    pair = internal_pair(replace(shapes.circle(10.0), lobes=2), ring_lobes=3)
    assert pair.center_distance == pytest.approx(5.0, abs=1e-12)
    assert pair.ring.r(np.linspace(0, 6, 7)) == pytest.approx(15.0, abs=1e-12)
    assert pair.angle_map(np.array([1.0]))[0] == pytest.approx(2 / 3, abs=1e-13)
    assert pair.curvature_margin == pytest.approx(1 / 10 - 1 / 15, abs=1e-12)


def test_the_focus_ellipse_closes_in_a_two_lobe_ring_at_the_closed_form():
    """r = p/(1 − ε·cos φ): ∫ r/(r + E) dφ = 2πp/√((p + E)² − E²ε²); closing at π (two lobes)
    gives (1 − ε²)E² + 2pE − 3p² = 0."""
    a, b = 25.0, 15.0
    p, eps = b * b / a, math.sqrt(a * a - b * b) / a
    exact = p * (math.sqrt(1 + 3 * (1 - eps**2)) - 1) / (1 - eps**2)
    pair = internal_pair(shapes.ellipse_focus(a, b), ring_lobes=2)
    assert pair.center_distance == pytest.approx(exact, rel=1e-13)
    assert pair.closure_error < 1e-11
    assert max(pair.contact_residual, pair.slip_residual) < 1e-9
    # the rolling checked without the pair's own angle map: trapezoid sums of r1/(r1 + E)
    phi = np.linspace(0.0, 2 * math.pi, 200001)
    r1 = pair.pinion.r(phi)
    rate = r1 / (r1 + exact)
    phi2 = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(phi))])
    k = np.arange(0, len(phi), 20000)
    assert pair.ring.r(phi2[k]) == pytest.approx(r1[k] + exact, abs=1e-6)
    assert phi2[-1] == pytest.approx(math.pi, abs=1e-8)


def test_a_ring_needs_more_lobes_than_its_pinion():
    with pytest.raises(DesignError, match=r"^ring.lobes = 2: .* 3 or more"):
        internal_pair(replace(shapes.circle(10.0), lobes=2), ring_lobes=2)


# ----------------------------------------------------------------------------- the mechanism


def _params(pinion: dict, lobes: int, count: int, backlash: float = 0.1, tolerance: float = 0.01):
    from gearcad.profiles import validated
    from gearcad.profiles.nc_internal import NcInternalParams

    return validated(
        NcInternalParams,
        **{
            "name": "nci",
            "mechanism": "nc-internal",
            "pinion": {"name": "pinion", **pinion},
            "ring": {"lobes": lobes},
            "teeth": {"count": count, "backlash": backlash},
            "output": {"tolerance": tolerance, "charts": False, "animation": False},
        },
    )


@pytest.fixture(scope="module")
def oval():
    return nc_internal.design(_params({"curve": "oval", "a": 20.0, "b": 16.0}, 3, 30))


def test_a_circle_in_a_two_lobe_ring_is_an_internal_spur_pair():
    """A circle of radius 15 (24 teeth) in a "two-lobe" ring: ring radius 30, E = 15, 48 teeth
    of module 1.25; the ring's hole is the hole cut on a circle of radius 30, point for point."""
    from gearcad.teeth.frame import arc_frame
    from gearcad.teeth.gear import cut_teeth

    draft = nc_internal.design(_params({"curve": "circle", "radius": 15.0}, 2, 24))
    assert draft.data["pair"]["center_distance"] == pytest.approx(15.0, abs=1e-12)
    assert draft.data["teeth"]["module"] == pytest.approx(1.25, abs=1e-12)
    assert draft.data["teeth"]["ring_teeth"] == 48
    rack = nc_internal._rack(1.25, math.radians(20), 0.1, internal=True)
    circle = cut_teeth(arc_frame(shapes.circle(30.0)), rack, 48, rack.pitch / 2, tolerance=0.0025)
    hole = draft.parts[1].hole
    r_hole, a_hole = np.hypot(*hole.T), np.arctan2(hole[:, 1], hole[:, 0])
    ring = circle.outline.outer
    order = np.argsort(np.arctan2(ring[:, 1], ring[:, 0]))
    r_exact = np.interp(a_hole, np.arctan2(ring[order, 1], ring[order, 0]), np.hypot(*ring[order].T), period=2 * np.pi)
    assert np.max(np.abs(r_hole - r_exact)) < 0.02  # both within the tolerance of the same outline
    assert draft.data["mesh"]["max_overlap"] == 0.0


def test_the_oval_in_a_three_lobe_ring_meshes_over_its_cycle(oval):
    mesh = oval.data["mesh"]
    assert oval.data["pair"]["closure_error"] < 1e-11
    assert mesh["positions"] >= 3 * 30 * 3  # three pinion turns, a position per third of a tooth
    assert mesh["max_overlap"] <= mesh["allowed_overlap"]
    assert mesh["max_depth"] <= mesh["allowed_depth"]
    assert mesh["nudged_min_overlap"] > mesh["allowed_overlap"]
    # the backlash is 0.1 mm on the pitch curves: the play is some of it, never more
    assert 0.0 < mesh["least_play"] <= 0.1 + 4 * 0.01
    assert not oval.findings


def test_the_parts_sit_where_the_pitch_curves_touch(oval):
    """The two pitch-curve marks, placed, touch on the +x axis at r1(0) and nowhere cross."""
    pinion_mark, ring_mark = oval.parts[0].marks[0], oval.parts[1].marks[0]
    e = oval.data["pair"]["center_distance"]
    placed_ring = ring_mark + (-e, 0.0)
    r_pinion = np.interp(0.0, *_polar(pinion_mark), period=2 * np.pi)
    r_ring = np.interp(0.0, *_polar(ring_mark), period=2 * np.pi)
    assert r_ring - e == pytest.approx(r_pinion, abs=0.01)
    angles, radii = _polar(pinion_mark)
    # every pinion pitch point inside the ring's pitch curve (about the ring's centre)
    p = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)]) + (e, 0.0)
    ring_a, ring_r = _polar(placed_ring + (e, 0.0))
    assert np.all(np.hypot(*p.T) <= np.interp(np.arctan2(p[:, 1], p[:, 0]), ring_a, ring_r, period=2 * np.pi) + 0.01)


def _polar(ring):
    angle, radius = np.arctan2(ring[:, 1], ring[:, 0]), np.hypot(ring[:, 0], ring[:, 1])
    order = np.argsort(angle)
    return angle[order], radius[order]


def test_a_ring_too_close_in_teeth_to_its_pinion_is_caught_by_the_proof():
    """20 teeth in 30: the tips of the two toothings cross away from the pitch point (an internal
    pair needs the ring well ahead in teeth); the proof over the cycle finds it and says so."""
    draft = nc_internal.design(_params({"curve": "oval", "a": 30.0, "b": 24.0}, 3, 20, backlash=0.2))
    assert draft.data["mesh"]["max_depth"] > 0.1
    assert [f.code for f in draft.findings] == ["interference"]


def test_bad_counts_are_refused_in_one_line():
    from gearcad.errors import ProfileError

    with pytest.raises(ProfileError, match=r"ring.lobes = 2: must exceed the pinion's 2 lobes"):
        _params({"curve": "oval", "a": 20.0, "b": 16.0}, 2, 30)
    with pytest.raises(
        ProfileError, match=r"teeth.count = 31: the ring's 31·3/2 teeth must be whole: give a multiple of 2"
    ):
        _params({"curve": "oval", "a": 20.0, "b": 16.0}, 3, 31)


def test_the_example_pairs_least_play_is_proven_under_an_independent_sweep(built):
    """report.json's band of the example pair (no process: the parts as drawn) is proven by the
    theorem, and its certified least play lies under the least play an independent sweep measures
    at 120 even pinion angles over the cycle (a pinion lobe, the ring then a lobe on: both
    outlines repeat by their lobes; 2.7 times the positions the proof starts from): the pinion turned
    −φ about O, the ring −φ2(φ) about (−E, 0) by the angle map, the ring turned each way about its
    pivot by bisection on whether it meets the pinion (shapely; in the ring's frame the pinion
    turned back, cut only within the ring's least radius, where it cannot touch), times the ring's
    pitch radius r1 + E at the contact.  At the band's tightest place the sweep's measure is the
    band's own least to 1 µm; the bound keeps the margin (the parts may bite 4·tol/cos α)."""
    import json

    import shapely

    from .conftest import drafted
    from .fit_oracle import _turn, turns_free

    (band,) = json.loads((built / "nc_internal" / "report.json").read_text())["bands"]
    draft = drafted("nc_internal", nc_internal.design)[1]
    pair = draft.detail
    e = pair.center_distance
    pinion, ring = (shapely.Polygon(p.outer, None if p.hole is None else [p.hole]) for p in draft.parts)
    assert band["mesh"] == "pinion/ring" and pair.lobes == (2, 3)

    def sweep(phi):
        phi2 = pair.angle_map(phi)
        pivot = _turn(np.column_stack([e + 0 * phi, 0 * phi]), phi2)  # the pinion's pivot in the ring's frame
        inside = shapely.buffer(shapely.points(_turn(-pivot, phi - phi2)), np.hypot(*ring.interiors[0].xy).min() - 0.01)
        pieces = shapely.difference(pinion, inside)
        up, down = turns_free(ring, pieces, lambda k, xy, t: _turn(_turn(xy, phi2[k] - phi[k]) + pivot[k], t), 0.01)
        return (up + down) * (pair.pinion.r(np.mod(phi, 2 * math.pi)) + e)

    plays = sweep(np.arange(120) * math.pi / 120)
    assert band["certificate"] == "theorem" and band["proven"] and band["verdict"] == "fits"
    assert -4 * 0.01 / math.cos(math.radians(20)) <= band["certified_min"] <= float(plays.min()) + 1e-6
    assert band["certified_min"] <= band["min"] and sweep(np.array([band["worst_phi"]]))[0] == pytest.approx(
        band["min"], abs=1e-3
    )
