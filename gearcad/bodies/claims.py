"""Seed 003's printed formulas and statements, each recomputed (Gogolin, Kobylyansky et al.).

The paper's kinematics section (eqs. 6–11) is written for the horizontal oscillation
f = a·sin mτ, g = 0 at uniform rotation φ = w·t, with α = (m + 1)w, β = (m − 1)w.  Checked here:

* eq. 9, |V| of a body point: holds;
* eq. 10, |A| of a body point: the last bracket (the w²·a·[…] cross term) has the wrong sign;
  the true form is A² = w⁴(x1² + y1²) + a²[α⁴ + β⁴ − 2α²β²cos(α + β)t]/4
  − w²a[x1β²sin(wt + βt) − x1α²sin(wt − αt) + y1β²cos(wt + βt) − y1α²cos(wt − αt)];
* the instants of the centre's largest speed: printed t = πk/(2wm); cos(α + β)t = 1 needs
  t = πk/(wm) — the printed odd k are the instants of the *smallest* speed, a·w;
* the instants of the largest acceleration, t = (2k + 1)π/(2wm): hold;
* the amplitude laws: the regression a = 1.74·m^−2.07 (R² = 0.97) is a log–log least-squares
  fit of the by-eye limits and is reproduced; √3/m² exceeds it by 7.5–20.3 % on m = 3…15 (the
  paper says 12–25 %); and in units of the roller spacing R√3 the law is a1 = a/√3 = 1/m², not
  3/m².  The exact convex limit tends to 1/m² (units of R) for large m;
* "the roller radius does not affect the body's shape" and the amplitude limits against r:
  :mod:`gearcad.bodies.limits`.

Every function takes plain numbers and returns plain numbers, arrays or report-ready dicts.
"""

from __future__ import annotations

import json
import math
from importlib.resources import files

import numpy as np

from . import rollers as RB

__all__ = [
    "PAPER_BY_EYE",
    "PAPER_M",
    "paper_speed_modulus",
    "paper_acceleration_modulus",
    "acceleration_modulus",
    "paper_vmax_instants",
    "vmax_instants",
    "amax_instants",
    "power_law_fit",
    "approximation_gap",
    "paper_a1",
    "a1_from_law",
    "paper_check",
    "kinematics_checks",
    "amplitude_law_checks",
]

PAPER_BY_EYE = {3: 0.15, 6: 0.05, 9: 0.025, 12: 0.01, 15: 0.005}
"""The paper's largest 'oval' amplitudes (units of R), judged by eye."""
PAPER_M = (3, 6, 9, 12, 15)

EQ4: dict[str, float] = next(
    t["eq4"]
    for t in json.loads(files("gearcad").joinpath("data/seed_tables.json").read_text("utf-8")).values()
    if isinstance(t, dict) and "eq4" in t
)
"""The paper's eq. 4 as printed (``gearcad/data/seed_tables.json``): a = coefficient·m^exponent,
fitted with R² = r2 to its by-eye limits."""
TWO_PI = 2 * math.pi


def _angles(m: int, w: float):
    return (m + 1) * w, (m - 1) * w


def paper_speed_modulus(x1, y1, *, a: float, m: int, w: float, t) -> np.ndarray:
    """Eq. 9 exactly as printed: |V| of the body point (x1, y1), horizontal oscillation."""
    al, be = _angles(m, w)
    t = np.asarray(t, dtype=float)
    wt = w * t
    sq = (
        w * w * (x1 * x1 + y1 * y1)
        + a * a * (al**2 + be**2 + 2 * al * be * np.cos((al + be) * t)) / 4
        + a
        * w
        * (
            x1 * be * np.sin(wt + be * t)
            + x1 * al * np.sin(wt - al * t)
            + y1 * be * np.cos(wt + be * t)
            + y1 * al * np.cos(wt - al * t)
        )
    )
    return np.sqrt(sq)


def _acceleration_terms(x1, y1, a, m, w, t):
    al, be = _angles(m, w)
    t = np.asarray(t, dtype=float)
    wt = w * t
    base = w**4 * (x1 * x1 + y1 * y1) + a * a * (al**4 + be**4 - 2 * al**2 * be**2 * np.cos((al + be) * t)) / 4
    cross = (
        w
        * w
        * a
        * (
            x1 * be**2 * np.sin(wt + be * t)
            - x1 * al**2 * np.sin(wt - al * t)
            + y1 * be**2 * np.cos(wt + be * t)
            - y1 * al**2 * np.cos(wt - al * t)
        )
    )
    return base, cross


def paper_acceleration_modulus(x1, y1, *, a: float, m: int, w: float, t) -> np.ndarray:
    """Eq. 10 exactly as printed (its cross term has the wrong sign).  Where the printed
    radicand goes negative the result is NaN."""
    base, cross = _acceleration_terms(x1, y1, a, m, w, t)
    sq = base + cross
    return np.sqrt(np.where(sq >= 0, sq, np.nan))


