"""A toothed gear pair's geometry as the band measures it: its made outlines, centre distance and
the driver angles to measure at (even steps along the driver's pitch curve for the certificate),
and the follower's largest speed over any driver interval (what bounds how fast the play changes)."""

from __future__ import annotations

import numpy as np

from ..geometry.outline import turn_repeats
from ..mechanisms.base import Design
from ..mechanisms.registry import MECHANISMS
from .certify import PER_TOOTH
from .play import PairGeometry
from .written import written_paths

__all__ = ["pair_geometry", "follower_speed", "interval_maxima"]


def pair_geometry(design: Design, positions: int | None = None, *, written: bool = False) -> PairGeometry | None:
    """A toothed gear pair's geometry as the band measures it, at ``positions`` driver angles over
    one cycle (default: one per driver tooth, 12 to 48), and at any others the certificate asks
    for; ``None`` for any other design.  ``written``: the outlines as the files write them and
    a cutter runs them (:func:`~.written.written_paths`, what the band measures: the rings the
    paths, ``cut`` the cutter's radius), else the thinned outlines the mesh proof holds."""
    detail = design.detail
    teeth = getattr(detail, "teeth", None)
    if MECHANISMS[design.mechanism].play != "pair" or teeth is None:
        return None
    pair = detail.pitch.pair
    positions = positions or min(48, max(12, teeth.plan.teeth[0]))
    first = teeth.gears[0]
    rings, cut = written_paths(design) if written else (tuple(g.outline.outer for g in teeth.gears), 0.0)
    alpha = design.params.teeth.pressure_angle
    cycle = _one_pitch(pair, rings, teeth.plan.teeth) or pair.cycle
    ratio = follower_speed(pair.angle_map.slope, cycle)

    def at(phi1: np.ndarray) -> PairGeometry:
        arc = teeth.frames[0].arc(phi1 % (2 * np.pi))
        return PairGeometry(
            rings=rings,
            center_distance=pair.center_distance,
            phi1=phi1,
            phi2=pair.angle_map(phi1),
            r1=pair.gear1.r(phi1 % (2 * np.pi)),
            module=teeth.plan.module,
            pressure_angle=alpha,
            teeth=np.floor((arc - first.phase) / first.rack.pitch).astype(int) % first.teeth,
            at=at,
            ratio=ratio,
            slope=pair.angle_map.slope,
            cycle=cycle,
            first=start,
            cut=cut,
        )

    if cycle < pair.cycle:  # one pitch is the whole cycle: 12 positions on it, to start from too
        start = np.linspace(0.0, cycle, 12, endpoint=False)
        return at(start)
    frame = teeth.frames[0]
    turns = max(1, round(pair.cycle / (2 * np.pi)))
    perimeter = float(frame.arc(np.array([2 * np.pi]))[0])
    s = np.linspace(0.0, perimeter * turns, PER_TOOTH * first.teeth * turns, endpoint=False)
    start = frame.angle(s % perimeter) + 2 * np.pi * np.floor(s / perimeter)
    return at(np.linspace(0.0, pair.cycle, positions, endpoint=False))


def _one_pitch(pair, rings, teeth) -> float | None:
    """One pitch of the driver (rad) where that is the pair's whole cycle: a constant ratio
    k = z1/z2 and each outline its own vertices turned by a tooth (:func:`turn_repeats`; the
    arcs of a gear drawn tooth by tooth are fitted so), so that the pair at φ + 2π/z1 is the pair
    at φ, each gear a tooth on; None otherwise."""
    k = pair.angle_map.slope(np.linspace(0.0, pair.cycle, 64, endpoint=False))
    z1, z2 = teeth
    if np.ptp(k) > 1e-12 * abs(k[0]) or abs(k[0] * z2 / z1 - 1) > 1e-9:
        return None
    if any(turn_repeats(ring) % z for ring, z in zip(rings, teeth)):
        return None
    return 2 * np.pi / z1


def follower_speed(slope, cycle: float, samples: int = 8192):
    """ratio(lo, hi) -> (k, s, dk, ddk, s2) per driver interval [lo, hi] (rad; either end may pass
    the cycle): the largest follower speed k = dφ2/dφ1 there, the largest speed |I'| and
    acceleration |I''| of the unit instant centre I = k/(1+k)·(cos φ1, sin φ1) (its distance from
    gear 1's pivot over E, and that turning: ``s``, ``s2``) and the largest |dk/dφ1|, |d²k/dφ1²|,
    from ``samples`` even driver angles over the ``cycle``, each raised by the largest step
    between neighbours (what falls between two samples)."""
    grid = np.linspace(0.0, cycle, samples + 1)
    k = np.abs(slope(grid))
    unit = k / (1 + k)
    du = np.gradient(unit, grid)
    ddu = np.gradient(du, grid)
    speed = np.hypot(unit, du)
    accel = np.hypot(ddu - unit, 2 * du)
    dk = np.gradient(k, grid)
    ddk = np.abs(np.gradient(dk, grid))
    dk = np.abs(dk)
    return interval_maxima((k, speed, dk, ddk, accel), cycle / samples)


def interval_maxima(series, step: float):
    """(lo, hi) -> each of ``series`` (arrays sampled every ``step`` rad over a cycle, the last
    sample the first again) at its largest over each interval [lo, hi] (either end may pass the
    cycle), raised by the largest step between neighbours (what falls between two samples)."""
    steps = [float(np.max(np.abs(np.diff(a)))) for a in series]
    tables = [a[:-1] for a in series]
    samples = len(tables[0])

    def ratio(lo, hi) -> tuple[np.ndarray, ...]:
        lo, hi = np.atleast_1d(np.asarray(lo, dtype=float)), np.atleast_1d(np.asarray(hi, dtype=float))
        first = np.floor(lo / step).astype(int)
        last = np.ceil(hi / step).astype(int)
        out = [np.empty(len(lo)) for _ in tables]
        for i, (f, g) in enumerate(zip(first.tolist(), last.tolist())):
            idx = np.arange(f, max(g, f) + 1) % samples
            for o, t in zip(out, tables):
                o[i] = t[idx].max()
        return tuple(o + s for o, s in zip(out, steps))

    return ratio
