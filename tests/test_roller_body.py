"""The roller-body mechanism (gearcad.mechanisms.roller_body): its draft and its charts' data."""

import math

import numpy as np
import pytest
import shapely

import gearcad
from gearcad.bodies import rollers as RB
from gearcad.mechanisms import roller_body, roller_charts
from gearcad.profiles import load_profile

from .conftest import ROOT


@pytest.fixture(scope="module")
def toothed():
    """The toothed body of the example at a coarse tolerance: its roller radius is adjusted to fit
    whole teeth (0.1 R asked, 0.100295 R cut)."""
    params = gearcad.load_profile(ROOT / "profiles" / "roller_body_m3.toml", {"output.tolerance": 0.02})
    return params, roller_body.design(params)


def test_draft_holds_the_body_and_three_rollers_that_mesh(toothed):
    params, draft = toothed
    assert [s.name for s in draft.parts] == ["body", "roller"]
    assert [c.second for c in draft.contacts] == [1, 2, 3] and all(c.module for c in draft.contacts)
    # three rollers 120° apart on the unit circle (R = scale)
    centres = np.array([pl.offset for pl in draft.placements[1:]])
    np.testing.assert_allclose(np.hypot(*centres.T), params.scale, rtol=1e-12)


def test_velocity_field_is_drawn_at_the_radius_the_rollers_are_cut_at(toothed):
    params, draft = toothed
    cut = draft.data["teeth"]["roller_radius"]
    assert cut != pytest.approx(params.roller_radius, abs=1e-5)  # adjusted to whole teeth
    chart = draft.charts["velocity_field.png"]
    assert chart["roller_radius"] == cut
    # independently: the drawn contour at φ = 0 is the roller path moved in by the cut radius
    # (a parallel curve), so every drawn point lies at that distance from the path
    osc = draft.detail.oscillation
    shift = RB.point_motion(osc, 0.0, 0.0, w=1.0, t=np.array([0.0]))[0][0]
    path = RB.roller_path(osc, np.linspace(0, 2 * math.pi, 40000)) + shift
    points = chart["field"][0]["points"]
    distance = shapely.distance(shapely.points(points), shapely.LineString(path))
    np.testing.assert_allclose(distance, cut, atol=1e-6)
    assert np.all(np.abs(distance - params.roller_radius) > 2e-4)  # not the requested radius
    assert [f["degrees"] for f in chart["field"]] == list(roller_charts.FIELD_ANGLES)


def test_velocity_field_arrows_have_a_scale_with_units(toothed, monkeypatch, tmp_path):
    """Issue 37 item 14: each row of velocity_field.png draws its arrows to one scale in drawing
    units (an arrow's length in R is its value over the scale), and every panel keys it with an
    arrow of a round length and its unit; the longest arrow is a readable fraction of R."""
    from matplotlib.quiver import Quiver, QuiverKey

    from gearcad.export.charts import mechanisms as charts

    figures = []
    monkeypatch.setattr(charts, "save_png", lambda fig, path: figures.append(fig))
    chart = toothed[1].charts["velocity_field.png"]
    charts.field_chart(chart, tmp_path / "field.png")
    axes = np.array(figures[0].axes).reshape(2, 4)
    for row, (key, unit) in enumerate((("velocity", "R/s"), ("acceleration", "R/s²"))):
        longest = max(float(np.max(np.linalg.norm(at[key], axis=1))) for at in chart["field"])
        scales = set()
        for ax in axes[row]:
            (arrows,) = [c for c in ax.collections if isinstance(c, Quiver)]
            (keyed,) = [a for a in ax.artists if isinstance(a, QuiverKey)]
            assert arrows.scale_units == "xy" and arrows.angles == "xy" and keyed.Q is arrows
            assert keyed.text.get_text() == f"{keyed.U:g} {unit}"
            mantissa = keyed.U / 10 ** math.floor(math.log10(keyed.U))
            assert round(mantissa, 9) in (1, 2, 5) and longest / 2.5 <= keyed.U <= longest
            scales.add(arrows.scale)
        (scale,) = scales  # one scale a row
        assert 0.2 <= longest / scale <= 0.5  # the longest arrow, in R


def test_no_chart_data_when_no_charts_are_asked_for():
    params = load_profile(ROOT / "profiles" / "roller_body_m3.toml", {"output.charts": False}, unset=["teeth"])
    assert roller_body.design(params).charts == {}
