"""sweep.html: every in-page link resolves (to a listed row, and only those), the ticks place
every dot at its values, the axes and columns carry their units, the constraints are shown with
how many designs meet them, the markers differ in shape and lightness (they read in greyscale),
the build commands build the rows, and in a real browser nothing runs off the right edge."""

import re
import shlex
import subprocess
from html import unescape
from pathlib import Path

import numpy as np
import pytest

import gearcad
from gearcad.sweeps import write_sweep
from gearcad.sweeps.front import RunningFront, parse_constraint, row_values
from gearcad.sweeps.page import MAX_DOTS, MAX_ROWS, nice_ticks, sweep_page, unit

from .conftest import ROOT
from .test_html import CHROMIUM, check_page

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    """A pitch-stage sweep (50 designs in milliseconds each) with a trade-off: a larger ratio
    against a larger smallest radius, and a constraint that some designs miss."""
    table = gearcad.sweep(
        FOCUS,
        ["gear1.eccentricity=0.1:0.9:25", "gear1.a=20,30"],
        stage="pitch",
        maximise=["pair.ratio_max", "gears.0.r_min"],
        constraints=["gears.0.r_min >= 4.5"],
        workers=1,
    )
    out = tmp_path_factory.mktemp("sweep")
    files = write_sweep(table, out)
    return table, files["sweep.html"]


def _listed(text: str) -> list[int]:
    return [int(n) for n in re.findall(r'<tr id="row-(\d+)">', text)]


def test_links_resolve_to_listed_rows_only(swept):
    table, page = swept
    checker = check_page(page)  # well formed, nothing fetched, every in-page link to an id in the page
    text = page.read_text(encoding="utf-8")
    linked = [int(n) for n in re.findall(r'href="#row-(\d+)"', text)]
    front = table.loc[table["pareto"], "index"].tolist()
    assert sorted(linked) == sorted(_listed(text)) == sorted(front) and len(front) >= 10
    assert {f"row-{n}" for n in linked} <= checker.ids
    # every dot is drawn: 50 made designs, one marker each
    assert len(re.findall(r"<g><title>#\d+:", text)) == 50


def _svg_points(text: str):
    """(tick labels with their pixel positions on each axis, dots: title values and pixel centre)."""
    svg = text[text.index('<svg class="chart"') : text.index("</svg>")]
    xt = [
        (float(v), float(x)) for x, v in re.findall(r'<text x="([\d.]+)" y="\d+" text-anchor="middle">([-\d.]+)<', svg)
    ]
    yt = [
        (float(v), float(y) - 4) for y, v in re.findall(r'<text x="\d+" y="([\d.]+)" text-anchor="end">([-\d.]+)<', svg)
    ]
    dots = []
    for title, mark in re.findall(r"<g><title>([^<]*)</title>(<[^>]*>)</g>", svg):
        values = [float(v) for v in re.findall(r"= ([-\d.e+]+)", unescape(title))]
        if mark.startswith("<circle"):
            cx, cy = (float(v) for v in re.search(r'cx="([\d.]+)" cy="([\d.]+)"', mark).groups())
        else:
            mx, my = (float(v) for v in re.search(r'd="M([\d.]+) ([\d.]+)', mark).groups())
            cx, cy = (mx, my + 6) if "z" in mark else (mx + 3, my + 3)
        dots.append((values, (cx, cy), mark))
    return xt, yt, dots


