"""Gears from a required motion: the fitted law recovers the focus ellipse from its closed-form
motion, reports the error it makes, and a dwell is refused naming the smallest ratio teeth allow."""

import math

import numpy as np
import pytest

import gearcad
from gearcad.pitch.focus_pair import follower_angle

PHI = 2 * np.pi * np.arange(360) / 360
A, B, E = 25.0, 15.0, 50.0
ECC = math.sqrt(A * A - B * B) / A  # 0.8


def _profile(**gear1):
    return {
        "name": "motion",
        "gear1": {"curve": "motion", **gear1},
        "pair": {"center_distance": E},
        "teeth": {"module": 1.0},
    }


@pytest.mark.parametrize("source", ["follower_deg", "ratio"])
def test_the_focus_ellipse_from_its_motion(source):
    if source == "follower_deg":
        samples = np.degrees(follower_angle(PHI, A, B))
    else:  # ψ' of the focus pair in closed form: K/(cos²(φ/2) + K²·sin²(φ/2)), K = (a + c)/(a − c)
        k = (1 + ECC) / (1 - ECC)
        samples = k / (np.cos(PHI / 2) ** 2 + (k * np.sin(PHI / 2)) ** 2)
    report = gearcad.design(_profile(**{source: samples.tolist(), "tolerance_deg": 1e-8}), stage="teeth").report()
    motion, driver = report["motion"], report["gears"][0]
    assert motion["error_deg"] <= 1e-8 and motion["samples"] == 360
    r_min, r_max = driver["r_min"], driver["r_max"]
    assert (r_max - r_min) / (r_max + r_min) == pytest.approx(ECC, abs=1e-6)
    assert r_min + r_max == pytest.approx(2 * A, abs=1e-6)  # a focus ellipse rolls on its twin at E = 2a
    assert report["pair"]["closure_error"] < 1e-11
    assert motion["ratio_min"] == pytest.approx(1 / 9, abs=1e-6) and motion["ratio_max"] == pytest.approx(9, abs=1e-5)
    # the same teeth as the elliptic_focus profile (41, an odd count for the identical pair)
    assert driver["teeth"]["count"] == 41 and not driver["teeth"]["undercut"]


def test_a_dwell_is_refused_naming_the_smallest_ratio():
    ratio = 1 - 0.999 * np.cos(PHI)  # nearly stops at φ = 0
    with pytest.raises(gearcad.DesignError) as caught:
        gearcad.design(_profile(ratio=ratio.tolist()), stage="pitch")
    text = str(caught.value)
    # the root at module 1 (dedendum 1.25) and a wall of one module: r1 ≥ 2.25 mm, k = r/(E − r)
    assert f"the smallest ratio the teeth allow is {2.25 / (E - 2.25):.4g}" in text
    assert text.startswith("gear1.ratio:") and "misses it by 57.24°" in text  # order 0: max |0.999·sin φ|


def test_a_motion_that_cannot_close_reports_the_best_error():
    drift = np.degrees(1.1 * PHI)  # the follower would gain 36° a turn: no closing law follows it
    with pytest.raises(gearcad.DesignError, match=r"gear1.follower_deg: ") as caught:
        gearcad.design(_profile(follower_deg=drift.tolist(), tolerance_deg=1.0), stage="pitch")
    # the periodic part 0.1·φ spans 35.9° over the samples and jumps back at the seam: a constant
    # offset misses by half the span, and a smooth law cannot do much better across the jump
    best = float(str(caught.value).split("misses it by ")[1].split("°")[0])
    assert 15.0 < best <= 17.95 + 1e-9


def test_motion_profile_errors():
    with pytest.raises(gearcad.ProfileError, match="exactly one"):
        gearcad.parse_profile(_profile())
    with pytest.raises(gearcad.ProfileError, match="center_distance"):
        gearcad.parse_profile({**_profile(ratio=[1.0] * 8), "pair": {"center_distance": "solve"}})


def test_measured_radii_smoothing():
    from gearcad.pitch.shapes import ellipse_focus, from_samples

    phi = 2 * np.pi * np.arange(720) / 720
    true = ellipse_focus(25.0, 20.0).r(phi)
    noisy = true + np.random.default_rng(1).uniform(-0.04, 0.04, len(phi))  # a scanner's ±0.04 mm
    profile = {"name": "scan", "gear1": {"curve": "samples", "radii": noisy.tolist(), "smoothing": 0.1}}
    report = gearcad.design(profile, stage="pitch").report()
    smoothing = report["gears"][0]["smoothing"]
    assert smoothing["allowed"] == 0.1 and 0.04 <= smoothing["deviation"] <= 0.1
    assert not [w for w in report["warnings"] if w["code"] == "concave"]
    # nearer the true curve than the samples are: the noise is gone, not copied
    smoothed = from_samples("scan", noisy, smoothing=0.1).r(phi)
    assert np.max(np.abs(smoothed - true)) < 0.8 * np.max(np.abs(noisy - true))
