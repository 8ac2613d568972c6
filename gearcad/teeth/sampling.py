"""Adaptive sampling of many parametric curves at once, from one tolerance.

Every curve is split into a few intervals; each round evaluates the quarter points of all of
them in one call, keeps the intervals whose midpoint and quarter points lie within the
tolerance of their chord and halves the rest, whose halves' midpoints are those quarter points
(so a later round evaluates two new points per interval, not three).  The result has no more
vertices than the tolerance needs, wherever the curvature is.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np

from ..errors import DesignError

__all__ = ["sample_curves", "Stopped"]

Curves = Callable[[np.ndarray, np.ndarray], np.ndarray]


class Stopped(Exception):
    """The sampling was called off (``stop`` set): other work of the same design failed, so
    this result would not be used."""


def _distance_to_chord(p, a, b):
    """Distances (k, n) of points p (k, n, 2) from the chords a → b (n, 2)."""
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    cross = np.abs(d[:, 0] * (p[..., 1] - a[:, 1]) - d[:, 1] * (p[..., 0] - a[:, 0]))
    far = np.hypot(p[..., 0] - a[:, 0], p[..., 1] - a[:, 1])
    return np.where(length > 1e-300, cross / np.where(length > 1e-300, length, 1.0), far)


MAX_POINTS = 400_000
"""More points than this for one curve set means it bends more sharply than any part can be
made: the work is refused rather than refined without end (bounded time and memory).  A caller
sampling several sets in one call (a gear's six rack parts) passes this times their number."""


def _too_many(max_points: int) -> DesignError:
    return DesignError(
        f"the tooth outline would need more than {max_points:,} points within the tolerance: the pitch "
        "curve bends too sharply for these teeth; use a coarser output.tolerance, or smaller or fewer teeth "
        "(teeth.module / teeth.count)"
    )


def _per_curve(func: Curves, t0, t1, ids, t, p) -> list[np.ndarray]:
    """The kept chords' start points (curve ``ids``, parameter ``t``, point ``p``) in order along
    each curve from t0 to t1, each curve's end after its last point, one view per curve."""
    n = len(t0)
    order = np.lexsort((t * np.sign(t1 - t0)[ids], ids))  # along each curve, from t0 to t1
    ids, p = ids[order], p[order]
    ends = func(np.arange(n), t1)
    cuts = np.searchsorted(ids, np.arange(n + 1))
    return np.split(np.insert(p, cuts[1:], ends, axis=0), cuts[1:-1] + np.arange(1, n))


def sample_curves(
    func: Curves,
    t0,
    t1,
    tolerance: float,
    *,
    start: int = 4,
    max_rounds: int = 40,
    max_points: int = MAX_POINTS,
    stop: threading.Event | None = None,
) -> list[np.ndarray]:
    """Sample curves ``func(ids, t) -> (n, 2)`` on their intervals [t0[i], t1[i]].

    Returns, for each curve i, its points (m_i, 2) from t0[i] to t1[i] inclusive, with every
    chord within ``tolerance`` of the curve at the chord's parameter midpoint and at its
    quarter points (so an inflexion inside a chord is not missed).  Raises
    :class:`DesignError` when that would take more than ``max_points`` points, and
    :class:`Stopped` once ``stop`` is set (checked every round).
    """
    t0, t1 = np.asarray(t0, dtype=float), np.asarray(t1, dtype=float)
    n = len(t0)
    if n == 0:
        return []
    frac = np.linspace(0.0, 1.0, start + 1)
    ids = np.repeat(np.arange(n), start)
    a = (t0[:, None] + (t1 - t0)[:, None] * frac[None, :-1]).ravel()
    b = (t0[:, None] + (t1 - t0)[:, None] * frac[None, 1:]).ravel()
    pa, pb = func(ids, a), func(ids, b)
    kept_ids, kept_t, kept_p = [], [], []
    pm = None  # the points at the midpoints, once known (a half's midpoint is a quarter point)
    for _ in range(max_rounds):
        if stop is not None and stop.is_set():
            raise Stopped
        m = 0.5 * (a + b)
        ask = [0.5 * (a + m), 0.5 * (m + b)] + ([m] if pm is None else [])
        pq = func(np.tile(ids, len(ask)), np.concatenate(ask)).reshape(len(ask), len(a), 2)
        p1, p3 = pq[0], pq[1]
        pm = pq[2] if pm is None else pm
        dev = np.max(_distance_to_chord(np.stack([p1, pm, p3]), pa, pb), axis=0)
        ok = dev <= tolerance
        kept_ids.append(ids[ok])
        kept_t.append(a[ok])
        kept_p.append(pa[ok])
        if np.all(ok):
            break
        bad = ~ok
        if 2 * np.count_nonzero(bad) + sum(len(k) for k in kept_t) > max_points:
            raise _too_many(max_points)
        ids = np.concatenate([ids[bad], ids[bad]])
        a, b = np.concatenate([a[bad], m[bad]]), np.concatenate([m[bad], b[bad]])
        pa, pb = np.concatenate([pa[bad], pm[bad]]), np.concatenate([pm[bad], pb[bad]])
        pm = np.concatenate([p1[bad], p3[bad]])
    else:  # the round limit: keep what is left rather than loop forever
        kept_ids.append(ids)
        kept_t.append(a)
        kept_p.append(pa)
    return _per_curve(func, t0, t1, np.concatenate(kept_ids), np.concatenate(kept_t), np.concatenate(kept_p))
