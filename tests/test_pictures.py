"""Every picture a build draws, audited as it was drawn (``gearcad.export.charts.png``): titles
inside the canvas, legends clear of the data; and the audit itself can fail."""

import json

import numpy as np

from gearcad.export.charts.png import layout_problems, subplots


def test_every_chart_of_every_profile_has_its_titles_and_legends_in_place(built):
    audited = [json.loads(line) for line in (built.parent / "chart_audit.jsonl").read_text().splitlines()]
    charts = {f"{p.parent.name}/{p.name}" for p in built.glob("*/*.png")}
    assert {a["file"] for a in audited} == charts  # every picture was audited
    assert {a["file"]: a["problems"] for a in audited if a["problems"]} == {}


def test_the_audit_finds_a_cut_title_and_a_legend_over_data():
    fig, ax = subplots(figsize=(3, 2))
    x = np.linspace(0, 1, 200)
    ax.plot(x, np.ones_like(x), label="flat line under the legend")
    ax.legend(loc="center")
    fig.suptitle("a title far too long for so small a figure, cut at both of its ends by the canvas")
    fig.canvas.draw()
    problems = layout_problems(fig)
    assert any("runs off the canvas" in p for p in problems)
    assert any("covers" in p for p in problems)
    assert sum("has no unit" in p for p in problems) == 2  # neither axis is labelled
    fig, ax = subplots(figsize=(6, 3))
    ax.plot(x, x, label="rising")
    ax.set_xlabel("length")  # a quantity without its unit
    fig.canvas.draw()
    assert layout_problems(fig) == ["x axis of '' has no unit ('length')", "y axis of '' has no unit ('')"]
    ax.set_xlabel("length, mm")
    ax.set_ylabel("a / R")  # a ratio
    ax.legend(loc="lower right")
    fig.suptitle("short")
    fig.canvas.draw()
    assert layout_problems(fig) == []
