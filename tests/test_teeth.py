"""Teeth: the rack envelope against the involute, the undercut limit, a boolean reference
method, tooth planning, and the mesh proof (which must be able to fail)."""

import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from gearcad.errors import DesignError
from gearcad.geometry.outline import ring_area
from gearcad.pitch import shapes
from gearcad.pitch.pair import conjugate_pair
from gearcad.teeth.frame import arc_frame
from gearcad.teeth.gear import cut_teeth, remove_loops
from gearcad.teeth.loops import remove_loops_each
from gearcad.teeth.mesh import mesh_check
from gearcad.teeth.pair import undercut_free_module
from gearcad.teeth.plan import plan_teeth
from gearcad.teeth.rack import Rack, RackParams
from gearcad.teeth.reference import rack_cut

ALPHA = math.radians(20)
TOL = 0.001


def _involute(t):
    return np.tan(t) - t


def spur(z, m=2.0, **rack):
    frame = arc_frame(shapes.circle(z * m / 2))
    r = Rack.from_params(RackParams(module=m, **rack))
    return cut_teeth(frame, r, z, r.pitch / 2, tolerance=TOL), frame


@pytest.mark.parametrize("z", [18, 20, 40, 97])
def test_circular_flanks_are_involutes_of_the_base_circle(z):
    """Every flank vertex between the form radius and the tip lies on the involute of
    r·cos α, and so does the curve between vertices (chords within the tolerance)."""
    m = 2.0
    gear, _ = spur(z, m)
    ring = gear.outline.outer
    r = z * m / 2
    rb = r * math.cos(ALPHA)
    rad = np.hypot(ring[:, 0], ring[:, 1])
    v_low = gear.rack.v_low
    r_form = math.hypot(r + v_low, v_low / math.tan(ALPHA))  # where the straight flank ends
    flank = (rad > r_form + 1e-6) & (rad < r + m - 1e-6)
    polar = np.arctan2(ring[:, 1], ring[:, 0])
    # tooth centres at 2πk/z; each flank is ±(π/2z + inv α − inv α_R) from its tooth centre
    roll = _involute(np.arccos(np.clip(rb / rad, -1, 1)))
    half = math.pi / (2 * z) + _involute(ALPHA) - roll
    pitch_angle = 2 * math.pi / z
    offset = (polar + pitch_angle / 2) % pitch_angle - pitch_angle / 2  # from the nearest tooth centre
    deviation = rb * np.abs(np.abs(offset) - half)  # normal distance to the involute
    assert np.count_nonzero(flank) > 4 * z
    assert deviation[flank].max() < 1e-9
    # between vertices: chord sag of an involute flank is bounded by the sampler's tolerance
    tip_radius = np.max(rad)
    assert tip_radius == pytest.approx(r + m, abs=1e-9)
    assert np.min(rad) == pytest.approx(r - 1.25 * m, abs=1e-9)


def test_tip_land_of_a_spur_gear_matches_the_textbook():
    z, m = 20, 2.0
    gear, _ = spur(z, m)
    ra, r = z * m / 2 + m, z * m / 2
    alpha_a = math.acos(r * math.cos(ALPHA) / ra)
    half_angle = math.pi / (2 * z) + _involute(ALPHA) - _involute(alpha_a)
    chord = 2 * ra * math.sin(half_angle)
    np.testing.assert_allclose(gear.tip_thickness, chord, rtol=1e-9)


def test_undercut_free_limit_of_a_20_degree_rack():
    """Closed form: no undercut iff r·sin²α ≥ (h_f − ρ_f(1 − sin α))·m, i.e. z ≥ 17.097."""
    z_min = 2 * (1.25 - 0.38 * (1 - math.sin(ALPHA))) / math.sin(ALPHA) ** 2
    assert z_min == pytest.approx(17.097, abs=1e-3)
    for z in (8, 12, 16):
        gear, _ = spur(z)
        assert gear.undercut and np.all(gear.undercut_depth > 0)
    for z in (18, 25, 60):
        gear, _ = spur(z)
        assert not gear.undercut and np.all(gear.space_loops == 0)
    gear, _ = spur(17)  # just below the limit: a sliver of undercut
    assert 0 < gear.undercut_depth.max() < 0.01 * 2.0
    m_limit = undercut_free_module(17 * 2.0 / 2, RackParams(module=2.0))
    assert m_limit * z_min / 2 == pytest.approx(17 * 2.0 / 2, rel=1e-12)


