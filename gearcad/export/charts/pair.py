"""Charts of a gear pair: pitch curves in mesh, follower speed and acceleration, teeth in mesh."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .png import PolyCollection, save_png, subplots

__all__ = ["draw", "pitch_chart", "kinematics_chart", "mesh_chart"]


def pitch_chart(data, path: Path, rings) -> None:
    """The pair in place at driver angle 0, and r(φ) of both gears."""
    fig, (ax, ax2) = subplots(1, 2, figsize=(12, 5.2), gridspec_kw={"width_ratios": [1.25, 1]})
    e = data.pair.center_distance
    colours, dashes = ("tab:blue", "tab:orange"), ("-", "--")  # dashed: an identical mate stays visible
    for gear, ring, colour, ls in zip(data.gears, rings, colours, dashes):
        closed = np.vstack([ring, ring[:1]]) + np.asarray(gear.pivot)
        ax.plot(closed[:, 0], closed[:, 1], color=colour, lw=1.4, ls=ls, label=gear.name)
        ax.plot(*gear.pivot, "+", color=colour, ms=10)
        for c in gear.shape.corners:  # the curve's own radius there: r(φ) (cos φ, sin φ)
            r = gear.curve.r(np.array([c.phi]))[0]
            ax.plot(
                *(r * np.array([np.cos(c.phi), np.sin(c.phi)]) + np.asarray(gear.pivot)),
                "o",
                mfc="none",
                color="red",
                ms=8,
            )
    contact = data.gears[0].curve.r(np.array([0.0]))[0]
    ax.plot([0, e], [0, 0], color="0.6", lw=0.8, ls=":")
    ax.plot(contact, 0, "k.", ms=6)
    ax.set_aspect("equal")
    ax.set_title(f"pitch curves in mesh, E = {e:.4f} mm")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.grid(alpha=0.3)
    phi = np.linspace(0.0, 2 * np.pi, 1441)
    for gear, colour, ls in zip(data.gears, colours, dashes):
        ax2.plot(np.degrees(phi), gear.curve.r(phi), color=colour, ls=ls, label=gear.name)
    ax2.set_xlabel("polar angle φ, degrees")
    ax2.set_ylabel("r, mm")
    ax2.set_xticks(range(0, 361, 45))
    ax2.set_title("radius against polar angle")
    ax2.grid(alpha=0.3)
    fig.legend(*ax.get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8)  # below the data
    fig.suptitle(data.params.title or data.params.name, parse_math=False)  # text, never mathtext
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.17, top=0.86, wspace=0.22)
    save_png(fig, path)


def kinematics_chart(data, path: Path) -> None:
    """Follower speed and acceleration against driver angle at constant driver speed."""
    k = data.kinematics
    p = data.params
    names = (p.gear1_name, p.gear2_name)
    driver, follower = names[k.driver - 1], names[2 - k.driver]
    fig, (a1, a2) = subplots(2, 1, figsize=(8, 6.4), sharex=True)
    x = np.degrees(k.driver_angle)
    a1.plot(x, k.speed, color="tab:blue")
    a1.set_ylabel(f"ω {follower}, rad/s")
    a1.grid(alpha=0.3)
    a2.plot(x, k.acceleration, color="tab:red")
    a2.set_ylabel(f"ε {follower}, rad/s²")
    a2.set_xlabel(f"{driver} angle, degrees")
    a2.set_xticks(range(0, 361, 45))
    a2.grid(alpha=0.3)
    a1.set_title(f"{follower} driven by {driver} at {p.driver_rpm:g} rpm ({k.driver_speed:.4g} rad/s)")
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.09, top=0.94, hspace=0.08)
    save_png(fig, path)


def mesh_chart(data, teeth, path: Path) -> None:
    """The toothed pair in mesh at driver angle 0: whole, and the mesh zone close up."""
    fig, (ax, zoom) = subplots(1, 2, figsize=(12, 5.6), gridspec_kw={"width_ratios": [1.3, 1]})
    colours = ("tab:blue", "tab:orange")
    for gear, toothed, colour in zip(data.gears, teeth.gears, colours):
        ring = np.vstack([toothed.outline.outer, toothed.outline.outer[:1]]) + np.asarray(gear.pivot)
        for a in (ax, zoom):
            # a collection: its limits come from the vertices at once (a patch walks them one by one)
            a.add_collection(PolyCollection([ring], facecolors=colour, alpha=0.25, linewidths=0))
            a.plot(
                ring[:, 0],
                ring[:, 1],
                color=colour,
                lw=0.7,
                label=f"{gear.name}: {toothed.teeth} teeth" if a is ax else None,
            )
            a.plot(*gear.pivot, "+", color=colour, ms=9)
    contact = data.gears[0].curve.r(np.array([0.0]))[0]
    m = teeth.plan.module
    zoom.set_xlim(contact - 5 * m, contact + 5 * m)
    zoom.set_ylim(-5 * m, 5 * m)
    for a in (ax, zoom):
        a.set_aspect("equal")
        a.grid(alpha=0.3)
        a.set_xlabel("x, mm")
        a.set_ylabel("y, mm")
    mesh = teeth.mesh
    ax.set_title(f"module {m:.4f} mm, E = {data.pair.center_distance:.4f} mm")
    fig.legend(*ax.get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8)  # below the data
    zoom.set_title(
        f"mesh zone: max overlap {mesh.max_overlap:.2g} mm² over {mesh.positions} positions "
        f"({'meshes' if mesh.meshes else 'INTERFERES'})",
        fontsize=9,
    )
    fig.suptitle(data.params.title or data.params.name, parse_math=False)  # text, never mathtext
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.15, top=0.88, wspace=0.15)
    save_png(fig, path)


def draw(design, folder: Path) -> list[str]:
    """Every chart of a gear pair the design's ``charts`` name; returns the file names."""
    charts, names = design.charts, []
    if "pitch_curves.png" in charts:
        pitch, rings = charts["pitch_curves.png"]
        pitch_chart(pitch, folder / "pitch_curves.png", rings)
        names.append("pitch_curves.png")
    if "kinematics.png" in charts:
        kinematics_chart(charts["kinematics.png"], folder / "kinematics.png")
        names.append("kinematics.png")
    if "mesh.png" in charts:
        mesh_chart(*charts["mesh.png"], folder / "mesh.png")
        names.append("mesh.png")
    papers = ("elliptic_type2.png", "vehicle_speed.png", "shoe.png")
    if any(n in charts for n in papers):
        from . import papers as drawn

        if "elliptic_type2.png" in charts:
            drawn.elliptic_type2_chart(charts["elliptic_type2.png"], folder / "elliptic_type2.png")
            names.append("elliptic_type2.png")
        if "vehicle_speed.png" in charts:
            drawn.walker_speed_chart(charts["vehicle_speed.png"], folder / "vehicle_speed.png")
            drawn.walker_pitch_chart(*charts["paper_pitch_curves.png"], folder / "paper_pitch_curves.png")
            names += ["vehicle_speed.png", "paper_pitch_curves.png"]
        if "shoe.png" in charts:
            drawn.shoe_chart(*charts["shoe.png"], folder / "shoe.png")
            names.append("shoe.png")
    return names
