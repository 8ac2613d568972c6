"""Charts of the roller bodies, the rolling wheel and carrier trains."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.ticker import NullFormatter

from ...geometry.outline import place
from .png import save_png, subplots

__all__ = ["draw", "limits_chart", "field_chart", "rolling_chart", "train_chart"]


def limits_chart(limits: dict, direction: str, roller_radius: float, path: Path, eq4: tuple[float, float]) -> None:
    """Largest amplitudes (convex and simple) against m: exact, the paper's, their fits."""
    m = np.array(limits["m"], dtype=float)
    fig, ax = subplots(figsize=(7.5, 5))
    ax.loglog(m, limits["convex"], "o-", label="convex (exact, root finding)")
    ax.loglog(m, limits["simple"], "s-", label="simple, no cusps (exact, bisection)")
    ax.loglog(m, limits["paper_by_eye"], "k^", label="paper: 'oval' by eye")
    mm = np.linspace(3, 15, 100)
    c, e = eq4
    ax.loglog(mm, c * mm**e, "k--", lw=0.8, label=f"paper: a = {c:g}·m^{e:g}".replace("-", "−"))
    ax.loglog(mm, np.sqrt(3) / mm**2, "k:", lw=0.8, label="paper: a = √3/m²")
    fit = limits["power_law_convex"]
    ax.loglog(
        mm,
        fit["coefficient"] * mm ** fit["exponent"],
        "C0--",
        lw=0.8,
        label=f"fit of exact convex: {fit['coefficient']:.3f}·m^{fit['exponent']:.3f}",
    )
    ax.set_xlabel("oscillation frequency m, per turn of the body")
    ax.set_ylabel("largest amplitude a / R")
    ax.set_xticks(m, [str(int(v)) for v in m])
    ax.xaxis.set_minor_formatter(NullFormatter())  # only the m ticks are labelled (no stray "4×10⁰")
    ax.set_title(f"{direction} oscillation, roller radius r = {roller_radius:g} R")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_png(fig, path)


def field_chart(chart: dict, path: Path) -> None:
    """Velocity and acceleration of contour points at four turn angles (``chart`` as the design
    computed it: ``mechanisms.roller_charts``), for the rollers the parts are cut with.  Each row
    draws its arrows to one scale (the longest a third of R), keyed by an arrow of a round length
    with its unit under every panel."""
    fig, axes = subplots(2, 4, figsize=(14, 7.6))
    rows = (("velocity", "velocity", "R/s"), ("acceleration", "acceleration", "R/s²"))
    for row, (label, key, unit) in enumerate(rows):
        longest = max(float(np.max(np.hypot(*np.asarray(at[key]).T))) for at in chart["field"])
        longest = longest if longest > 0 else 1.0
        scale = longest / 0.35  # (units of the quantity) per R of arrow on the drawing
        shown = _round_down(longest)
        for col, at in enumerate(chart["field"]):
            ax = axes[row, col]
            ax.plot(*at["outline"].T, color="0.5", lw=0.8)
            p, v = at["points"], at[key]
            arrows = ax.quiver(
                p[:, 0], p[:, 1], v[:, 0], v[:, 1], color="C0" if row == 0 else "C3",
                angles="xy", scale_units="xy", scale=scale, width=0.006,
            )  # fmt: skip
            ax.quiverkey(arrows, 0.5, -0.07, shown, f"{shown:g} {unit}", labelpos="E", coordinates="axes")
            ax.set_aspect("equal")
            ax.set_title(f"{label}, φ = {at['degrees']:.0f}°", fontsize=9)
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(
        f"body on three rollers: {chart['direction']}, m = {chart['m']}, a = {chart['amplitude']:g} R, "
        f"r = {chart['roller_radius']:.6g} R, {chart['rpm']:g} rpm (units of R; arrows to the key under each panel)"
    )
    fig.tight_layout(h_pad=2.5)
    save_png(fig, path)


def _round_down(value: float) -> float:
    """The largest 1, 2 or 5 × 10^k not above ``value`` (> 0): a key arrow's length."""
    power = 10.0 ** np.floor(np.log10(value))
    return float(max(s * power for s in (1, 2, 5) if s * power <= value * (1 + 1e-12)))


def rolling_chart(motion, params, path: Path) -> None:
    phi1, by_contour, by_rates = motion.phi1, motion.by_contour, motion.by_rates
    w2, w3, e2 = motion.omega2, motion.omega3, motion.eps2
    fig, axes = subplots(2, 2, figsize=(11, 7), sharex=True)
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
    fig, (ax, bar) = subplots(1, 2, figsize=(12, 5), gridspec_kw={"width_ratios": [1.3, 1]})
    for k, (part, pl) in enumerate(zip(parts, placements)):
        for ring in part.outline.rings:
            pts = place(ring, pl.angle, pl.offset)
            pts = np.vstack([pts, pts[:1]])
            ax.plot(pts[:, 0], pts[:, 1], color=f"C{k}", lw=0.7)
        ax.plot(*pl.offset, "+", color=f"C{k}")
    ax.plot([0, max(pl.offset[0] for pl in placements)], [0, 0], color="0.5", lw=2, alpha=0.4, label="carrier")
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
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
    names = []
    charts = design.charts
    if "amplitude_limits.png" in charts:
        c = charts["amplitude_limits.png"]
        limits_chart(c["limits"], c["direction"], c["roller_radius"], folder / "amplitude_limits.png", c["eq4"])
        names.append("amplitude_limits.png")
    if "velocity_field.png" in charts:
        field_chart(charts["velocity_field.png"], folder / "velocity_field.png")
        names.append("velocity_field.png")
    if "limits_vs_r.png" in charts:
        from . import papers

        c = charts["limits_vs_r.png"]
        papers.limits_vs_r_chart(c["table"], folder / "limits_vs_r.png", paper_by_eye=c["paper_by_eye"])
        names.append("limits_vs_r.png")
        # the paper's Figs. 1 and 2: contours for several amplitudes and roller radii
        for name in sorted(n for n in charts if n.startswith("shape_family_")):
            papers.shape_family_chart(charts[name]["family"], folder / name, title=charts[name]["title"])
            names.append(name)
    if "motion.png" in charts:
        rolling_chart(charts["motion.png"], design.params, folder / "motion.png")
        names.append("motion.png")
    if "train.png" in charts:
        train_chart(charts["train.png"], design.parts(), design.placements, folder / "train.png")
        names.append("train.png")
    return names
