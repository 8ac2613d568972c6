"""Stages: ``pitch`` and ``teeth`` say what the full design would, by other means, and claim no more.

The closed-form focus pair is held against the spectral synthesis of the full build, and the
teeth stage's equivalent-spur-gear tip land against the land measured on the cut outline.
"""

import json
import math

import numpy as np
import pytest

import gearcad
from gearcad.cli import main
from gearcad.mechanisms.pair_stages import tip_land
from gearcad.pitch.focus_pair import focus_pair, follower_angle
from gearcad.teeth.rack import RackParams

from .conftest import ROOT


def _built(built, name):
    return json.loads((built / name / "report.json").read_text(encoding="utf-8"))


@pytest.mark.parametrize("name", ["elliptic_focus", "spur_pair"])
def test_stages_agree_with_the_full_build(built, name):
    full = _built(built, name)
    teeth = gearcad.design(ROOT / "profiles" / f"{name}.toml", stage="teeth").report()
    assert teeth["stage"] == "teeth" and full["stage"] == "full"
    for key in ("center_distance", "ratio_min", "ratio_max"):
        assert teeth["pair"][key] == pytest.approx(full["pair"][key], rel=1e-9)
    for g_full, g in zip(full["gears"], teeth["gears"]):
        for key in ("r_min", "r_max", "perimeter", "min_curvature_radius", "convexity_margin_min"):
            assert g[key] == pytest.approx(g_full[key], rel=1e-9), key
        t_full, t = g_full["teeth"], g["teeth"]
        assert (t["count"], t["undercut"], t["pointed"]) == (t_full["count"], t_full["undercut"], False)
        assert t["module"] == pytest.approx(t_full["module"], rel=1e-12)
        # the involute land at the smallest radius of curvature vs the land measured on the cut outline
        assert t["min_tip_thickness"] == pytest.approx(t_full["min_tip_thickness"], abs=0.002)


def test_a_stage_claims_nothing_it_did_not_compute():
    report = gearcad.design(ROOT / "profiles" / "elliptic_focus.toml", stage="pitch").report()
    assert report["stage"] == "pitch" and report["pair"]["method"] == "closed form"
    assert not {"parts", "assembly", "output", "files", "kinematics"} & set(report)
    assert all("teeth" not in g and "part" not in g for g in report["gears"])


def test_focus_pair_closed_form():
    f = focus_pair(25.0, 15.0)
    # Meshchersky 14.6: a = 25, b = 15 → c = 20, ratio from 1/9 to 9, E = 2a
    assert (f.r_min, f.r_max, f.center_distance) == (5.0, 45.0, 50.0)
    assert f.ratio_range == pytest.approx((1 / 9, 9.0), rel=1e-15)
    assert max(f.contact_residual, f.slip_residual) < 1e-12
    phi = np.linspace(0, 2 * math.pi, 9)
    psi = follower_angle(phi, 25.0, 15.0)
    assert psi[0] == 0 and psi[-1] == pytest.approx(2 * math.pi, abs=1e-14) and psi[4] == pytest.approx(math.pi)
    # half the perimeter from apex to apex; the ellipse's perimeter by Ramanujan's second formula (error ~h⁵)
    h = ((25 - 15) / (25 + 15)) ** 2
    assert f.arc(np.array([math.pi]))[0] == pytest.approx(f.perimeter / 2, rel=1e-14)
    assert f.perimeter == pytest.approx(math.pi * 40 * (1 + 3 * h / (10 + math.sqrt(4 - 3 * h))), rel=1e-7)


def test_tip_land_textbook():
    # ISO 21771 spur gear, z = 20, m = 2, α = 20°, x = 0: s_a = d_a(π/2z + inv α − inv α_a)
    alpha = math.radians(20)
    a_tip = math.acos(40 * math.cos(alpha) / 44)
    expected = 44 * (math.pi / 40 + math.tan(alpha) - alpha - math.tan(a_tip) + a_tip)
    assert tip_land(20.0, RackParams(module=2.0)) == pytest.approx(expected, rel=1e-12)
    assert expected == pytest.approx(1.3898, abs=1e-4)


def test_stage_cli_and_refusals(capsys):
    assert main(["check", "--stage", "teeth", str(ROOT / "profiles" / "elliptic_focus.toml")]) == 0
    assert "stage teeth" in capsys.readouterr().out
    walker = ROOT / "profiles" / "walker.toml"
    assert main(["check", "--stage", "teeth", "--set", "gear1.blend_width_deg=0", str(walker)]) == 2
    assert "corners" in capsys.readouterr().err
    assert main(["check", "--stage", "pitch", str(ROOT / "profiles" / "roller_body_m3.toml")]) == 2
    assert "roller-body has no stages before 'full'" in capsys.readouterr().err
    with pytest.raises(gearcad.ProfileError, match="stage = 'mesh'"):
        gearcad.design(walker, stage="mesh")