def acceleration_modulus(x1, y1, *, a: float, m: int, w: float, t) -> np.ndarray:
    """|A| of the body point (x1, y1): eq. 10 with the sign of the w²·a·[…] term corrected."""
    base, cross = _acceleration_terms(x1, y1, a, m, w, t)
    return np.sqrt(base - cross)


def paper_vmax_instants(m: int, w: float, k) -> np.ndarray:
    """The printed instants of the centre's largest speed, t = πk/(2wm)."""
    return math.pi * np.asarray(k, dtype=float) / (2 * w * m)


def vmax_instants(m: int, w: float, k) -> np.ndarray:
    """The instants where cos(α + β)t = 1, i.e. t = πk/(wm) (the centre passes its mean)."""
    return math.pi * np.asarray(k, dtype=float) / (w * m)


def amax_instants(m: int, w: float, k) -> np.ndarray:
    """The instants where cos(α + β)t = −1, t = (2k + 1)π/(2wm) (as printed)."""
    return (2 * np.asarray(k, dtype=float) + 1) * math.pi / (2 * w * m)


def power_law_fit(ms, amplitudes) -> tuple[float, float, float]:
    """a = C·m^p by least squares on log a against log m: (C, p, R² of the log fit).

    This is how the paper's eq. 4 (1.74, −2.07, R² = 0.97) comes out of its by-eye limits.
    """
    x, y = np.log(np.asarray(ms, dtype=float)), np.log(np.asarray(amplitudes, dtype=float))
    p, logc = np.polyfit(x, y, 1)
    residual = y - (logc + p * x)
    r2 = 1 - float(np.sum(residual**2) / np.sum((y - y.mean()) ** 2))
    return float(math.exp(logc)), float(p), r2


def approximation_gap(ms=PAPER_M) -> np.ndarray:
    """How much √3/m² exceeds eq. 4 (1.74·m^−2.07), as a fraction of eq. 4, at each m."""
    m = np.asarray(ms, dtype=float)
    law = EQ4["coefficient"] * m ** EQ4["exponent"]
    return (math.sqrt(3) / m**2 - law) / law


def paper_a1(m) -> np.ndarray:
    """The paper's amplitude law in units of the roller spacing R√3: a1 = 3/m²."""
    return 3.0 / np.asarray(m, dtype=float) ** 2


def a1_from_law(m) -> np.ndarray:
    """√3/m² (units of R) restated in units of R√3: a1 = a/√3 = 1/m²."""
    return math.sqrt(3) / np.asarray(m, dtype=float) ** 2 / math.sqrt(3)


def paper_check(code: str, claim: str, paper, computed, holds: bool, message: str) -> dict:
    """One report entry: the statement, the paper's value, gearcad's, whether it holds, and the
    finding's message (the code to emit when it does not hold)."""
    return {
        "code": code,
        "claim": claim,
        "paper": paper,
        "computed": computed,
        "holds": bool(holds),
        "message": message,
    }


def _printed_gaps(osc, *, a: float, m: int, w: float, radius: float, samples: int):
    """How far printed eqs. 9 and 10 stray from the differentiated motion of the centre and four
    points on the roller circle over one turn, and the largest speed and acceleration."""
    points = [(radius * x, radius * y) for x, y in ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (-0.6, 0.8), (0.8, -0.6))]
    t = np.linspace(0.0, TWO_PI / w, samples)
    gap_v = gap_a = 0.0
    a_scale = v_scale = 0.0
    for x1, y1 in points:
        _, vel, acc = RB.point_motion(osc, x1, y1, w=w, t=t)
        v, acc_true = np.hypot(*vel.T), np.hypot(*acc.T)
        v_scale, a_scale = max(v_scale, float(v.max())), max(a_scale, float(acc_true.max()))
        gap_v = max(gap_v, float(np.max(np.abs(paper_speed_modulus(x1, y1, a=a, m=m, w=w, t=t) - v))))
        printed = paper_acceleration_modulus(x1, y1, a=a, m=m, w=w, t=t)
        gap_a = max(gap_a, float(np.nanmax(np.abs(np.where(np.isnan(printed), 0.0, printed) - acc_true))))
    return gap_v, gap_a, v_scale, a_scale


