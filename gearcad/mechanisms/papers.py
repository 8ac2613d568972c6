"""The papers' numbers beside gearcad's: report.json's ``papers`` block of a profile that
reproduces a seed (its tables, stated numbers and claims, and the errata), drawn as ``papers.html``.

The papers' values are read from ``gearcad/data/seed_tables.json`` (as printed, not corrected);
gearcad's are computed here from the profile's own geometry with the numerical cores, at the
paper's data (seed 004's tables at ω1 = 9π rad/s).  A row agrees when the printed value is
gearcad's rounded or truncated to the printed digits (the papers do both); otherwise it differs,
and names the erratum where docs/papers.md explains it.
"""

from __future__ import annotations

import json
import math
from functools import cache
from importlib.resources import files

import numpy as np

from ..bodies import claims as C
from ..pitch import shapes
from ..pitch import walker as W
from ..pitch.kinematics import kinematics
from ..pitch.pair import conjugate_pair
from ..profiles import EllipseParams, WalkerParams

__all__ = [
    "seed_tables",
    "gear_pair_papers",
    "roller_body_papers",
    "rolling_wheel_papers",
    "carrier_train_papers",
    "printed_digits",
    "agrees_as_printed",
]

SEEDS = {
    "004": "Gorbach & Yarovenko: elliptic gears (Meshchersky's problem 14.6)",
    "002": "Skoybeda, Komyak, Zhukovets: the wheel-walker drive",
    "003": "Gogolin, Kobylyansky et al.: bodies rolling on three rollers",
    "000": "Kovalevsky & Vikhrenko: a wheel driven through an inclined rack",
    "001": "gear trains on a carrier, the method of stopping",
}
CITATIONS = {
    "004": "N. I. Gorbach, D. V. Yarovenko, «Кинематика зубчатых передач с некруглыми колесами» (Kinematics of "
    "gear drives with noncircular wheels), on problem 14.6 of I. V. Meshchersky's «Сборник задач по теоретической "
    "механике» (Moscow: Nauka, 1981)",
    "002": "A. T. Skoybeda, I. M. Komyak, V. N. Zhukovets, «Применение некруглых зубчатых колес в приводе "
    "колесно-шагающего движителя» (Noncircular gears in the drive of a wheel-walking mover), Belarusian National "
    "Technical University, Minsk",
    "003": "V. A. Gogolin, M. T. Kobylyansky, V. F. Gorbunov, D. M. Kobylyansky, «Геометрия и кинематика тел при "
    "движении по роликам» (Geometry and kinematics of bodies moving on rollers)",
    "000": "A. S. Kovalevsky (student), V. S. Vikhrenko (supervisor), «Кинематика привода катящегося колеса» "
    "(Kinematics of the drive of a rolling wheel), Belarusian State Technological University, department of "
    "mechanics and design",
    "001": "a lecture on the method of stopping: three gears on a crank (a transcript; no author or title given)",
}
"""Each seed's paper as a reader cites it: authors, title as printed (with a translation) and
where it comes from, as the seed's own first lines give them."""

_ERRATA_004 = {
    ("table1", 150, 1): "Table 1 prints 1.08; eq. 8 gives 1.0708",
    ("table1", 210, 1): "Table 1 prints 1.08; eq. 8 gives 1.0708",
    **{("table2", phi, 2): "Table 2 prints ∓113.43; eq. 20 gives ∓113.51" for phi in (15, 165, 195, 345)},
}


@cache
def seed_tables() -> dict:
    """The papers' tables exactly as printed (package data ``gearcad/data/seed_tables.json``)."""
    return json.loads(files("gearcad").joinpath("data/seed_tables.json").read_text(encoding="utf-8"))


def printed_digits(printed: float) -> int:
    """How many decimals a printed value carries (1.08 → 2, 81 → 0)."""
    text = repr(float(printed))
    return 0 if text.endswith(".0") else len(text.split(".")[1])


def agrees_as_printed(value: float, printed: float) -> bool:
    """True if ``printed`` is ``value`` rounded or truncated to the printed digits."""
    scale = 10.0 ** printed_digits(printed)
    return any(math.isclose(printed, f(value * scale) / scale, abs_tol=1e-9) for f in (lambda x: round(x), math.trunc))


def _row(quantity: str, paper: float, gearcad: float, erratum: str | None = None, *, exact=None) -> dict:
    """One compared number; ``exact`` overrides the printed-precision rule (a tolerance)."""
    ok = agrees_as_printed(gearcad, paper) if exact is None else abs(gearcad - paper) <= exact
    return {
        "quantity": quantity,
        "paper": paper,
        "gearcad": float(gearcad),
        "difference": float(gearcad) - paper,
        "verdict": "agrees" if ok else "differs",
        "erratum": None if ok else (erratum or "not explained: see docs/papers.md"),
    }


def _claims(entries) -> list[dict]:
    """Claims the mechanism checked (its report's checks), as the page lists them."""
    return [
        {"claim": c.get("claim", ""), "holds": bool(c.get("holds")), "message": c.get("message", "")}
        for c in entries
        if isinstance(c, dict) and "holds" in c
    ]


