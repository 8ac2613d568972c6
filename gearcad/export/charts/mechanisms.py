"""Charts of the roller bodies, the rolling wheel and carrier trains."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.ticker import NullFormatter

from ...bodies import rollers as RB
from ...geometry.outline import rotate
from .png import plt, save_png

__all__ = ["draw", "limits_chart", "field_chart", "rolling_chart", "train_chart"]


def limits_chart(limits: dict, params, path: Path) -> None:
    """Largest amplitudes (convex and simple) against m: exact, the paper's, their fits."""
    m = np.array(limits["m"], dtype=float)
    fig, ax = plt.subplots(figsize=(7.5, 5))
    ax.loglog(m, limits["convex"], "o-", label="convex (exact, root finding)")
    ax.loglog(m, limits["simple"], "s-", label="simple, no cusps (exact, bisection)")
    ax.loglog(m, limits["paper_by_eye"], "k^", label="paper: 'oval' by eye")
    mm = np.linspace(3, 15, 100)
    ax.loglog(mm, 1.74 * mm**-2.07, "k--", lw=0.8, label="paper: a = 1.74·m^−2.07")
    ax.loglog(mm, np.sqrt(3) / mm**2, "k:", lw=0.8, label="paper: a = √3/m²")
    fit = limits["power_law_convex"]
    ax.loglog(
        mm,
        fit["coefficient"] * mm ** fit["exponent"],
        "C0--",
        lw=0.8,
        label=f"fit of exact convex: {fit['coefficient']:.3f}·m^{fit['exponent']:.3f}",
    )
    ax.set_xlabel("oscillation frequency m")
    ax.set_ylabel("largest amplitude a / R")
    ax.set_xticks(m, [str(int(v)) for v in m])
    ax.xaxis.set_minor_formatter(NullFormatter())  # only the m ticks are labelled (no stray "4×10⁰")
    ax.set_title(f"{params.direction} oscillation, roller radius r = {params.roller_radius:g} R")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_png(fig, path)


def field_chart(osc, params, path: Path, roller_radius: float) -> None:
    """Velocity and acceleration of contour points at four turn angles (w from the profile)."""
    w = params.rpm * 2 * math.pi / 60
    tau = np.linspace(0, 2 * math.pi, 49, endpoint=False)
    fig, axes = plt.subplots(2, 4, figsize=(14, 7))
    dense = np.linspace(0, 2 * math.pi, 2000)
    for col, phi in enumerate(np.radians([0, 30, 60, 90])):
        t = phi / w
        for row, (label, k) in enumerate((("velocity", 1), ("acceleration", 2))):
            ax = axes[row, col]
            outline = RB.contour(osc, dense, r=roller_radius)
            pos = [RB.point_motion(osc, x, y, w=w, t=np.array([t]))[0][0] for x, y in outline[::10]]
            ax.plot(*np.array(pos).T, color="0.5", lw=0.8)
            pts = RB.contour(osc, tau, r=roller_radius)
            motion = [RB.point_motion(osc, x, y, w=w, t=np.array([t])) for x, y in pts]
            p = np.array([mo[0][0] for mo in motion])
            v = np.array([mo[k][0] for mo in motion])
            ax.quiver(p[:, 0], p[:, 1], v[:, 0], v[:, 1], color="C0" if k == 1 else "C3", angles="xy")
            ax.set_aspect("equal")
            ax.set_title(f"{label}, φ = {math.degrees(phi):.0f}°", fontsize=9)
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(
        f"body on three rollers: {params.direction}, m = {params.m}, a = {params.amplitude:g} R, "
        f"{params.rpm:g} rpm (units of R)"
    )
    fig.tight_layout()
    save_png(fig, path)


