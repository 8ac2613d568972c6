"""Exact bounding boxes of rings: arcs reach past their end vertices (sheets, SVG viewBox, DXF $EXTMIN)."""

from __future__ import annotations

import numpy as np

from .arcfit import ArcRing  # noqa: F401 - the doctest's
from .bulge import segments

__all__ = ["ring_bounds", "rings_bounds"]

_DIRECTIONS = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])  # +x, +y, -x, -y


def ring_bounds(ring) -> np.ndarray:
    """``(xmin, ymin, xmax, ymax)`` of a closed ring, arcs included at their true extremes.

    Parameters
    ----------
    ring : ArcRing or (n, 2) float, mm
        Vertices with bulges (``bulge = tan(θ/4)``), or a plain polygon or open polyline.

    Returns
    -------
    (4,) float, mm

    Notes
    -----
    An arc of sweep θ spans the directions within θ/2 of ``u``, the unit vector from its centre
    to its midpoint ``M``.  If a direction ``d`` lies in that span, the arc reaches
    ``d·M + r·|d − u|²/2`` along it (since ``1 − cos ψ = |d − u|²/2``): no centre and no
    difference of large numbers, so it stays exact as the bulge goes to 0 and the radius to ∞.

    Examples
    --------
    >>> half = ArcRing(np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([1.0, 0.0]))
    >>> ring_bounds(half).tolist()
    [-1.0, 0.0, 1.0, 1.0]
    """
    return rings_bounds([ring])


def rings_bounds(rings) -> np.ndarray:
    """``(xmin, ymin, xmax, ymax)`` of several closed rings together: :func:`ring_bounds` of all
    of them in one pass over their joined arrays (a drawing's hundreds of dashes and letters
    cost one array operation, not one each): the extremes of their boxes, to the last bit.

    Parameters
    ----------
    rings : sequence of ArcRing or (n, 2) float, mm; at least one vertex in all

    Returns
    -------
    (4,) float, mm
    """
    pairs = [segments(ring) for ring in rings]
    v = np.concatenate([p[0] for p in pairs])
    bulge = np.concatenate([p[1] for p in pairs])
    # each vertex's successor on its own ring: the next one, and the ring's first after its last
    sizes = np.array([len(p[0]) for p in pairs], dtype=int)
    ends = np.cumsum(sizes)
    following = np.arange(1, len(v) + 1)
    following[ends[sizes > 0] - 1] = (ends - sizes)[sizes > 0]
    reach = v @ _DIRECTIONS.T  # (n, 4): every vertex along every direction
    arcs = np.nonzero(bulge)[0]
    if len(arcs):
        a, b, k = v[arcs], v[following[arcs]], bulge[arcs]
        chord = b - a
        length = np.hypot(chord[:, 0], chord[:, 1])
        left = np.column_stack([-chord[:, 1], chord[:, 0]]) / length[:, None]
        mid = (a + b) / 2 - left * (length * k / 2)[:, None]  # the sagitta is half the chord × bulge
        u = -left * np.sign(k)[:, None]
        gap2 = ((_DIRECTIONS[None, :, :] - u[:, None, :]) ** 2).sum(axis=2)  # (arcs, 4)
        span2 = 4 * k * k / (1 + k * k)  # (2 sin(|θ|/4))²: the gap at the span's edge
        inside = gap2 <= span2[:, None]
        # r·gap²/2 with r = chord (1 + k²) / (4|k|); inside the span gap²/|k| ≤ 4|k|, so dividing
        # there only never overflows, however small the bulge
        ratio = np.divide(gap2, np.abs(k)[:, None], out=np.zeros_like(gap2), where=inside)
        extreme = mid @ _DIRECTIONS.T + (length * (1 + k * k) / 8)[:, None] * ratio
        reach = np.vstack([reach, np.where(inside, extreme, -np.inf)])
    top = reach.max(axis=0)
    return np.array([-top[2], -top[3], top[0], top[1]]) + 0.0  # + 0.0: no -0.0 for a min of 0