def test_ticks_place_every_dot_at_its_values(swept):
    """The tick labels, read as a reader reads them (a straight line through label against
    position), put every dot where its tooltip's values say, to 0.15 px (the file's rounding)."""
    table, page = swept
    xt, yt, dots = _svg_points(page.read_text(encoding="utf-8"))
    assert len(xt) >= 4 and len(yt) >= 4
    for ticks in (xt, yt):
        values = [v for v, _ in ticks]
        steps = np.diff(values)
        assert np.allclose(steps, steps[0]) and steps[0] > 0  # evenly spaced, rising
        assert f"{steps[0]:.0e}"[0] in "125"  # 1, 2 or 5 × 10ᵏ apart
    fx = np.polyfit([v for v, _ in xt], [p for _, p in xt], 1)
    fy = np.polyfit([v for v, _ in yt], [p for _, p in yt], 1)
    assert fy[0] < 0  # up is larger
    for (x, y), (cx, cy), _ in dots:
        assert abs(np.polyval(fx, x) - cx) < 0.15 and abs(np.polyval(fy, y) - cy) < 0.15
    # every row's values are the table's
    made = table[table["refusal"].isna()]

    def ordered(pairs):
        return sorted(pairs, key=lambda p: (round(p[0], 3), round(p[1], 3)))

    pairs = ordered(zip(made["pair.ratio_max"], made["gears.0.r_min"]))
    assert np.allclose(ordered(tuple(xy) for xy, _, _ in dots), pairs, rtol=1e-5)  # the tooltips' 6 digits


def test_units_on_axes_columns_and_constraints(swept):
    table, page = swept
    text = unescape(re.sub(r"<wbr>", "", page.read_text(encoding="utf-8")))
    assert "pair.ratio_max (ω₂/ω₁) — maximised" in text and "gears.0.r_min (mm) — maximised" in text
    assert "<th>set.gear1.a (mm)</th>" in text and "<th>set.gear1.eccentricity</th>" in text
    # the constraint with its unit, how many made designs meet it (counted here), and its column
    met = int((table["gears.0.r_min"] >= 4.5).sum())
    assert f"gears.0.r_min >= 4.5 mm</code>: met by {met} of 50 made designs" in text and 0 < met < 50
    assert int(table["feasible"].sum()) == met


@pytest.mark.parametrize(
    ("key", "expected"),
    [
        ("pair.center_distance", "mm"),  # docs/files.md: `pair` center_distance, mm
        ("set.pair.center_distance", "mm"),
        ("gears.0.teeth.min_tip_thickness", "mm"),
        ("gears.1.teeth.area", "mm²"),
        ("assembly.overlap", "mm²"),
        ("pair.closure_error", "rad"),
        ("pair.slip_residual", "mm/rad"),
        ("pair.ratio_max", "ω₂/ω₁"),
        ("kinematics.follower_speed_max", "rad/s"),
        ("kinematics.follower_acceleration_min", "rad/s²"),
        ("set.teeth.pressure_angle_deg", "°"),
        ("set.pair.driver_rpm", "rev/min"),
        ("set.teeth.profile_shift", "× module"),
        ("set.body.amplitude", "× R"),  # a roller body's lengths are in units of R
        ("set.body.scale", "mm"),
        ("set.gear1.eccentricity", ""),
        ("set.teeth.count", ""),
        ("gears.0.lobes", ""),
    ],
)
def test_unit(key, expected):
    assert unit(key) == expected


def test_markers_differ_in_shape_and_in_grey():
    """Front: a filled diamond, dark; feasible: a hollow circle; outside the constraints: a
    cross, light.  Their greys (Rec. 709 luma of fill or stroke) are far apart."""
    import pandas as pd

    table = pd.DataFrame(
        {"index": [0, 1, 2], "refusal": [None] * 3, "feasible": [True, True, False], "pareto": [True, False, False]}
    )
    table["x"], table["y"] = [1.0, 2.0, 3.0], [3.0, 1.0, 2.0]
    table.attrs.update(minimise=["x", "y"], inputs=[], constraints=[])
    text = sweep_page(table)
    css = dict(re.findall(r"\.(front|ok|out)\{\{?([^}]*)\}", text))

    def grey(rule: str, prop: str) -> float:
        colour = re.search(rf"{prop}:#([0-9a-f]{{3,6}})", rule).group(1)
        colour = "".join(c * 2 for c in colour) if len(colour) == 3 else colour
        r, g, b = (int(colour[i : i + 2], 16) / 255 for i in (0, 2, 4))
        return 0.2126 * r + 0.7152 * g + 0.0722 * b

    assert grey(css["front"], "fill") < 0.15 and grey(css["ok"], "fill") > 0.95
    assert 0.2 < grey(css["ok"], "stroke") < 0.5 < 0.6 < grey(css["out"], "stroke")
    svg = text[text.index('<svg class="chart"') :]
    assert re.search(r'<path class="front" d="M[^"]*z"', svg)  # closed: filled
    assert re.search(r'<circle class="ok"', svg) and re.search(r'<path class="out" d="M[^"z]*"', svg)