def _seed004(params, data: dict) -> dict | None:
    g = params.gear1
    paper = seed_tables()["elliptic_gears_004"]
    if not (isinstance(g, EllipseParams) and (g.a, g.b) == (paper["data"]["a_cm"], paper["data"]["b_cm"])):
        return None
    omega1 = 9 * math.pi  # the tables' ω1, whatever the profile's speed
    if g.pivot == "focus":
        key, label, pair = "table1_focus_pivot", "table1", conjugate_pair(shapes.ellipse_focus(g.a, g.b), mate_lobes=1)
        title = "Table 1: type 1, pivots at the foci, E = 2a"
        stated = ("max/min of ω2, type 1", paper["stated"]["max_over_min_type1"])
    else:
        key, label = "table2_centre_pivot_as_published", "table2"
        pair = conjugate_pair(shapes.ellipse_centre(g.a, g.b), mate_lobes=2, center_distance=g.a + g.b)
        title = "Table 2: type 2 as the paper builds it, identical ellipses at E = a + b (which does not roll)"
        stated = ("max/min of ω2, type 2 (the paper's construction)", paper["stated"]["max_over_min_type2"])
    rows_in = paper[key]["rows"]
    kin = kinematics(pair, speed=omega1, angle=np.radians([r[0] for r in rows_in]))
    rows = []
    for (phi, w_paper, e_paper), w, e in zip(rows_in, kin.speed / math.pi, kin.acceleration / math.pi**2):
        rows.append(_row(f"ω2/π at φ = {phi}°, rad/s", w_paper, w, _ERRATA_004.get((label, phi, 1))))
        rows.append(_row(f"ε2/π² at φ = {phi}°, rad/s²", e_paper, e, _ERRATA_004.get((label, phi, 2))))
    whole = kinematics(pair)
    ratio = float(whole.ratio.max() / whole.ratio.min())
    tables = [
        {"name": title, "rows": rows},
        {"name": "Stated in the text", "rows": [_row(stated[0], stated[1], ratio)]},
    ]
    claim = data.get("claim")  # the type-2 claim: identical ellipses roll at a + b
    claims = _claims([{**claim, "claim": claim["source"], "message": _claim_message(claim)}] if claim else [])
    return _block("004", tables, claims + _claims(data.get("paper_claims", [])))


def _claim_message(claim: dict) -> str:
    if claim["holds"]:
        return "the mate closes at the stated centre distance"
    return (
        f"at E = {claim['center_distance']:g} mm the mate turns {math.degrees(claim['mate_turn']):.2f}° per turn "
        f"({math.degrees(claim['shortfall']):.2f}° short); an identical ellipse misses the contact by "
        f"{claim['shape_difference']:.3g} mm"
    )


def _seed002(params, data: dict) -> dict | None:
    g = params.gear1
    paper = seed_tables()["wheel_walker_002"]
    d = paper["data_mm"]
    if not isinstance(g, WalkerParams) or (params.center_distance, g.a, g.b, g.c) != (d["L"], d["a"], d["b"], d["c"]):
        return None
    geometry = W.WalkerGeometry(L=d["L"], a=d["a"], b=d["b"], c=d["c"])
    walker = data.get("walker", {})
    i_paper = walker.get("i_paper") or W.paper_ratio_constant(geometry)[0]
    rows = [_row("i, by the paper's method (eq. 15, trapezoid 0.1°/0.4°)", paper["i_published"], i_paper)]
    if "i" in walker:
        rows.append(
            _row(
                "i of the pair that rolls and closes 4:1",
                paper["i_published"],
                walker["i"],
                "the paper's pinion (θ = 4φ) does not roll on its wheel; rolling needs i = 2π/(π/2 + 3b/K)",
            )
        )
    table = []
    for phi, r_h, theta, r in paper["table1"]["rows"]:
        table.append(_row(f"r_H at φ = {phi}°, mm", r_h, W.paper_wheel_radius(math.radians(phi), i_paper, geometry)))
        table.append(_row(f"r at θ = {theta}°, mm", r, W.paper_pinion_radius(math.radians(theta), i_paper, geometry)))
    tables = [
        {"name": "The ratio constant i", "rows": rows},
        {"name": "Table 1: eqs. 10 and 12 with the published i", "rows": table},
    ]
    claims = []
    if "paper_table_offset" in walker:
        claims.append(
            {
                "claim": "the pitch curves of Table 1 roll without slip",
                "holds": False,
                "message": f"with θ = 4φ the pinion slides by up to {walker['paper_slip']:.3g} mm per rad; the pair "
                f"that rolls differs from Table 1 by up to {walker['paper_table_offset']:.3g} mm",
            }
        )
    return _block("002", tables, claims)