def kinematics_checks(*, a: float, m: int, w: float, radius: float = 1.0, samples: int = 2001) -> list[dict]:
    """Eqs. 9, 10 and the instants of extreme centre speed and acceleration, for the horizontal
    oscillation a·sin mτ at w, checked against the motion of body points (eqs. 5–7 differentiated
    in :func:`rollers.point_motion`) over one turn.

    The body points checked are the centre and four points on the roller circle, whose radius
    ``radius`` is R in the length unit of ``a`` (1 for units of R, the profile's scale for mm).
    Returns report-ready checks (see :func:`_check`).
    """
    osc = RB.harmonic("horizontal", a, m)
    gap_v, gap_a, v_scale, a_scale = _printed_gaps(osc, a=a, m=m, w=w, radius=radius, samples=samples)
    k = np.arange(0, 2 * m + 1)
    _, vel_paper, _ = RB.point_motion(osc, 0.0, 0.0, w=w, t=paper_vmax_instants(m, w, k))
    v_at_paper = np.hypot(*vel_paper.T)
    vmax = a * m * w
    _, _, acc_at = RB.point_motion(osc, 0.0, 0.0, w=w, t=amax_instants(m, w, k))
    amax = a * w * w * (m * m + 1)
    tol_v, tol_a = 1e-9 * max(v_scale, 1e-300), 1e-9 * max(a_scale, 1e-300)
    amax_ok = bool(np.allclose(np.hypot(*acc_at.T), amax, rtol=1e-9))
    return [
        paper_check(
            "paper-formula",
            "eq. 9: |V| of a body point",
            "as printed",
            {"largest_difference": gap_v},
            gap_v <= tol_v,
            f"printed eq. 9 differs from the differentiated motion by up to {gap_v:.3g}",
        ),
        paper_check(
            "paper-formula",
            "eq. 10: |A| of a body point",
            "+w²a[x1β²sin(wt+βt) − x1α²sin(wt−αt) + y1β²cos(wt+βt) − y1α²cos(wt−αt)]",
            {"largest_difference": gap_a, "largest_acceleration": a_scale},
            gap_a <= tol_a,
            "printed eq. 10 has the sign of its w²a[…] term reversed: A² = w⁴(x1² + y1²) + "
            "a²[α⁴ + β⁴ − 2α²β²cos(α+β)t]/4 − w²a[x1β²sin(wt+βt) − x1α²sin(wt−αt) + y1β²cos(wt+βt) − "
            f"y1α²cos(wt−αt)]; as printed it is off by up to {gap_a:.4g} "
            f"({100 * gap_a / max(a_scale, 1e-300):.0f}% of the largest |A|) here",
        ),
        paper_check(
            "paper-formula",
            "instants of the centre's largest speed a·m·w",
            "t = πk/(2wm)",
            {"t": "πk/(wm)", "speeds_at_printed_instants": sorted({round(float(s), 12) for s in v_at_paper})},
            bool(np.allclose(v_at_paper, vmax, rtol=1e-9)),
            f"printed t = πk/(2wm) includes the instants of the smallest speed a·w = {a * w:.4g} (odd k); "
            f"cos(α + β)t = 1 needs t = πk/(wm) (speed a·m·w = {vmax:.4g})",
        ),
        paper_check(
            "paper-formula",
            "instants of the centre's largest acceleration a·w²(m² + 1)",
            "t = (2k + 1)π/(2wm)",
            {"a_max": amax},
            amax_ok,
            "printed instants of the largest acceleration hold" if amax_ok else "printed Amax instants fail",
        ),
    ]


def amplitude_law_checks(ms=PAPER_M, by_eye=None) -> list[dict]:
    """The paper's regression (eq. 4), its √3/m² approximation and error range, and a1."""
    by_eye = by_eye or PAPER_BY_EYE
    m = np.array(ms, dtype=float)
    coefficient, exponent, r2 = power_law_fit(m, [by_eye[int(k)] for k in ms])
    gap = approximation_gap(ms)
    return [
        paper_check(
            "paper-claim",
            "eq. 4: a = 1.74·m^−2.07 with R² = 0.97, fitted to the by-eye limits",
            dict(EQ4),
            {"coefficient": coefficient, "exponent": exponent, "r2": r2},
            all(round(v, 2) == EQ4[k] for k, v in {"coefficient": coefficient, "exponent": exponent, "r2": r2}.items()),
            f"eq. 4 reproduced as a log–log fit: {coefficient:.4f}·m^{exponent:.4f}, R² = {r2:.4f}",
        ),
        paper_check(
            "paper-claim",
            "√3/m² replaces eq. 4 with an error of 12–25 % for m = 3…15",
            [0.12, 0.25],
            {"m": [int(k) for k in ms], "excess": gap.tolist()},
            abs(gap.min() - 0.12) < 0.005 and abs(gap.max() - 0.25) < 0.005,
            f"√3/m² exceeds eq. 4 by {100 * gap.min():.1f}% (m = {int(m[0])}) to {100 * gap.max():.1f}% "
            f"(m = {int(m[-1])}), not 12–25%",
        ),
        paper_check(
            "paper-formula",
            "in units of the roller spacing R√3 the law reads a1 = 3/m²",
            "a1 = 3/m²",
            {"a1": "1/m²", "a1_at_m": {int(k): float(v) for k, v in zip(ms, a1_from_law(m))}},
            False,
            "a1 = a/√3, so √3/m² (units of R) is a1 = 1/m² in units of R√3, not 3/m² (which is three "
            "times larger: a = 3√3/m²); eq. 4 itself gives a1 = 1.005·m^−2.07",
        ),
    ]
