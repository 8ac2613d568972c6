"""Polylines of a pitch curve within a tolerance, with no more points than it needs."""

from __future__ import annotations

import numpy as np

from .curve import PitchCurve, curvature, points, segments

__all__ = ["polyline_angles", "polyline", "chord_deviation"]


def chord_deviation(curve: PitchCurve, phi: np.ndarray) -> np.ndarray:
    """Distance of the curve point at each parameter midpoint from its chord, mm.

    ``phi`` is the closed list of vertex angles (last = first + 2π).
    """
    a, b = points(curve, phi[:-1]), points(curve, phi[1:])
    m = points(curve, 0.5 * (phi[:-1] + phi[1:]))
    chord = b - a
    length = np.hypot(chord[:, 0], chord[:, 1])
    cross = np.abs(chord[:, 0] * (m[:, 1] - a[:, 1]) - chord[:, 1] * (m[:, 0] - a[:, 0]))
    return cross / np.where(length > 0, length, 1.0)


def polyline_angles(curve: PitchCurve, tolerance: float) -> np.ndarray:
    """Vertex angles (closed: last = first + 2π) whose chords stay within ``tolerance`` mm.

    A chord of length h on a curve of curvature κ strays κh²/8 from it, so the vertices are
    spread with density √(|κ|/8·tol) per mm of arc; seams are always vertices, so corners
    stay sharp.  Chords still over the tolerance are split until none is.
    """
    edges = segments(curve)
    parts = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        fine = np.linspace(lo, hi, 1025)
        speed = np.hypot(curve.r(fine), curve.dr(fine))
        density = speed * np.sqrt(np.abs(curvature(curve, fine)) / (8 * tolerance))
        cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(fine))])
        n = max(2, int(np.ceil(cumulative[-1] * 1.05)))
        parts.append(np.interp(np.linspace(0, cumulative[-1], n + 1), cumulative, fine)[:-1])
    phi = np.concatenate([*parts, [edges[-1]]])
    for _ in range(20):
        bad = chord_deviation(curve, phi) > tolerance
        if not np.any(bad):
            break
        mids = 0.5 * (phi[:-1] + phi[1:])[bad]
        phi = np.sort(np.concatenate([phi, mids]))
    return phi


def polyline(curve: PitchCurve, tolerance: float) -> np.ndarray:
    """Counter-clockwise vertices of the curve within ``tolerance``: (n, 2) float, mm (open ring)."""
    return points(curve, polyline_angles(curve, tolerance)[:-1])