def rolling_chart(motion, params, path: Path) -> None:
    phi1, by_contour, by_rates = motion.phi1, motion.by_contour, motion.by_rates
    w2, w3, e2 = motion.omega2, motion.omega3, motion.eps2
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    x = np.degrees(phi1)
    axes[0, 0].plot(x, np.degrees(by_contour), label="closed contour (eqs. 3, 5)")
    axes[0, 0].plot(x, np.degrees(by_rates), "--", label="integrated rate law (eq. 8)")
    axes[0, 0].set_ylabel("φ2, degrees")
    axes[0, 0].legend(fontsize=8)
    axes[0, 1].semilogy(x, np.maximum(np.abs(by_contour - by_rates), 1e-17))
    axes[0, 1].set_ylabel("|difference|, rad")
    axes[1, 0].plot(x, w2, label="ω2 (wheel)")
    axes[1, 0].plot(x, w3, label="ω3 (rack)")
    axes[1, 0].set_ylabel("rad/s")
    axes[1, 0].legend(fontsize=8)
    axes[1, 1].plot(x, e2, color="C3")
    axes[1, 1].set_ylabel("ε2, rad/s²")
    for ax in axes[1]:
        ax.set_xlabel("φ1 (driver), degrees")
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    fig.suptitle(
        f"wheel driven through an inclined rack: r = {params.r:g}, R = {params.R:g}, L = {params.L:g}, "
        f"H = {params.H:g} mm, {params.driver_rpm:g} rpm"
    )
    fig.tight_layout()
    save_png(fig, path)


def train_chart(report: dict, parts, placements, path: Path) -> None:
    fig, (ax, bar) = plt.subplots(1, 2, figsize=(12, 5), gridspec_kw={"width_ratios": [1.3, 1]})
    for k, (part, pl) in enumerate(zip(parts, placements)):
        for ring in part.outline.rings:
            pts = rotate(ring, pl.angle) + np.asarray(pl.offset)
            pts = np.vstack([pts, pts[:1]])
            ax.plot(pts[:, 0], pts[:, 1], color=f"C{k}", lw=0.7)
        ax.plot(*pl.offset, "+", color=f"C{k}")
    ax.plot([0, max(pl.offset[0] for pl in placements)], [0, 0], color="0.5", lw=2, alpha=0.4, label="carrier")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_title("gears on the carrier (assembled)")
    names = [g["name"] for g in report["gears"]]
    bar.bar(names, [g["omega_rpm"] for g in report["gears"]], color=[f"C{k}" for k in range(len(names))])
    bar.axhline(report["train"]["carrier_rpm"], color="0.4", ls="--", label="carrier")
    bar.set_ylabel("absolute speed, rpm")
    bar.legend(fontsize=8)
    bar.grid(alpha=0.3)
    bar.set_title("method of stopping")
    fig.tight_layout()
    save_png(fig, path)


def draw(design, folder: Path) -> list[str]:
    """Every chart of a roller-body, rolling-wheel or carrier-train design; returns file names."""
    p, names = design.params, []
    if design.mechanism == "roller-body":
        if "limits" in design.data:
            limits_chart(design.data["limits"], p, folder / "amplitude_limits.png")
            names.append("amplitude_limits.png")
        field_chart(design.detail.oscillation, p, folder / "velocity_field.png", p.roller_radius)
        names.append("velocity_field.png")
        if "limits_vs_r" in design.data:
            from ...bodies import claims as C
            from ...bodies import limits as LM
            from . import papers

            table = design.data["limits_vs_r"]
            papers.limits_vs_r_chart(table, folder / "limits_vs_r.png", paper_by_eye=C.PAPER_BY_EYE)
            names.append("limits_vs_r.png")
            # the paper's Figs. 1 and 2: contours for several amplitudes and roller radii
            for fig, m, amplitudes in ((1, 3, [0.1, 0.15, 0.2]), (2, 6, [0.03, 0.05, 0.1])):
                family = LM.shape_family(p.direction, m, amplitudes, LM.PAPER_RADII)
                name = f"shape_family_m{m}.png"
                papers.shape_family_chart(family, folder / name, title=f"Fig. {fig}: {p.direction}, m = {m}")
                names.append(name)
    elif design.mechanism == "rolling-wheel":
        rolling_chart(design.detail, p, folder / "motion.png")
        names.append("motion.png")
    elif design.mechanism == "carrier-train":
        train_chart(design.data, design.parts(), design.placements, folder / "train.png")
        names.append("train.png")
    return names
