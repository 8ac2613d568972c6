"""The tolerance budget: every rule derived from output.tolerance, from its closed form."""

import math

import pytest

from gearcad.tolerances import Budget, budget, designed_play

from .conftest import ROOT


def test_budget_rules_from_their_closed_forms():
    b = budget(0.01)
    assert b.fine == pytest.approx(0.01 * 0.25)
    assert b.fit == pytest.approx(0.01 * 0.75)
    # two flanks, each off by the tolerance over the working depth 2.25·m
    assert b.teeth_overlap(2.0) == pytest.approx(2 * 0.01 * 2.25 * 2.0)
    assert b.allowed_overlap(7.0) == pytest.approx(2 * 0.01 * 7.0)
    # the nudge: play + 200·tol, capped at half a module
    assert b.nudge_arc(module=10.0, play=0.1) == pytest.approx(0.1 + 2.0)
    assert b.nudge_arc(module=2.0, play=0.1) == pytest.approx(0.1 + 1.0)
    assert Budget(0.2, fine_fraction=0.5).fine == pytest.approx(0.1)


def test_designed_play():
    alpha = math.radians(20)
    assert designed_play(backlash=0.1, clearance=0.05, pressure_angle=alpha) == pytest.approx(
        0.1 + 0.2 / math.cos(alpha)
    )


def test_tolerance_rules_are_derived_in_one_place():
    """``fine_fraction`` is read, and the overlap and nudge rules typed, only in tolerances.py
    (teeth/pair.py takes a whole Tolerances, whose fine_fraction it hands to a Budget)."""
    allowed = {"tolerances.py", "pair.py"}
    for path in (ROOT / "gearcad").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        if path.name not in allowed:
            assert "fine_fraction" not in text, path
        if path.name != "tolerances.py":
            assert "2.25 * " not in text and "200 * " not in text, path