@pytest.mark.parametrize("z", [12, 20])
def test_envelope_matches_boolean_rack_cut_reference(z):
    """Independent method: blank minus 48 rack copies per pitch, what a rack cutter does —
    including the undercut at z = 12, which the envelope trims by loop removal."""
    gear, frame = spur(z)
    reference = rack_cut(frame, gear.rack, z, gear.phase, steps_per_pitch=48)
    distance = shapely.hausdorff_distance(reference.exterior, shapely.Polygon(gear.outline.outer).exterior)
    assert distance < 0.002


def test_elliptic_gear_against_the_reference_and_its_own_perimeter():
    frame = arc_frame(shapes.ellipse_focus(25, 15))
    z = 41
    rack = Rack.from_params(RackParams(module=frame.perimeter / (z * math.pi)))
    gear = cut_teeth(frame, rack, z, rack.pitch / 2, tolerance=TOL)
    reference = rack_cut(frame, rack, z, gear.phase, steps_per_pitch=48)
    assert shapely.hausdorff_distance(reference.exterior, shapely.Polygon(gear.outline.outer).exterior) < 0.002
    with pytest.raises(DesignError, match="is not 40"):
        cut_teeth(frame, rack, 40, 0.0, tolerance=TOL)


def test_vertices_fall_as_the_tolerance_loosens():
    frame = arc_frame(shapes.ellipse_focus(25, 15))
    rack = Rack.from_params(RackParams(module=frame.perimeter / (41 * math.pi)))
    counts = [cut_teeth(frame, rack, 41, rack.pitch / 2, tolerance=t).outline.vertex_count for t in (1e-4, 1e-3, 1e-2)]
    assert counts[0] > counts[1] > counts[2]


def test_pointed_teeth_are_found():
    gear, _ = spur(10, addendum=1.6, dedendum=1.9, tip_radius=0.1)
    assert len(gear.pointed) == 10 and np.all(gear.tip_thickness <= 0)
    assert shapely.Polygon(gear.outline.outer).is_valid  # trimmed at the flank crossing


def test_module_too_large_for_the_curve_is_an_error():
    """Teeth 6 mm deep at an apex whose radius of curvature is 1.44 mm cannot be cut."""
    frame = arc_frame(shapes.ellipse_focus(25, 6))
    rack = Rack.from_params(RackParams(module=frame.perimeter / (14 * math.pi)))
    with pytest.raises(DesignError, match="smaller teeth.module"):
        cut_teeth(frame, rack, 14, rack.pitch / 2, tolerance=TOL)


def test_remove_loops_cuts_a_figure_of_eight():
    pts = np.array([[0, 0], [2, 0], [2, 1], [1, -1], [1, -2], [3, -2]], dtype=float)
    out, n = remove_loops(pts)
    assert n == 1
    np.testing.assert_allclose(out, [[0, 0], [1.5, 0], [1, -1], [1, -2], [3, -2]])


def test_remove_loops_each_cuts_each_line_as_alone():
    """Lines that cross each other but not themselves keep every vertex; each line's own
    loop is cut at its crossing, worked out by hand."""
    eight = np.array([[0, 0], [2, 0], [2, 1], [1, -1], [1, -2], [3, -2]], dtype=float)
    across = np.array([[1, 2], [1, -3], [1.2, -3], [1.2, 2]], dtype=float)
    out = remove_loops_each([eight, across, eight[:3], eight + 10])
    assert [n for _, n in out] == [1, 0, 0, 1]
    # segment 0 (y = 0) meets segment 2 ((2, 1) -> (1, -1)) at (1.5, 0): the loop through (2, 0), (2, 1) goes
    cut = np.array([[0, 0], [1.5, 0], [1, -1], [1, -2], [3, -2]], dtype=float)
    np.testing.assert_allclose(out[0][0], cut, atol=1e-15)
    np.testing.assert_array_equal(out[1][0], across)
    np.testing.assert_allclose(out[3][0], cut + 10, atol=1e-14)
    np.testing.assert_array_equal(out[0][0], remove_loops(eight)[0])  # remove_loops: one line alone


def _pair_and_plan(curve, mate_lobes, **kw):
    pair = conjugate_pair(curve, mate_lobes=mate_lobes)
    frames = (arc_frame(pair.gear1), arc_frame(pair.gear2))
    return pair, frames, plan_teeth(frames[0], frames[1], pair.lobes, **kw)