def test_build_commands_build_their_rows(swept):
    table, page = swept
    text = unescape(page.read_text(encoding="utf-8"))
    commands = re.findall(r"<code>(gearcad build [^<]*)</code>", text)
    front = table[table["pareto"]].sort_values("pair.ratio_max", kind="stable")
    assert len(commands) == len(front)
    for command, (_, row) in zip(commands, front.iterrows()):
        words = shlex.split(command)
        assert words[:3] == ["gearcad", "build", str(FOCUS)]
        sets = dict(w.split("=", 1) for w in words[4::2])
        assert words[3::2] == ["--set"] * len(sets)
        assert float(sets["gear1.eccentricity"]) == row["set.gear1.eccentricity"]
        assert float(sets["gear1.a"]) == row["set.gear1.a"]


def test_a_large_sweep_draws_and_lists_at_most_its_caps():
    """12 000 rows (600 refused, a front of 700 on a line): at most MAX_DOTS markers, the front
    drawn whole, MAX_ROWS rows listed and linked, no link to a refused or unlisted row."""
    import pandas as pd

    rng = np.random.default_rng(5)
    n = 12_000
    x = rng.random(n)
    y = rng.random(n) + 1
    y[:700] = 1 - x[:700]  # these 700 dominate every other row
    refused = np.zeros(n, dtype=bool)
    refused[rng.choice(np.arange(700, n), 600, replace=False)] = True
    x[refused], y[refused] = np.nan, np.nan
    front = RunningFront(2)
    for chunk in np.array_split(np.arange(n), 7):
        front.add(chunk, np.column_stack([x[chunk], y[chunk]]))
    pareto = np.zeros(n, dtype=bool)
    pareto[front.rows()] = True
    table = pd.DataFrame(
        {
            "index": np.arange(n),
            "set.k": np.arange(n),
            "feasible": ~refused,
            "pareto": pareto,
            "refusal": np.where(refused, "refused here", None),
            "x": x,
            "y": y,
        }
    )
    table.attrs.update(minimise=["x", "y"], inputs=["set.k"], constraints=[], profile="p.toml")
    text = sweep_page(table)
    assert pareto.sum() == 700
    markers = re.findall(r'<(?:path|circle) class="(front|ok|out)"', text)
    assert len(markers) == MAX_DOTS and markers.count("front") == 700
    listed, linked = _listed(text), [int(v) for v in re.findall(r'href="#row-(\d+)"', text)]
    assert len(listed) == MAX_ROWS and sorted(linked) == sorted(listed) and set(listed) <= set(np.flatnonzero(pareto))
    assert f"{n - 600 - MAX_DOTS} of the {n - 600} designs with both values are not drawn" in text
    assert "600 designs (refused, or without a value of either axis) have no point" in text
    assert "600 × refused here" in text


def test_nice_ticks():
    assert nice_ticks(0.93, 4.07)[:3] == (0.0, 5.0, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0])  # 3.14 / 6 → steps of 1
    assert nice_ticks(0.93, 3.07)[:3] == (0.5, 3.5, [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5])  # 2.14 / 6 → 0.5
    lo, hi, ticks, decimals = nice_ticks(50.0, 50.0)  # one value: a span about it
    assert lo <= 49.5 and hi >= 50.5 and 50.0 in ticks and decimals == 1
    lo, hi, ticks, decimals = nice_ticks(1e-6, 3e-6)
    assert lo <= 1e-6 and hi >= 3e-6 and len(ticks) <= 7 and decimals == 7


