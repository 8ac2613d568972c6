"""Bulges: a closed ring's segment k, from vertex k to vertex k + 1, is a circular arc whose bulge
is tan(θ/4), θ its signed sweep (positive counter-clockwise), or a line where the bulge is 0 (the
DXF LWPOLYLINE convention, ezdxf's ``math/bulge.py``).  Every reader and writer of arcs takes
its arrays, sweeps, radii and centres from here.

>>> v, b = segments(np.array([[1.0, 0.0], [-1.0, 0.0]]))
>>> b.tolist()
[0.0, 0.0]
>>> float(sweep(1.0)), float(radius(2.0, sweep(1.0)))  # a half turn on a chord of 2: radius 1
(3.141592653589793, 1.0)
"""

from __future__ import annotations

import numpy as np

__all__ = ["segments", "sweep", "radius", "centres"]


def segments(ring) -> tuple[np.ndarray, np.ndarray]:
    """The vertices ((n, 2) float, mm) and bulges ((n,) float) of a ring: an ``ArcRing``, or a
    plain (n, 2) polygon whose segments are all lines."""
    bulges = getattr(ring, "bulges", None)
    if bulges is not None:
        return np.asarray(ring.vertices, dtype=float), np.asarray(bulges, dtype=float)
    v = np.asarray(ring, dtype=float)
    return v, np.zeros(len(v))


def sweep(bulges):
    """The signed sweep (rad) of arcs of these bulges: 4·atan(bulge)."""
    return 4 * np.arctan(bulges)


def radius(chord, sweeps):
    """The radius (mm) of arcs of signed ``sweeps`` (rad, not 0) on chords of length ``chord``
    (mm): chord / (2·|sin(θ/2)|)."""
    return chord / (2 * np.abs(np.sin(sweeps / 2)))


def centres(a: np.ndarray, b: np.ndarray, sweeps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centres ((m, 2) float, mm) and radii ((m,) float, mm) of the arcs from ``a`` to ``b``
    ((m, 2) each) of signed ``sweeps`` (rad, not 0): from the chord's middle along its left
    normal by r·cos(θ/2), to the left for a counter-clockwise arc."""
    chord = np.hypot(*(b - a).T)
    r = radius(chord, sweeps)
    normal = np.column_stack([-(b - a)[:, 1], (b - a)[:, 0]]) / chord[:, None]
    return (a + b) / 2 + normal * (r * np.cos(sweeps / 2) * np.sign(sweeps))[:, None], r
