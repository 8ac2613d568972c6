"""The README's numbers, read from the golden table and compared with what the build wrote."""

import json
import math

import pytest

from gearcad.bodies import rollers as RB

from .conftest import read_dxf


def _report(built, name):
    return json.loads((built / name / "report.json").read_text(encoding="utf-8"))


def _same(value, entry):
    assert round(value, entry["digits"]) == pytest.approx(entry["value"], abs=10 ** -entry["digits"])


def test_gear_pairs(built, golden):
    centre = _report(built, "elliptic_centre")
    g = golden["elliptic_centre"]
    _same(centre["pair"]["center_distance"], g["center_distance"])
    _same(math.degrees(centre["claim"]["shortfall"]), g["claim_shortfall_deg"])
    _same(centre["claim"]["shape_difference"], g["claim_contact_miss_mm"])
    focus, g = _report(built, "elliptic_focus"), golden["elliptic_focus"]
    for key in ("center_distance", "ratio_min", "ratio_max"):
        _same(focus["pair"][key], g[key])
    _same(_report(built, "oval_centre")["pair"]["center_distance"], golden["oval_centre"]["center_distance"])


def test_walker(built, golden):
    w, g = _report(built, "walker")["walker"], golden["walker"]
    _same(w["i_paper"], g["i_paper"])
    _same(w["i"], g["i"])
    _same(math.degrees(w["paper_turn_per_quarter"]), g["paper_turn_per_quarter_deg"])
    _same(w["paper_slip"], g["paper_slip_mm_per_rad"])
    _same(w["paper_table_offset"], g["paper_table_offset_mm"])
    _same(100 * w["blend_ratio_deviation"], g["blend_ratio_deviation_percent"])


def test_roller_body(built, golden):
    r, g = _report(built, "roller_body_m3"), golden["roller_body_m3"]
    _same(r["body"]["amplitude_limit_convex"], g["amplitude_limit_convex"])
    _same(r["body"]["amplitude_limit_simple"], g["amplitude_limit_simple"])
    for value, expected in zip(r["limits"]["convex"], g["limits_convex"]["value"]):
        _same(value, {"value": expected, "digits": g["limits_convex"]["digits"]})
    for value, expected in zip(r["limits"]["simple"], g["limits_simple"]["value"]):
        _same(value, {"value": expected, "digits": g["limits_simple"]["digits"]})
    _same(r["limits"]["power_law_convex"]["coefficient"], g["power_law_coefficient"])
    _same(r["limits"]["power_law_convex"]["exponent"], g["power_law_exponent"])
    v, a = RB.centre_extremes(0.01, 3, 3 * math.pi)
    _same(v, golden["seed003_example"]["v_max_m_s"])
    _same(a, golden["seed003_example"]["a_max_m_s2"])


def test_rolling_wheel(built, golden):
    r, g = _report(built, "rolling_wheel"), golden["rolling_wheel"]
    _same(r["geometry"]["rack_length_start"], g["rack_length_start"])
    _same(r["geometry"]["rack_length_paper_eq2"], g["rack_length_paper_eq2"])
    _same(r["motion"]["ratio_horizontal_rack"], g["ratio_horizontal_rack"])


def test_compound_ring(built, golden):
    r, g = _report(built, "compound_ring"), golden["compound_ring"]
    _same(r["compound"]["omega3_rpm"], g["omega3_rpm"])
    _same(r["compound"]["omega3_seed_formula_rpm"], g["omega3_seed_formula_rpm"])
    _same(r["compound"]["radius_ratio"], g["radius_ratio"])
    (ring,) = [gear for gear in r["gears"] if gear["name"] == r["compound"]["gear"]]
    _same(ring["wall"], g["wall_mm"])


def test_output_size_stays_within_the_readme(built, golden):
    """The focus pair's driver (41 teeth, 0.001 mm): arcs need at most the README's count and
    at least 5× fewer vertices than chords within the same tolerance."""

    g = golden["output_size"]
    doc = read_dxf(built / "elliptic_focus" / "driver.dxf")  # the outline's vertices: the CUT layer's
    vertices = sum(len(e) for e in doc.modelspace().query('LWPOLYLINE[layer=="CUT"]'))
    assert vertices <= g["dxf_vertices_41_teeth_0.001"]["value"]
    assert g["arc_saving_at_least"]["value"] * vertices <= g["chord_vertices_41_teeth_0.001"]["value"]