def test_identical_focus_ellipses_need_an_odd_count():
    curve = shapes.ellipse_focus(25, 15)
    _, _, plan = _pair_and_plan(curve, 1, module=1.0, identical_rotation=0.0)
    assert plan.teeth == (41, 41) and plan.identical
    assert plan.module * math.pi * 41 == pytest.approx(arc_frame(curve).perimeter, rel=1e-12)
    with pytest.raises(DesignError, match="nearest counts that can: 39, 41"):
        _pair_and_plan(curve, 1, count=40, identical_rotation=0.0)


def test_identical_ovals_need_an_odd_count_per_lobe():
    _, _, plan = _pair_and_plan(shapes.oval(25, 15), 2, module=1.0, identical_rotation=math.pi / 2)
    assert plan.teeth[0] % 4 == 2


def test_counts_follow_the_lobe_ratio():
    _, _, plan = _pair_and_plan(shapes.circle(20.0), 2, count=20)
    assert plan.teeth == (20, 40) and plan.module == pytest.approx(2.0)
    law = shapes.harmonic_ratio(4.0, [(4, 0.4, 0.0)])
    wheel = shapes.from_ratio("law", *law, 75.0, lobes=4)
    pair = conjugate_pair(wheel, mate_lobes=1, center_distance=75.0)
    frames = (arc_frame(pair.gear1), arc_frame(pair.gear2))
    with pytest.raises(DesignError, match="multiple of 4"):
        plan_teeth(*frames, pair.lobes, count=82)
    assert plan_teeth(*frames, pair.lobes, count=80).teeth == (80, 20)


def _cut_pair(curve, mate_lobes, **kw):
    """The pair cut at :data:`TOL`, and gear 2 cut again a tenth of a pitch out of phase."""
    pair, frames, plan = _pair_and_plan(curve, mate_lobes, **kw)
    racks = [Rack.from_params(RackParams(module=plan.module)) for _ in range(2)]
    gears = tuple(cut_teeth(f, r, z, ph, tolerance=TOL) for f, r, z, ph in zip(frames, racks, plan.teeth, plan.phases))
    shifted = cut_teeth(frames[1], racks[1], plan.teeth[1], plan.phases[1] + racks[0].pitch / 10, tolerance=TOL)
    return pair, gears, (gears[0], shifted), frames


@pytest.mark.parametrize(
    "curve,lobes,kw",
    [
        (shapes.ellipse_focus(25, 15), 1, {"module": 1.0, "identical_rotation": 0.0}),
        (shapes.ellipse_centre(25, 15), 2, {"module": 1.25}),
        (shapes.circle(20.0), 2, {"count": 20}),
    ],
)
def test_pairs_mesh_and_the_check_can_fail(curve, lobes, kw):
    pair, gears, wrong, frames = _cut_pair(curve, lobes, **kw)
    mesh = mesh_check(pair, gears, frames, tolerance=TOL)
    assert mesh.max_overlap <= mesh.allowed_overlap
    assert mesh.nudged_min_overlap > 10 * mesh.allowed_overlap
    assert mesh.meshes
    # the same pair with gear 2's teeth a tenth of a pitch out of phase interferes (everywhere:
    # a quarter of the positions shows it as well as all of them)
    bad = mesh_check(pair, wrong, frames, tolerance=TOL, positions=90)
    assert bad.max_overlap > 100 * bad.allowed_overlap and not bad.meshes


FAST = settings(max_examples=15, deadline=None)


@FAST
@given(a=st.floats(10, 60), ecc=st.floats(0.0, 0.7), z=st.integers(20, 60), pivot=st.sampled_from(["focus", "centre"]))
def test_random_toothed_outlines_are_simple_ccw_rings(a, ecc, z, pivot):
    curve = (shapes.ellipse_focus if pivot == "focus" else shapes.ellipse_centre)(a, a * math.sqrt(1 - ecc**2))
    frame = arc_frame(curve)
    m = frame.perimeter / (z * math.pi)
    rack = Rack.from_params(RackParams(module=m))
    try:
        gear = cut_teeth(frame, rack, z, rack.pitch / 2, tolerance=TOL)
    except DesignError as exc:  # a clear refusal is allowed, a wrong outline is not
        assert "smaller teeth.module" in str(exc)
        return
    ring = gear.outline.outer
    polygon = shapely.Polygon(ring)
    assert polygon.is_valid and ring_area(ring) > 0
    # the gear lies between its root and tip offset curves
    s = np.linspace(0, frame.perimeter, 20000, endpoint=False)
    c, _, n = frame.frame(s)
    tip, root = shapely.Polygon(c + rack.v_tip * n), shapely.Polygon(c + rack.v_root * n)
    assert root.area - 1e-6 <= polygon.area <= tip.area + 1e-6
    assert polygon.buffer(1e-4).contains(root.buffer(-1e-3)) and tip.buffer(1e-4).contains(
        polygon
    )  # chord sag of the 20000-gons


