"""The papers' numbers beside gearcad's (issue 24, item 17): report.json's ``papers`` block and
``papers.html`` of every built profile that reproduces a seed.  The paper's values must be
seed_tables.json's as printed; gearcad's are checked against closed forms written out here (one
or more rows per seed), not against the code that made them."""

from __future__ import annotations

import hashlib
import json
import math
import re
from html import unescape

import pytest

from gearcad.mechanisms.papers import agrees_as_printed

SEED_OF = {
    "elliptic_focus": "004",
    "elliptic_centre": "004",
    "herringbone_elliptic": "004",  # the same ellipses about their foci, with helical teeth
    "walker": "002",
    "roller_body_m3": "003",
    "rolling_wheel": "000",
    "planetary_external": "001",
    "compound_ring": "001",
}


def _report(built, name: str) -> dict:
    return json.loads((built / name / "report.json").read_text(encoding="utf-8"))


def _rows(block: dict, table: int) -> dict[str, dict]:
    return {r["quantity"]: r for r in block["tables"][table]["rows"]}


def test_profiles_that_reproduce_a_seed_have_the_block_and_the_page_others_not(built):
    for folder in sorted(p for p in built.iterdir() if p.is_dir()):
        report = _report(built, folder.name)
        block = report.get("papers")
        assert (block["seed"] if block else None) == SEED_OF.get(folder.name), folder.name
        assert ("papers.html" in report["files"]) == (block is not None) == (folder / "papers.html").exists()
        if block is None:
            continue
        rows = [r for t in block["tables"] for r in t["rows"]]
        assert block["agree"] + block["differ"] == len(rows) > 0
        for r in rows:  # every row: a difference that is gearcad − paper, a verdict, an erratum where it differs
            assert r["difference"] == pytest.approx(r["gearcad"] - r["paper"], abs=1e-12)
            assert (r["verdict"] == "differs") == (r["erratum"] is not None)
        page = unescape((folder / "papers.html").read_text(encoding="utf-8"))
        assert all(r["quantity"] in page for r in rows)
        assert 'href="papers.html"' in (folder / "index.html").read_text(encoding="utf-8")


def test_seed004_rows_are_the_printed_tables_and_eq8_eq14_corrected(built, seed_tables):
    a, b, c, w1 = 25.0, 15.0, 20.0, 9 * math.pi
    paper = seed_tables["elliptic_gears_004"]
    for name, key in (
        ("elliptic_focus", "table1_focus_pivot"),
        ("elliptic_centre", "table2_centre_pivot_as_published"),
    ):
        block = _report(built, name)["papers"]
        rows = block["tables"][0]["rows"]
        printed = [v for row in paper[key]["rows"] for v in row[1:]]
        assert [r["paper"] for r in rows] == printed
        by = _rows(block, 0)
        phi = math.radians(60)
        if name == "elliptic_focus":  # eq. 8, and eq. 14 with ω1² and its sign
            den = a * a - 2 * a * c * math.cos(phi) + c * c
            omega, eps = w1 * b * b / den, -2 * a * c * b * b * w1**2 * math.sin(phi) / den**2
        else:  # Table 2: ω1·r1/(a + b − r1) for the ellipse about its centre, ε by a central difference
            r1 = lambda p: a * b / math.sqrt((b * math.cos(p)) ** 2 + (a * math.sin(p)) ** 2)  # noqa: E731
            w2 = lambda p: w1 * r1(p) / (a + b - r1(p))  # noqa: E731
            omega, h = w2(phi), 1e-6
            eps = (w2(phi + h) - w2(phi - h)) / (2 * h) * w1
        assert by["ω2/π at φ = 60°, rad/s"]["gearcad"] == pytest.approx(omega / math.pi, rel=1e-9)
        assert by["ε2/π² at φ = 60°, rad/s²"]["gearcad"] == pytest.approx(eps / math.pi**2, rel=1e-6)
    focus = _rows(_report(built, "elliptic_focus")["papers"], 0)
    assert focus["ω2/π at φ = 150°, rad/s"]["verdict"] == "differs"  # the erratum: 1.08 for 1.0708
    assert focus["ω2/π at φ = 90°, rad/s"]["verdict"] == "agrees"  # 1.97 truncates 1.9756
    stated = _rows(_report(built, "elliptic_focus")["papers"], 1)["max/min of ω2, type 1"]
    assert stated["paper"] == paper["stated"]["max_over_min_type1"]
    assert stated["gearcad"] == pytest.approx(((a + c) / (a - c)) ** 2, rel=1e-9)


