"""Charts of the papers' claims against gearcad's numbers.  Every function takes plain data (the
``as_dict()`` / report blocks of the numerical cores) and a path, and writes one PNG."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...geometry.outline import place
from .png import save_png, subplots

__all__ = [
    "limits_vs_r_chart",
    "shape_family_chart",
    "elliptic_type2_chart",
    "walker_speed_chart",
    "walker_pitch_chart",
    "shoe_chart",
]

_KIND_STYLE = {"convex": ("C0", "-"), "concave": ("C1", "-"), "looped": ("C3", "-")}


def limits_vs_r_chart(table: dict, path: Path, *, paper_by_eye: dict | None = None) -> None:
    """Seed 003: largest convex and simple amplitudes against the roller radius r, one line per
    m, one panel per direction (``table`` = ``LimitTable.as_dict()``: both directions).  The
    paper's by-eye values give no r, so they are no point here: they are listed under the legend
    (amplitude_limits.png draws them against m, where the paper gives them)."""
    directions = list(table["convex"])
    r = np.array(table["r"], dtype=float)
    fig, axes = subplots(1, len(directions), figsize=(6.5 * len(directions), 5), squeeze=False)
    for ax, d in zip(axes[0], directions):
        for i, m in enumerate(table["m"]):
            convex = np.array([np.nan if v is None else v for v in table["convex"][d][i]], dtype=float)
            simple = np.array([np.nan if v is None else v for v in table["simple"][d][i]], dtype=float)
            ax.semilogy(r, convex, "o-", color=f"C{i}", label=f"m = {m}: convex")
            ax.semilogy(r, simple, "s--", color=f"C{i}", label=f"m = {m}: simple (no loops)")
        ax.set_xlabel("roller radius r / R")
        ax.set_ylabel("largest amplitude a / R")
        ax.set_title(f"{d} oscillation")
        ax.grid(alpha=0.3, which="both")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.set_size_inches(6.5 * len(directions) + 2.4, 5)
    fig.legend(handles, labels, loc="upper right", fontsize=7)  # beside the data
    if paper_by_eye:
        values = "\n".join(f"m = {m}: {a:g}" for m, a in sorted(paper_by_eye.items()))
        fig.text(0.995, 0.04, f"paper, 'oval' by eye\n(no r given;\nsee amplitude_limits.png):\n{values}",
                 ha="right", va="bottom", fontsize=7)  # fmt: skip
    fig.suptitle("amplitude limits against the roller radius:\nthe convex limit does not move, the loops do")
    fig.tight_layout(rect=(0, 0, 1 - 2.4 / (6.5 * len(directions) + 2.4), 1))
    save_png(fig, path)


def shape_family_chart(family: list[dict], path: Path, *, title: str = "") -> None:
    """Seed 003, Figs. 1–2: contours by amplitude (rows) and roller radius (columns), coloured
    by kind (convex 'oval', concave, looped).  ``family`` is ``claims.shape_family(...)``."""
    amplitudes = sorted({f["amplitude"] for f in family})
    radii = sorted({f["r"] for f in family})
    fig, axes = subplots(len(amplitudes), len(radii), figsize=(2.4 * len(radii), 2.4 * len(amplitudes)), squeeze=False)
    for f in family:
        ax = axes[amplitudes.index(f["amplitude"]), radii.index(f["r"])]
        colour, style = _KIND_STYLE[f["kind"]]
        pts = np.asarray(f["points"])
        ax.plot(pts[:, 0], pts[:, 1], color=colour, ls=style, lw=1.0)
        for k in range(3):  # the rollers, at the body's start position
            a = 2 * math.pi * k / 3
            t = np.linspace(0, 2 * math.pi, 60)
            ax.plot(math.sin(a) + f["r"] * np.cos(t), math.cos(a) + f["r"] * np.sin(t), color="0.6", lw=0.6)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"a = {f['amplitude']:g}, r = {f['r']:g}: {f['kind']}", fontsize=7, color=colour)
    fig.suptitle(title or "body shapes (units of R)")
    fig.tight_layout()
    save_png(fig, path)


def elliptic_type2_chart(data: dict, path: Path) -> None:
    """Seed 004, Fig. 10 / Table 2: ω2 and ε2 of the paper's type-2 construction (identical
    ellipses at a + b, which does not roll) beside the ellipse pair that rolls and the oval.
    ``data`` is ``Type2Comparison.as_dict()``."""
    phi = np.asarray(data["phi_deg"])
    fig, (top, bottom) = subplots(2, 1, figsize=(9, 7), sharex=True)
    series = (
        ("paper", "k--", "paper's construction: identical ellipses at a + b (does NOT roll)"),
        ("rolling_ellipse", "C0-", f"ellipse + computed mate at E = {data['rolling_ellipse']['center_distance']:.4f}"),
        ("oval", "C2-", "self-conjugate oval at a + b"),
    )
    for key, style, label in series:
        top.plot(phi, np.asarray(data[key]["omega2"]) / math.pi, style, label=label)
        bottom.plot(phi, np.asarray(data[key]["eps2"]) / math.pi**2, style, label=label)
    top.set_ylabel("ω2 / π, rad/s")
    bottom.set_ylabel("ε2 / π², rad/s²")
    bottom.set_xlabel("φ (driver), degrees")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
        ax.set_xticks(np.arange(0, 361, 45))
    fig.legend(*top.get_legend_handles_labels(), loc="lower center", ncol=1, fontsize=8)  # below the data
    fig.suptitle("elliptic gears pivoted at their centres (type 2):\nthe paper's Table 2 against pairs that roll")
    fig.tight_layout(rect=(0, 0.13, 1, 1))
    save_png(fig, path)


def walker_speed_chart(speeds: dict, path: Path) -> None:
    """Seed 002: vehicle speed per unit drive-shaft speed over a stance quarter, for round gears
    (i = 4), the paper's pair and the pair that rolls.  ``speeds`` is
    ``shoe.speed_comparison(...)``."""
    phi = np.asarray(speeds["phi_deg"])
    labels = {
        "round": "round gears, i = 4 (the existing machine)",
        "paper_as_built": "paper's pair, contact on the centre line (θ = 4φ): same as round",
        "paper_as_intended": "paper's pair as intended (pinion would turn {turn:.2f}° per quarter)",
        "rolling": "the pair that rolls and closes 4:1",
    }
    styles = {"round": "C3-", "paper_as_built": "k:", "paper_as_intended": "k--", "rolling": "C0-"}
    fig, ax = subplots(figsize=(9, 5))
    for key, label in labels.items():
        if key not in speeds:
            continue
        entry = speeds[key]
        text = label.format(turn=entry["pinion_turn_per_quarter_deg"])
        ax.plot(phi, entry["v"], styles[key], label=f"{text}: ±{50 * entry['variation']:.1f}%")
    ax.set_xlabel("hub angle φ, degrees (one stance)")
    ax.set_ylabel("v / ω, mm per rad of the drive shaft")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("wheel-walker: vehicle speed with the shoe of eqs. 1–2")
    fig.tight_layout()
    save_png(fig, path)


def walker_pitch_chart(paper: dict, rolling: dict, path: Path) -> None:
    """Seed 002: the paper's pitch curves (eqs. 10, 12 with θ = 4φ) beside the pair that rolls.

    Each dict holds polar samples about each pivot: ``wheel_phi``, ``wheel_r``, ``pinion_theta``,
    ``pinion_r`` (rad, mm), and the centre distance ``L``.
    """
    fig, axes = subplots(1, 2, figsize=(12, 6))
    for ax, data, title in ((axes[0], paper, "paper (θ = 4φ)"), (axes[1], rolling, "the pair that rolls")):
        wp, wr = np.asarray(data["wheel_phi"]), np.asarray(data["wheel_r"])
        pp, pr = np.asarray(data["pinion_theta"]), np.asarray(data["pinion_r"])
        ax.plot(wr * np.cos(wp), wr * np.sin(wp), "C0-", label="carrier wheel")
        ax.plot(data["L"] - pr * np.cos(pp), pr * np.sin(pp), "C1-", label="pinion")
        ax.plot([0, data["L"]], [0, 0], "k+", ms=10)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel("x from the wheel's pivot, mm")
        ax.set_ylabel("y, mm")
        ax.set_title(title)
        ax.legend(fontsize=8)
    fig.suptitle("wheel-walker pitch curves (mm)")
    fig.tight_layout()
    save_png(fig, path)


def shoe_chart(ring, poses, hub_height: float, path: Path) -> None:
    """Seed 002: the leg part placed at several hub angles over the ground line.

    ``ring`` (n, 2) mm in the leg frame; ``poses`` a list of (hub angle rad, rotation rad,
    (x, y) offset of B1 from the hub, mm); the ground is ``hub_height`` below the hub.
    """
    ring = np.asarray(ring)
    fig, ax = subplots(figsize=(9, 7))
    for k, (phi, angle, offset) in enumerate(poses):
        pts = place(ring, angle, offset)
        pts = np.vstack([pts, pts[:1]])
        ax.plot(pts[:, 0], pts[:, 1], color=f"C{k % 10}", lw=0.8, label=f"φ = {math.degrees(phi):.0f}°")
        ax.plot([0, offset[0]], [0, offset[1]], color=f"C{k % 10}", lw=0.6, alpha=0.6)
    ax.axhline(-hub_height, color="0.3", lw=1.5)
    ax.plot([0], [0], "k+", ms=12)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x from the hub, mm")
    ax.set_ylabel("y from the hub, mm")
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    fig.set_size_inches(9, min(9.0, max(3.5, 6.9 * (y1 - y0) / (x1 - x0) + 1.2)))  # as high as the drawing needs
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside the data
    ax.set_title(f"wheel-walker leg over a stance: hub {hub_height:g} mm above the ground at every angle")
    fig.tight_layout()
    save_png(fig, path)
