"""The `pressure-angle` warning (issue 33) against the written parts: the working pressure angle
measured on the driver's DXF outline where each flank crosses the pitch curve, as the angle
between the flank's normal and the perpendicular to the radius there (the line of centres'
perpendicular when that point is the pitch point), against α ± μ with tan μ = r'/r of the pitch
curve read from kinematics.csv (r1 = E·i/(1 + i)), and the warning's largest against the
largest measured."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from . import fit_oracle as fo


def _flank_angles(folder):
    """Per flank crossing of the driver's pitch curve: (polar angle, measured angle, μ), degrees."""
    mesh = fo.pair_mesh(folder, "driver", "follower", "driver", 20.0, 1.0)
    (a1, c1), (_, c2) = mesh.pose0
    line = math.atan2(*(c2 - c1)[::-1])
    phi = np.linspace(0, 2 * np.pi, 4000, endpoint=False)
    turn, _ = mesh.turns(phi)
    theta = np.mod(line - (a1 + turn), 2 * np.pi)  # the pitch point in the driver's own frame
    order = np.argsort(theta)
    theta, radius = theta[order], np.asarray(mesh.contact_radius1(phi))[order]

    def pitch(t):
        return np.interp(t, theta, radius, period=2 * np.pi)

    xy = np.asarray(mesh.shapes[0].exterior.coords)
    gap = np.hypot(xy[:, 0], xy[:, 1]) - pitch(np.arctan2(xy[:, 1], xy[:, 0]))
    out = []
    for i in np.flatnonzero(np.sign(gap[:-1]) != np.sign(gap[1:])):
        q = xy[i] + gap[i] / (gap[i] - gap[i + 1]) * (xy[i + 1] - xy[i])
        tangent = (xy[i + 1] - xy[i]) / np.hypot(*(xy[i + 1] - xy[i]))
        t = math.atan2(q[1], q[0])
        across = np.array([-math.sin(t), math.cos(t)])  # perpendicular to the radius
        measured = math.degrees(math.acos(min(1.0, abs(tangent[0] * across[1] - tangent[1] * across[0]))))
        h = 1e-4
        mu = math.degrees(math.atan((pitch(t + h) - pitch(t - h)) / (2 * h) / pitch(t)))
        out.append((math.degrees(t) % 360, measured, mu))
    return np.array(out)


def test_the_focus_pairs_working_pressure_angle_is_measured_on_its_flanks(built):
    import json

    folder = built / "elliptic_focus"
    flanks = _flank_angles(folder)
    assert len(flanks) == 2 * 41  # each tooth's two flanks
    alpha = 20.0
    # every flank: the rack's α tilted by the pitch curve's μ, one way on one flank, the other on the next
    plus, minus = np.abs(alpha + flanks[:, 2]), np.abs(alpha - flanks[:, 2])
    error = np.minimum(np.abs(flanks[:, 1] - plus), np.abs(flanks[:, 1] - minus))
    assert error.max() < 0.5, flanks[np.argmax(error)]  # the written arcs' tangents stray ~0.2°
    report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    (warning,) = [w for w in report["warnings"] if w["code"] == "pressure-angle"]
    largest = float(re.search(r"reaches ([0-9.]+)°", warning["message"]).group(1))
    where = float(re.search(r"at driver angle ([0-9.]+)°", warning["message"]).group(1))
    assert largest == pytest.approx(73.13, abs=0.05)  # 20° + asin(e), e = 0.8: the focus ellipse's largest tilt
    assert flanks[:, 1].max() == pytest.approx(largest, abs=0.5)  # flanks 4.4° apart near a flat top
    assert "45" in warning["message"] and f"{largest - 45:.1f}° over" in warning["message"]
    # where: the driver angle at which the tilt is largest, (π − acos e) from the far vertex
    assert min(abs(where - 36.87), abs(where - 323.13)) < 0.2