def _seed003(params, data: dict) -> dict | None:
    paper = seed_tables()["roller_bodies_003"]
    limits = data.get("limits")
    if not limits:
        return None
    exact = dict(zip(limits["m"], limits["convex"]))
    by_eye = paper["largest_oval_amplitude_by_eye"]["rows"]
    note = "judged by eye; the exact convex limit is lower (the paper's shapes there have concave stretches)"
    rows = [  # values judged by eye, printed to one digit: agreeing means within 5 %
        _row(f"largest 'oval' amplitude a/R, m = {m}", a, exact[m], note, exact=0.05 * a)
        for m, a in by_eye
        if m in exact
    ]
    coefficient, exponent, r2 = C.power_law_fit([r[0] for r in by_eye], [r[1] for r in by_eye])
    fit = [
        _row("eq. 4 coefficient (fit of the by-eye values)", C.EQ4["coefficient"], coefficient),
        _row("eq. 4 exponent", C.EQ4["exponent"], exponent),
        _row("eq. 4 R²", C.EQ4["r2"], r2),
    ]
    tables = [
        {"name": f"Largest convex amplitude ({params.direction}, r = {params.roller_radius:g} R)", "rows": rows},
        {"name": "Eq. 4 from the by-eye values", "rows": fit},
    ]
    ex, centre = paper["example"], data.get("centre", {})
    body = params.body
    same = body.m == ex["m"] and math.isclose(body.amplitude * body.scale, ex["a_m"] * 1000)
    if same and centre and math.isclose(centre.get("w", 0.0), 3 * math.pi):
        a, m = ex["a_m"], ex["m"]
        coarse = (
            f"to one digit {centre['a_max'] / 1000:.3g} m/s² is {centre['a_max'] / 1000:.0f}; the printed value is "
            f"a·w²(m² + 1) with w = 3π taken as 10 s⁻¹: {a:g}·10²·{m * m + 1} = {a * 100 * (m * m + 1):g}"
        )
        example = [
            _row("centre Vmax, m/s", ex["Vmax_m_s"], centre["v_max"] / 1000, "a·m·w, printed to one digit"),
            _row("centre Amax, m/s²", ex["Amax_m_s2"], centre["a_max"] / 1000, coarse),
        ]
        tables.append({"name": "The example: w = 3π s⁻¹, m = 3, a = 0.01 m", "rows": example})
    return _block("003", tables, _claims(data.get("paper_checks", [])))


def _seed000(params, data: dict) -> dict | None:
    geometry = data.get("geometry", {})
    if "rack_length_paper_eq2" not in geometry:
        return None
    erratum = "eq. 2 prints + (R − r)²; eq. 1 gives l² = L² + H² − (R − r)²"
    rows = [
        _row("rack length l at the start, eq. 2 as printed, mm", geometry["rack_length_paper_eq2"],
             geometry["rack_length_start"], erratum, exact=1e-6),
        _row("rack inclination β at the start, eq. 10, rad", geometry["beta_paper_eq10"], geometry["beta_start"],
             "eq. 10 gives the other common tangent here", exact=1e-9),
    ]  # fmt: skip
    checks = data.get("checks", {})
    return _block("000", [{"name": "Eqs. 2 and 10 against the closed contour", "rows": rows}],
                  _claims(checks.values()))  # fmt: skip


def _seed001(params, data: dict) -> dict | None:
    compound = data.get("compound")
    gears = data.get("gears", [])
    rows = []
    if compound:
        rows.append(
            _row("ω3 by the seed's formula (one radius for gear 2), rpm", compound["omega3_seed_formula_rpm"],
                 compound["omega3_rpm"], "the seed's formula takes one radius for both toothings of the ring",
                 exact=1e-9)
        )  # fmt: skip
    elif len(gears) == 3 and not any(g["internal_teeth"] for g in gears) and "train" in data:
        r1, r3 = gears[0]["pitch_radius"], gears[2]["pitch_radius"]
        w1, w = data["train"]["gear1_rpm"], data["train"]["carrier_rpm"]
        formula = w1 * r1 / r3 + w * (r1 - r3) / r3
        rows.append(_row("ω3 = ω1·r1/r3 + ω·(r1 − r3)/r3, rpm", formula, gears[2]["omega_rpm"], exact=1e-9))
    if not rows:
        return None
    return _block("001", [{"name": "The method of stopping", "rows": rows}], [])


def _block(seed: str, tables: list[dict], claims: list[dict]) -> dict:
    rows = [r for t in tables for r in t["rows"]]
    return {
        "seed": seed,
        "paper": SEEDS[seed],
        "source": CITATIONS[seed],
        "page": "papers.html",
        "agree": sum(r["verdict"] == "agrees" for r in rows),
        "differ": sum(r["verdict"] == "differs" for r in rows),
        "tables": tables,
        "claims": [c for c in claims if c["claim"]],
    }


def gear_pair_papers(params, data: dict) -> dict | None:
    """A gear pair's ``papers`` block: seed 004's elliptic pair, else seed 002's walker."""
    return _seed004(params, data) or _seed002(params, data)


def roller_body_papers(params, data: dict) -> dict | None:
    """A roller body's ``papers`` block (seed 003)."""
    return _seed003(params, data)


def rolling_wheel_papers(params, data: dict) -> dict | None:
    """A rolling wheel's ``papers`` block (seed 000)."""
    return _seed000(params, data)


def carrier_train_papers(params, data: dict) -> dict | None:
    """A carrier train's ``papers`` block (seed 001, the method of stopping)."""
    return _seed001(params, data)
