"""Issue 33 item 2: where the process's worst case brings the tips into the mate's roots, gearcad
gives them room with the keys the profile leaves out — the first-layer chamfer against a
printer's elephant foot, then ``teeth.clearance``, then a shorter ``teeth.addendum`` — before it
looks for the backlash.  Checked here against the radial closed form, on drafts made of plain
numbers (no design: cheap): the rack's radial clearance (dedendum − addendum)·m less both edges
at their largest, 2·δ, and the centres' error Δa, plus twice the clearance (every flank moved
in), must keep 5·tol + 0.03·m."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearcad.fitting.fit import radial_room, tip_choices

from .conftest import profile


def _draft(params, module: float, land: float):
    """A stand-in for a draft: the pitch module, every tooth's tip land ``land`` mm, and one part
    whose outline (a 20 mm circle) takes any chamfer."""
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    part = SimpleNamespace(outer=np.column_stack([20 * np.cos(t), 20 * np.sin(t)]), hole=None, caps=())
    gear = SimpleNamespace(tip_thickness=np.full(41, land))
    teeth = SimpleNamespace(plan=SimpleNamespace(module=module), gears=(gear, gear))
    return SimpleNamespace(params=params, parts=(part,), detail=SimpleNamespace(teeth=teeth))


def _lack(m: float, tol: float, edge: float, spread: float) -> float:
    """What the tips lack (mm) by the closed form with the standard rack: 5·tol + 0.03·m of room."""
    return 5 * tol + 0.03 * m - (0.25 * m - 2 * edge - spread)


@pytest.mark.parametrize(
    "land,expect",
    [
        (0.4, {"output.chamfer": 0.2, "teeth.clearance": None}),  # the clearance is enough
        (0.3, {"output.chamfer": 0.2, "teeth.clearance": 0.05, "teeth.addendum": None}),  # tip land short
    ],
)
def test_a_printed_module_1_pair_gets_the_chamfer_then_the_clearance_then_a_shorter_addendum(land, expect):
    params = profile("elliptic_focus", {"process.kind": "fdm"})
    m, tol = 1.0, params.output.tolerance
    picks = tip_choices(params, _draft(params, m, land))
    # FDM's defaults: each edge +0.1 and the elephant foot 0.2, the centres 0.2 closer
    lack = _lack(m, tol, 0.3, 0.2) - 2 * 0.2  # the chamfer takes the foot off
    clearance = min(math.ceil(lack / 2 * 1000 - 1e-6) / 1000, round((land - 0.2 * m) / 2, 3))
    assert picks["output.chamfer"] == pytest.approx(0.2)
    assert picks["teeth.clearance"] == pytest.approx(clearance, abs=1e-9)
    if "teeth.addendum" in expect:
        addendum = math.floor((1 - (lack - 2 * clearance) / m) * 1000 + 1e-6) / 1000
        assert picks["teeth.addendum"] == pytest.approx(addendum, abs=1e-9) and addendum < 1
    else:
        assert "teeth.addendum" not in picks
    chosen = params.model_copy(
        update={
            "output": params.output.model_copy(update={"chamfer": picks["output.chamfer"]}),
            "teeth": params.teeth.model_copy(
                update={"clearance": picks["teeth.clearance"], "addendum": picks.get("teeth.addendum", 1.0)}
            ),
        }
    )
    from gearcad.fitting.fit import made

    assert radial_room(made(chosen), m) >= 5 * tol + 0.03 * m - 1e-9  # and the room is then there


def test_keys_the_profile_sets_are_kept_and_a_laser_needs_none():
    """The herringbone sets its chamfer (0.3) and clearance (0.02): only the addendum is left to
    choose, shorter by what the tips lack over the normal module; a laser's kerf variation and
    ±0.1 mm of centres leave module-1 tips room, so nothing is chosen."""
    params = profile("herringbone_elliptic", {"process.kind": "fdm"})
    mn, beta, tol = 1.0, math.radians(25), params.output.tolerance
    picks = tip_choices(params, _draft(params, mn / math.cos(beta), 0.4))
    assert set(picks) == {"teeth.addendum"}
    lack = _lack(mn, tol, 0.1, 0.2) - 2 * 0.02  # chamfer 0.3 ≥ the foot: each edge +0.1
    assert picks["teeth.addendum"] == pytest.approx(math.floor((1 - lack / mn) * 1000 + 1e-6) / 1000, abs=1e-9)
    laser = profile("elliptic_focus", {"process.kind": "laser"})
    assert tip_choices(laser, _draft(laser, 1.0, 0.4)) == {}