@pytest.mark.parametrize("backlash,clearance", [(0.1, 0.0), (0.0, 0.1)])
def test_measured_play_matches_the_designed_one(backlash, clearance):
    """Backlash b thins each tooth by b/2: the pair plays b on the pitch circle.  A clearance c
    moves every flank in by c along its normal: 2c between flanks on each side, so 4c/cos α of
    play in all — both measured by turning gear 2 until it touches gear 1."""
    from gearcad.fitting import design
    from gearcad.profiles import parse_profile

    params = parse_profile(
        {
            "gear1": {"curve": "circle", "radius": 20.0},
            "gear2": {"lobes": 2},
            "teeth": {"count": 20, "backlash": backlash, "clearance": clearance},
        }
    )
    teeth = design(params).detail.teeth
    expected = backlash + 4 * clearance / math.cos(ALPHA)
    low, high = teeth.backlash_range
    assert low == pytest.approx(expected, abs=0.002) and high == pytest.approx(expected, abs=0.002)
    assert teeth.mesh.max_overlap == 0 and teeth.mesh.meshes


def test_printed_clearance_on_an_eccentric_pair_meshes_and_plays_as_designed():
    """The README's printing settings on the focus ellipse (ratio 1/9 … 9): the nudge turns gear 2
    by the same arc at the contact wherever it is, so it neither skips a tooth where gear 2 is
    large nor misses contact where it is small, and the measured play stays near 4c/cos α.
    (The play is the teeth's mesh measure: no charts, and the band bounded by the estimate, a
    third of the theorem's CPU, which gives the same mesh.)"""
    from gearcad.fitting import design
    from gearcad.profiles import load_profile

    from .conftest import QUICK

    params = load_profile(
        Path(__file__).parent.parent / "profiles" / "elliptic_focus.toml",
        {
            **QUICK,
            "teeth.clearance": 0.05,
            "output.tolerance": 0.01,
            "output.formats": ["dxf"],
            "output.certificate": "estimate",
        },
    )
    teeth = design(params).detail.teeth
    expected = 4 * 0.05 / math.cos(ALPHA)
    assert teeth.mesh.meshes
    low, high = teeth.backlash_range
    assert expected * 0.95 < low and high < 3 * expected


def test_sampling_is_called_off_when_asked():
    """A gear that cannot be cut sets the event; its mate's sampling then ends at the next round
    (the design's error is the failing gear's, see the stability map's eccentricity 0.99)."""
    import threading

    from gearcad.teeth.sampling import Stopped, sample_curves

    def circle(ids, t):
        return np.column_stack([np.cos(t), np.sin(t)])

    stop = threading.Event()
    assert len(sample_curves(circle, [0.0], [np.pi], 1e-6, stop=stop)[0]) > 100
    stop.set()
    with pytest.raises(Stopped):
        sample_curves(circle, [0.0], [np.pi], 1e-6, stop=stop)


def test_the_point_bound_is_each_rack_parts_not_the_gears(monkeypatch):
    """``sample_curves`` refuses past MAX_POINTS for one curve set; a gear's six rack parts are
    sampled in one call, so their bound is six times that, as when each part was sampled alone:
    a 40-tooth spur gear of ~2 000 points is cut with the bound at 600 a part (when the call held
    the whole gear to one part's bound, it was refused) and refused at 200."""
    import gearcad.teeth.gear as gear_module

    rack = Rack.from_params(RackParams(module=2.0, pressure_angle=math.radians(20), thinning=0.0))
    frame = arc_frame(shapes.circle(40.0))
    whole = len(gear_module.cut_teeth(frame, rack, 40, rack.pitch / 2, tolerance=0.01).outline.outer)
    assert 1200 < whole < 3000
    monkeypatch.setattr(gear_module, "MAX_POINTS", 600)
    assert len(gear_module.cut_teeth(frame, rack, 40, rack.pitch / 2, tolerance=0.01).outline.outer) == whole
    monkeypatch.setattr(gear_module, "MAX_POINTS", 200)
    with pytest.raises(DesignError, match="more than"):
        gear_module.cut_teeth(frame, rack, 40, rack.pitch / 2, tolerance=0.01)
