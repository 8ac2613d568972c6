"""A wheel rolling on the ground, driven through an inclined rack (seed 000): inclination, rack
length, rates, the motion law two ways, and the two wheels as parts."""

from __future__ import annotations

import math

import numpy as np

from ..findings import finding
from ..geometry.rings import circle_ring
from ..profiles import RollingWheelParams
from ..tolerances import budget
from ..trains import rack_drive as RD
from .chart_data import Blocks, RollingWheelDetail
from .finish import Contact, Draft, PartSpec
from .parts import Placement

__all__ = ["RollingWheelDetail", "design"]

TWO_PI = 2 * math.pi
UNITS = {"length": "mm", "angle": "rad", "speed": "rad/s", "acceleration": "rad/s^2"}


def _motion(d: RD.RackDrive, p: RollingWheelParams, w1: float) -> RollingWheelDetail:
    if math.isclose(p.H, p.R - p.r, rel_tol=1e-12, abs_tol=1e-12 * max(p.R, p.r)):
        # a horizontal rack stays horizontal (β ≡ 0): the law is linear, φ2 = φ1·r/(2R), and
        # both methods give it exactly; the rack does not turn (ω3 = 0) and ε2 = 0
        phi1 = np.linspace(0.0, p.travel / p.R * 2 * p.R / p.r, 401)
        phi2 = phi1 * p.r / (2 * p.R)
        zero = np.zeros_like(phi1)
        return RollingWheelDetail(phi1, phi2, phi2.copy(), zero + w1 * p.r / (2 * p.R), zero, zero)
    beta_end = float(RD.inclination(d, p.L - p.travel))
    phi1 = np.linspace(0.0, RD.contour_state(d, beta_end)[0], 401)
    by_contour = RD.law_by_contour(d, phi1)
    by_rates = RD.law_by_rates(d, phi1)
    w2, w3, e2 = RD.rates(d, p.L - p.R * by_contour, omega1=w1)
    return RollingWheelDetail(phi1, by_contour, by_rates, w2, w3, e2)


def _printed_formulas(
    d: RD.RackDrive, p: RollingWheelParams, motion: RollingWheelDetail, w1: float, l0: float, paper_l: float
) -> list:
    """A finding for each of the paper's printed formulas that differs from what it derives from."""
    e2 = motion.eps2
    findings = []
    if abs(paper_l - l0) > 1e-9 * l0:
        findings.append(
            finding(
                "paper-formula",
                f"printed eq. 2 (l² = L² + H² + (R − r)²) gives l = {paper_l:.4f} mm; eq. 1 gives "
                f"l² = L² + H² − (R − r)², l = {l0:.4f} mm (used)",
                "drive",
            )
        )
    scale = float(np.max(np.abs(e2))) or 1.0
    gap = float(np.max(np.abs(RD.paper_eps2(d, p.L - p.R * motion.by_contour, omega1=w1) - e2)))
    if gap > 1e-9 * scale:
        findings.append(
            finding(
                "paper-formula",
                "printed eq. 9 lacks a factor 1/(1 + cos β) in its second term: its ε2 differs from the derivative of "
                f"eq. 8 by up to {gap:.4g} rad/s² here ({100 * gap / scale:.0f}% of the largest ε2); the corrected "
                "form is used",
                "drive",
            )
        )
    return findings


def _data(d, p: RollingWheelParams, motion: RollingWheelDetail, w1: float, geometry: Blocks, checks: dict) -> Blocks:
    """The report's blocks: the drive as given, its geometry, its motion over the travel, the checks."""
    w2, w3, e2 = motion.omega2, motion.omega3, motion.eps2
    difference = float(np.max(np.abs(motion.by_contour - motion.by_rates)))
    return {
        "drive": {"r": p.r, "R": p.R, "L": p.L, "H": p.H, "travel": p.travel, "driver_rpm": p.driver_rpm},
        "geometry": geometry,
        "motion": {
            "phi1_end": float(motion.phi1[-1]),
            "phi2_end": float(motion.by_contour[-1]),
            "law_difference": difference,
            "omega2_min": float(w2.min()),
            "omega2_max": float(w2.max()),
            "omega3_min": float(w3.min()),
            "omega3_max": float(w3.max()),
            "eps2_min": float(e2.min()),
            "eps2_max": float(e2.max()),
            "ratio_start": float(w2[0] / w1),
            "ratio_horizontal_rack": p.r / (2 * p.R),
        },
        "checks": checks,
    }


def design(p: RollingWheelParams) -> Draft[RollingWheelDetail]:
    """The drive's geometry and motion, checked two ways, and its two wheels as parts."""
    d = RD.RackDrive(p.r, p.R, p.L, p.H)
    beta0 = float(RD.inclination(d))
    l0 = float(RD.rack_length(d))
    beta_end = float(RD.inclination(d, p.L - p.travel))
    w1 = p.driver_rpm * TWO_PI / 60
    motion = _motion(d, p, w1)
    difference = float(np.max(np.abs(motion.by_contour - motion.by_rates)))
    w2 = motion.omega2
    paper_l = RD.paper_rack_length(d)
    findings = _printed_formulas(d, p, motion, w1, l0, paper_l)
    if difference > 1e-9:
        findings.append(finding("not-closed", f"the two motion laws differ by {difference:.3g} rad", "drive"))
    along = p.L - p.R * motion.by_contour  # horizontal distances over the travel
    checks = {"eq10": RD.eq10_check(d, along), "projections": RD.projection_check(d, along, omega1=w1)}
    for check in checks.values():
        if not check.get("holds", True) and check.get("code"):
            findings.append(finding(check["code"], check["message"], "drive"))
    paper_beta = RD.paper_inclination(d) if p.R != p.r else None
    geometry = {
        "beta_start": beta0,
        "beta_end": beta_end,
        "rack_length_start": l0,
        "rack_length_paper_eq2": paper_l,
        "beta_paper_eq10": paper_beta,
    }
    data = _data(d, p, motion, w1, geometry, checks)
    out = p.output
    fine = budget(out.tolerance).fine
    # a plain wheel has no pitch curve to engrave apart from its cut: only the pivot is marked
    parts = (PartSpec("wheel1", circle_ring(p.r, fine)), PartSpec("wheel2", circle_ring(p.R, fine)))
    placements = (Placement("wheel1", 0.0, (p.L, p.H)), Placement("wheel2"))
    summary = (
        f"β {math.degrees(beta0):.3f}°→{math.degrees(beta_end):.3f}°, ω2/ω1 {w2.min() / w1:.5f}…"
        f"{w2.max() / w1:.5f}, motion laws agree to {difference:.1e} rad"
    )
    return Draft(
        params=p,
        mechanism="rolling-wheel",
        summary=summary,
        findings=tuple(findings),
        parts=parts,
        placements=placements,
        contacts=(Contact(0, 1, touch="apart"),),  # the wheels must not touch
        data=data,
        units=UNITS,
        detail=motion,
        charts={"motion.png": motion},
        placed="the two wheels where the drive holds them, joined by the rack (not drawn), not touching",
        where="drive",
    )