def test_seed002_rows_are_table1_and_the_rolling_i(built, seed_tables):
    paper = seed_tables["wheel_walker_002"]
    block = _report(built, "walker")["papers"]
    L, a, b, c = (paper["data_mm"][k] for k in ("L", "a", "b", "c"))
    K = a - b + c
    i_rows = block["tables"][0]["rows"]
    assert {r["paper"] for r in i_rows} == {paper["i_published"]}
    assert i_rows[0]["verdict"] == "agrees"
    assert i_rows[1]["gearcad"] == pytest.approx(2 * math.pi / (math.pi / 2 + 3 * b / K), rel=1e-12)
    assert i_rows[1]["verdict"] == "differs"
    table = block["tables"][1]["rows"]
    assert [r["paper"] for r in table] == [v for row in paper["table1"]["rows"] for v in (row[1], row[3])]
    i = paper["i_published"]
    u = K + 3 * b * math.cos(2 * math.radians(-45))  # eq. 10 at φ = −45°
    assert table[0]["gearcad"] == pytest.approx(L * i * u / (K + i * u), abs=5e-6)
    assert all(r["verdict"] == "agrees" for r in table)


def test_seed003_rows_are_the_by_eye_limits_and_the_example(built, seed_tables):
    paper = seed_tables["roller_bodies_003"]
    block = _report(built, "roller_body_m3")["papers"]
    limits = block["tables"][0]["rows"]
    assert [r["paper"] for r in limits] == [row[1] for row in paper["largest_oval_amplitude_by_eye"]["rows"]]
    assert limits[0]["gearcad"] == pytest.approx(2 / (9 * math.sqrt(3)), rel=1e-6)  # exact, vertical, m = 3
    assert limits[0]["verdict"] == "differs"
    ex = paper["example"]
    example = _rows(block, 2)
    w, m, amp = 3 * math.pi, ex["m"], ex["a_m"]
    assert example["centre Vmax, m/s"]["paper"] == ex["Vmax_m_s"]
    assert example["centre Vmax, m/s"]["gearcad"] == pytest.approx(amp * m * w, rel=1e-9)
    assert example["centre Amax, m/s²"]["gearcad"] == pytest.approx(amp * w * w * (m * m + 1), rel=1e-9)
    assert [example[k]["verdict"] for k in ("centre Vmax, m/s", "centre Amax, m/s²")] == ["agrees", "differs"]


def test_seed000_and_001_rows_against_the_closed_forms(built):
    drive = _report(built, "rolling_wheel")["drive"]
    rows = _report(built, "rolling_wheel")["papers"]["tables"][0]["rows"]
    L, H, R, r = drive["L"], drive["H"], drive["R"], drive["r"]
    assert rows[0]["paper"] == pytest.approx(math.sqrt(L * L + H * H + (R - r) ** 2), rel=1e-12)  # eq. 2 as printed
    assert rows[0]["gearcad"] == pytest.approx(math.sqrt(L * L + H * H - (R - r) ** 2), rel=1e-12)  # from eq. 1
    assert rows[0]["verdict"] == "differs"
    ring = _report(built, "compound_ring")
    (row,) = ring["papers"]["tables"][0]["rows"]
    r1, r3 = (g["pitch_radius"] for g in ring["gears"] if g["name"] in ("gear1", "gear3"))
    c = ring["compound"]
    w1, w = ring["train"]["gear1_rpm"], ring["train"]["carrier_rpm"]
    assert row["paper"] == pytest.approx(-(w1 * r1 + w * r1 + w * r3) / r3, rel=1e-12)  # the seed's formula
    assert row["gearcad"] == pytest.approx(-(w1 + w) * r1 * c["r2_inner"] / (c["r2_outer"] * r3) - w, rel=1e-12)
    assert row["verdict"] == "differs"


def test_printed_precision_rule():
    assert agrees_as_printed(1.9756, 1.97) and agrees_as_printed(1.9756, 1.98)  # truncated or rounded
    assert not agrees_as_printed(1.0708, 1.08) and agrees_as_printed(81.0, 81)
    assert not agrees_as_printed(-113.51041, -113.43)


def test_index_thumbnails_are_pictures_of_the_parts_and_differ(built):
    index = (built / "index.html").read_text(encoding="utf-8")
    thumbs = re.findall(r'<img class="thumb" src="([^"]+)"', index)
    assert len(thumbs) == len([p for p in built.iterdir() if p.is_dir()])
    assert all(t.endswith((".gif", ".svg")) for t in thumbs), thumbs  # no chart
    digests = {hashlib.sha256((built / t).read_bytes()).hexdigest() for t in thumbs}
    assert len(digests) == len(thumbs)  # every row its own picture
    assert "roller_body_m3/assembly.svg" in thumbs  # the roller body shows its body, not its limits chart


def test_the_pages_output_table_gives_units(built):
    page = (built / "roller_body_m3" / "index.html").read_text(encoding="utf-8")
    table = dict(re.findall(r"<tr><th>([^<]+)</th><td>([^<]+)</td></tr>", page.split("<h3>Output</h3>")[1]))
    assert table["thickness"] == "8 mm" and table["bore"] == "8 mm" and table["pilot hole"] == "1 mm"
    assert table["cutting sheet"] == "600 × 400 mm" and table["print bed"] == "250 × 210 mm"
