"""Contact ratio and working pressure angle of every toothed pair (issue 24, item 14).

Oracles: the textbook ε_α of a spur pair, the largest angle between an ellipse's focal radius
and its normal (asin e, at cos φ = e), and the tooth pairs counted in the placed outlines.
"""

import json
import math
from html import unescape

import numpy as np
import pytest
import shapely

import gearcad
from gearcad.teeth.mesh import placing

from .conftest import QUICK


def _contact(built, name):
    return json.loads((built / name / "report.json").read_text(encoding="utf-8"))["pair"]["teeth"]["contact"]


def test_spur_pair_contact_ratio_is_the_textbook_one(built):
    a, m = math.radians(20), 2.0
    rb1, rb2 = 20 * math.cos(a), 40 * math.cos(a)
    closed = (math.sqrt(22**2 - rb1**2) + math.sqrt(42**2 - rb2**2) - 60 * math.sin(a)) / (math.pi * m * math.cos(a))
    assert abs(closed - 1.6352) < 1e-4
    c = _contact(built, "spur_pair")
    for key in ("ratio_min", "ratio_max"):
        assert c[key] == pytest.approx(closed, rel=0.01)
    for key in ("pressure_angle_min_deg", "pressure_angle_max_deg", "coast_pressure_angle_max_deg"):
        assert abs(c[key] - 20.0) < 1e-6
    page = unescape((built / "spur_pair" / "index.html").read_text(encoding="utf-8"))
    assert f"contact ratio {c['ratio_min']:.3f}" in page and "working pressure angle 20.00°" in page


def test_focus_ellipse_pressure_angle_swings_by_asin_e(built):
    """r = p/(1 − e·cos φ) about a focus: the common tangent tilts by at most asin e off the
    perpendicular to the line of centres, at cos φ = e; e = 0.8 for a = 25, b = 15."""
    e = 0.8
    c = _contact(built, "elliptic_focus")
    tilt = math.degrees(math.asin(e))
    assert abs(c["pressure_angle_max_deg"] - (20 + tilt)) < 0.01
    assert abs(c["pressure_angle_min_deg"] - (20 - tilt)) < 0.01
    assert abs(c["pressure_angle_max_at_phi1_deg"] - math.degrees(math.acos(e))) <= 0.5
    assert abs(c["coast_pressure_angle_max_deg"] - (20 + tilt)) < 0.01
    assert 1.0 < c["ratio_min"] < c["ratio_max"] < 2.0
    for name in ("elliptic_centre", "walker", "herringbone_elliptic", "oval_centre"):
        c = _contact(built, name)
        assert 1.0 < c["ratio_min"] <= c["ratio_max"] < 2.5, name


def _counted(design, phi1, arc):
    """Mean number of tooth pairs overlapping with gear 2 turned ``arc`` mm into gear 1."""
    teeth, pair = design.detail.teeth, design.detail.pitch.pair
    place = placing(pair, teeth.gears, teeth.frames, phi1)
    g1, g2 = place(arc / (pair.center_distance - pair.gear1.r(phi1)))
    found = shapely.intersection(g1, g2)
    return float(np.mean([len(shapely.get_parts(x)) if not x.is_empty else 0 for x in found]))


def test_contact_ratio_is_the_tooth_pairs_counted_in_mesh():
    """Turned δ into gear 1, the driving flanks overlap a little beyond each end of the path of
    contact (by ~√δ): counts at δ and 4δ extrapolate to the touching count, 2·n(δ) − n(4δ),
    averaged over one pitch of the spur pair, which is ε itself."""
    # exact teeth: no default play (6·tol/cos α) between the flanks; the parts and the mesh's
    # contact ratio are what is read (no charts, the band bounded by the estimate: half the CPU)
    quick = {**QUICK, "output.certificate": "estimate"}
    design = gearcad.design(gearcad.load_profile("profiles/spur_pair.toml", {"teeth.backlash": 0.0, **quick}))
    phi1 = np.linspace(0.0, 2 * np.pi / 20, 100, endpoint=False)
    counted = 2 * _counted(design, phi1, 0.002) - _counted(design, phi1, 0.008)
    assert abs(counted - design.report()["pair"]["teeth"]["contact"]["ratio_min"]) < 0.03