@pytest.mark.skipif(
    not Path(CHROMIUM).is_file(), reason="no chromium: install it with `apt-get install -y chromium` (Debian)"
)
def test_page_in_a_headless_browser(swept, tmp_path):
    """Chromium lays the page out at 800 px: nothing wider than the window (the build
    commands wrap), every link's target is an element of the page as the browser parsed it, and
    the designs are in view (issue 37): the chart starts within the first screen and every
    design's marker lies inside its frame and the window.  A probe script is added to a copy
    (the page itself has none) and its findings read from the DOM chromium dumps."""
    _, page = swept
    probe = """<script>
const w = document.documentElement.clientWidth;
const wide = [...document.querySelectorAll('body *')].filter(e => e.getBoundingClientRect().right > w + 0.5);
const links = [...document.querySelectorAll('a[href^="#"]')];
const missing = links.filter(a => !document.getElementById(a.getAttribute('href').slice(1)));
const frame = document.querySelector('svg.chart rect.frame').getBoundingClientRect();
const marks = [...document.querySelectorAll('svg.chart .front, svg.chart .ok, svg.chart .out')]
  .filter(e => !e.classList.contains('key')).map(e => e.getBoundingClientRect());
const inside = marks.filter(r => r.left >= frame.left - 6 && r.right <= frame.right + 6 && r.top >= frame.top - 6
  && r.bottom <= frame.bottom + 6 && r.left >= 0 && r.right <= w && r.width > 0);
document.body.setAttribute('data-probe', JSON.stringify({width: w, scroll: document.documentElement.scrollWidth,
  wide: wide.map(e => e.tagName + ':' + e.textContent.slice(0, 40)), links: links.length, missing: missing.length,
  screen: window.innerHeight, chart: frame.top, marks: marks.length, inside: inside.length}));
</script></body>"""
    copy = tmp_path / "sweep.html"
    copy.write_text(page.read_text(encoding="utf-8").replace("</body>", probe), encoding="utf-8")
    dom = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}",
            "--window-size=800,900",
            "--dump-dom",
            copy.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=60,
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert dom.returncode == 0, dom.stderr[-2000:]
    import json

    found = json.loads(unescape(re.search(r'data-probe="([^"]*)"', dom.stdout).group(1)))
    assert found["width"] >= 700 and found["scroll"] <= found["width"], found
    assert found["wide"] == [] and found["links"] >= 10 and found["missing"] == 0, found
    # the 50 designs (every one has both values): each drawn, in the frame, the frame on the first screen
    assert found["marks"] == len(swept[0]) == 50 and found["inside"] == 50, found
    assert 0 <= found["chart"] < found["screen"], found


def test_running_front_from_chunk_rows_is_the_tables(swept):
    """The rows as chunks return them (report keys, no inputs), in shuffled chunks, merged by
    :class:`RunningFront` through :func:`row_values`: the table's own front column."""
    table, _ = swept
    rows = table.drop(columns=[c for c in table.columns if c.startswith("set.")]).to_dict("records")
    goals = dict(minimise=[], maximise=list(table.attrs["maximise"]))
    constraints = [parse_constraint(c) for c in table.attrs["constraints"]]
    order = np.random.default_rng(3).permutation(len(rows))
    front = RunningFront(2)
    for chunk in np.array_split(order, 6):
        front.add(*row_values([rows[i] for i in chunk], constraints=constraints, **goals))
    assert front.rows().tolist() == np.flatnonzero(table["pareto"]).tolist()
    # closed form: the ratio (1 + e)/(1 − e) does not depend on a, r_min = a(1 − e) grows with it,
    # so a = 30 beats a = 20 at every e, and along a = 30 a larger ratio costs r_min: the front
    # is the rows of a = 30 that meet r_min = 30(1 − e) >= 4.5, e <= 0.85 — 23 of the 25 — although
    # the two ratios at one e may differ in their last bits (rounding)
    e = table["set.gear1.eccentricity"].to_numpy()
    assert table.loc[table["pareto"], "set.gear1.a"].tolist() == [30] * 23
    assert (
        np.flatnonzero(table["pareto"]).tolist() == np.flatnonzero((table["set.gear1.a"] == 30) & (e <= 0.85)).tolist()
    )
    ratios = table["pair.ratio_max"].to_numpy()
    assert np.any((ratios[0::2] != ratios[1::2]) & np.isclose(ratios[0::2], ratios[1::2], rtol=1e-14, atol=0))
