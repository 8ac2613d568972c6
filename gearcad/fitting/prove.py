"""The proven certificate of a pair's least play between the driver positions measured
(``output.certificate = "theorem"``; docs/fit.md, "How the least play is certified"): a lower
bound on the play over each driver interval derived from the geometry — a theorem, not the slope
estimate of :mod:`.certify` — refined where it cannot keep the margin (:func:`prove_play`).

The bound (:func:`_tube`).  In gear 1's frame gear 2 is placed by the driver angle φ and its own
turn t beyond the rolling angle: a point of it is X(φ, t) = C(φ) + R(φ + φ2(φ) + t)·q, C = E'(cos φ,
sin φ) its pivot.  Its speeds are ∂φX = ω·J(X − I) (ω = 1 + k, k = dφ2/dφ, I = k/(1+k)·C the
instant centre) and ∂tX = J(X − C); its second derivatives are bounded by |∂φφX| ≤ (|k'| + ω²)·ρ
+ ω·|I'|, |∂φtX| ≤ ω·|X − C| (or ω·ρ), |∂ttX| ≤ |X − C|, ρ = |X − I|.  Measured at a position c,
gear 2 turns freely over [t0 − Δc, t0 + Δc]; placed at (c, t0) the windows are apart.  Over the
box φ ∈ [c − h, c + h], t ∈ [t0 − Δ, t0 + Δ] no vertex of either window reaches an edge of the
other when, for each (vertex, edge), either its distance to the edge's segment less the most the
vertex can move, or its distance to the edge's line less the line's Taylor bound (first
derivatives exact at (c, t0), second bounded as above) stays ≥ 0; then the windows never touch
(two polygons moving continuously first meet vertex on edge), so every driver angle of the
interval has a free turn 2Δ wide, a play ≥ 2Δ·r2_min.  Gear 1's vertices against gear 2's moving
edges are the same bound in gear 2's frame (the relative motion inverted: the same ω, |I'|)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..geometry.outline import place_each
from .certify import Certificate
from .play import _WINDOW, PairGeometry, _signed_from, _windows, play_between

__all__ = ["prove_play"]


BUDGET = 12
"""The work budget: this many times the first positions."""
JAM_HALVINGS = 1
"""Once a measured position jams, the intervals about the least play are halved this many times
more to say how far short it falls (the verdict is settled)."""


@dataclass
class _Site:
    """One measured driver angle: the windows placed at the middle of gear 2's free turn there."""

    phi: float
    play: float
    t0: float = 0.0
    """Middle of the free turn (rad beyond the rolling angle)."""
    cap: float = -math.inf
    """Half the free turn (rad); −inf: jammed, or the windows not apart at ``t0``."""
    k: float = 0.0
    dk: float = 0.0
    arm: float = 0.0
    a: tuple | None = None
    """Gear 1's window: (vertices, edge starts, edge ends, polygon)."""
    b: tuple | None = None
    """Gear 2's window at (φ, t0): the same."""


BEYOND = 0.5
"""Gear 1's window for the bound reaches this many modules beyond gear 2's (:data:`~.play._WINDOW`):
the cut edges of the two windows then lie apart, and only the real outlines come near."""


def _edges(narrow, wide, other) -> tuple:
    """(the vertices of ``narrow``, the edge starts and ends of ``wide``, each vertex's distance
    to ``other``): a gear's narrow window's vertices, its wide window's edges."""
    xy = shapely.get_coordinates(narrow)
    rings = shapely.get_rings(shapely.get_parts(wide))
    ends, ring = shapely.get_coordinates(rings, return_index=True)
    same = ring[1:] == ring[:-1]
    return xy, ends[:-1][same], ends[1:][same], shapely.distance(shapely.points(xy), other)


def _sites(g: PairGeometry, offsets, spread: float, tol: float, reach: float) -> tuple[list[_Site], np.ndarray]:
    """Measure ``g``'s positions: the signed play and, where free, the windows as the bound needs them."""
    halves: list[np.ndarray] = []
    keep: dict = {}
    play, start = play_between(g, offsets, spread, tol, reach=reach, halves=halves, keep=keep)
    signed = _signed_from(g, play, start, offsets, spread, tol, reach=reach)
    up, down = halves
    t0 = start + (up - down) / 2
    free = np.flatnonzero(~np.isnan(play))
    sites = [_Site(float(p), float(s)) for p, s in zip(g.phi1, signed)]
    if not len(free):
        return sites, signed
    # each gear's window and a wider one, gear 2's placed at the middle of its free turn; the
    # bound checks each narrow window's vertices against the other's wide one (docs/fit.md)
    phi1, r1 = g.phi1[free], g.r1[free]
    contact = r1[:, None] * np.column_stack([np.cos(phi1), np.sin(phi1)])
    own = (r1 - g.center_distance)[:, None] * np.column_stack([np.cos(-g.phi2[free]), np.sin(-g.phi2[free])])
    wide_r = (_WINDOW + BEYOND) * g.module
    wide1 = _windows(g.rings[0], contact, wide_r, offsets[0], tol)
    wide2 = _windows(g.rings[1], own, wide_r, offsets[1], tol)
    xy, which = shapely.get_coordinates(wide2, return_index=True)
    pivot = (g.center_distance + spread) * np.column_stack([np.cos(phi1), np.sin(phi1)])
    wide2 = shapely.set_coordinates(wide2.copy(), place_each(xy, which, phi1 + g.phi2[free] + t0[free], pivot))
    discs = shapely.buffer(shapely.points(contact), _WINDOW * g.module, quad_segs=16)
    narrow1, narrow2 = shapely.intersection(wide1, discs), shapely.intersection(wide2, discs)
    apart = ~(shapely.intersects(narrow1, wide2) | shapely.intersects(narrow2, wide1))
    k = g.slope(phi1)
    dk = (g.slope(phi1 + 1e-5) - g.slope(phi1 - 1e-5)) / 2e-5
    for j, i in enumerate(free.tolist()):
        if not apart[j]:
            continue
        s = sites[i]
        s.t0, s.cap, s.k, s.dk = float(t0[i]), float((up[i] + down[i]) / 2), float(k[j]), float(dk[j])
        s.arm = float(g.center_distance - g.r1[i])
        s.a, s.b = _edges(narrow1[j], wide1[j], wide2[j]), _edges(narrow2[j], wide2[j], wide1[j])
    return sites, signed


def _one_sided_min(b: np.ndarray, c: np.ndarray, a) -> np.ndarray:
    """min of b·x + c·x²/2 over 0 ≤ x ≤ a (elementwise)."""
    end = b * a + 0.5 * c * a * a
    inside = (c > 0) & (b < 0) & (-b < c * a)
    vertex = np.full_like(end, np.inf)
    vertex[inside] = -0.5 * b[inside] ** 2 / c[inside]
    return np.minimum(np.minimum(end, 0.0), vertex)


def _tube(s: _Site, h: float, e: float, bounds) -> float:
    """The half-width Δ (rad) of gear 2's turn about ``s.t0`` proven free at every driver angle
    within ``h`` of ``s.phi`` (module docstring; −inf: none), gear 2's pivot ``e`` mm from gear 1's;
    ``bounds``: over the interval, the largest k, |I'|/E', |k'|, |k''| and |I''|/E'."""
    if s.a is None:
        return -math.inf
    kmax, unit_speed, dk, ddk, unit_accel = bounds
    w, sigma, sigma2 = 1.0 + kmax, e * unit_speed, e * unit_accel
    if w * h >= 0.5:
        return -math.inf
    cosp, sinp = math.cos(s.phi), math.sin(s.phi)
    centre = e * np.array([cosp, sinp])
    u, du = s.k / (1 + s.k), s.dk / (1 + s.k) ** 2
    instant = u * centre
    turning = e * np.array([du * cosp - u * sinp, du * sinp + u * cosp])  # I'(c)
    omega = 1.0 + s.k
    cap = s.cap
    best = cap
    for mine, other, moving in ((s.b, s.a, True), (s.a, s.b, False)):
        xy = mine[0]
        r0 = np.hypot(*(xy - centre).T)
        rho0 = np.hypot(*(xy - instant).T)
        if moving:  # gear 2's vertices: |X − C| is fixed; ρ grows with the motion itself
            rbar = r0
            rho = (rho0 + r0 * cap + sigma * h) / (1 - w * h)
        else:  # gear 1's, seen from gear 2: |w − I(φ)| and |w − C(φ)| move with φ only
            rbar = r0 + e * h
            rho = rho0 + sigma * h
        move = w * rho * h  # the most a vertex moves over the driver interval
        lip = (mine[3] - move) / rbar
        near = np.flatnonzero(lip < best)
        if not len(near):
            continue
        p, q = other[1], other[2]
        v = xy[near][:, None, :]
        seg = q - p
        length = np.maximum(np.hypot(*seg.T), 1e-300)
        unit = seg / length[:, None]
        normal = np.column_stack([-unit[:, 1], unit[:, 0]])
        rel = v - p[None]
        side = rel[..., 0] * normal[None, :, 0] + rel[..., 1] * normal[None, :, 1]
        ahead = rel[..., 0] * unit[None, :, 0] + rel[..., 1] * unit[None, :, 1]
        along = np.clip(ahead, 0.0, length[None])
        dseg = np.hypot(*(rel - along[..., None] * unit[None]).transpose(2, 0, 1))
        # two linear functionals, each a lower bound on the distance to the segment where
        # positive: the distance to its line (normal towards the vertex), and how far the vertex
        # lies past the segment's nearer end along it (negative while its foot is on it)
        rn, rb = rho[near][:, None], rbar[near][:, None]
        lip_pair = (dseg - move[near][:, None]) / rb
        vi, ei = np.nonzero(lip_pair < best)  # the pairs the segment's bound leaves open
        if not len(vi):
            best = min(best, float(np.min(lip_pair)))
            continue
        side, ahead, rel = side[vi, ei], ahead[vi, ei], rel[vi, ei]
        normal, unit, length = normal[ei], unit[ei], length[ei]
        v = xy[near][vi]
        rn, rb = rn[vi, 0], rb[vi, 0]
        n_line = np.where(side[:, None] < 0, -1.0, 1.0) * normal
        past = np.where(ahead > length, ahead - length, -ahead)
        n_end = np.where((ahead > length)[:, None], 1.0, -1.0) * unit
        xi = v - instant  # from the instant centre
        xc = v - centre  # from gear 2's pivot
        jxi = np.stack([-xi[:, 1], xi[:, 0]], -1)
        jxc = np.stack([-xc[:, 1], xc[:, 0]], -1)
        jturn = np.array([-turning[1], turning[0]])
        sign = 1.0 if moving else -1.0  # gear 1's vertices move against gear 2's edges
        accel = sign * s.dk * jxi - omega**2 * xi - sign * omega * jturn
        big = np.maximum(rn, rb)
        m_ppp = ddk * rn + dk * (3 * w * rn + 2 * sigma) + w * w * (w * rn + sigma) + w * (sigma2 + w * sigma)
        m_ppt = (dk + w * w) * big + w * sigma
        m_ptt = w * big
        m_ttt = rb
        # the two functionals (axis 0) over the four quadrants (axis 1: the signs of φ − c and
        # t − t0), all at once
        d = np.stack([n_line, n_end])[:, None]  # (2, 1, pairs, 2)
        f0 = np.stack([np.abs(side), past])[:, None]
        sp = np.array([1.0, 1.0, -1.0, -1.0])[None, :, None]
        st = np.array([1.0, -1.0, 1.0, -1.0])[None, :, None]
        f_p, f_t = sign * omega * (d * jxi).sum(-1), sign * (d * jxc).sum(-1)
        f_pp, f_tt = (d * accel).sum(-1), (d * -xc).sum(-1)
        f_pt = (d * (-omega * (xc if moving else xi))).sum(-1)
        # over a quadrant: lead − b·y − c·y² − d·y³ for a turn y ≤ Δ (each term a bound: the
        # turn's own curvature counted only where it closes the gap)
        f_p, f_pp = np.broadcast_arrays(sp * f_p, f_pp)
        lead = f0 + _one_sided_min(f_p, f_pp, h) - m_ppp * h**3 / 6
        b1 = np.maximum(0.0, -st * f_t) + np.maximum(0.0, -sp * st * f_pt) * h + m_ppt * h * h / 2
        c1 = np.maximum(0.0, -f_tt) / 2 + m_ptt * h / 2
        d1 = m_ttt / 6
        lo, hi = np.zeros_like(lead), np.full_like(lead, best)
        ok0 = lead >= 0
        okhi = lead - hi * (b1 + hi * (c1 + hi * d1)) >= 0
        for _ in range(12):
            mid = 0.5 * (lo + hi)
            good = lead - mid * (b1 + mid * (c1 + mid * d1)) >= 0
            lo, hi = np.where(good, mid, lo), np.where(good, hi, mid)
        safe = np.where(okhi, best, np.where(ok0, lo, -np.inf))  # (2, 4, pairs)
        pair = np.min(np.max(safe, axis=0), axis=0)
        pair = np.maximum(pair, lip_pair[vi, ei])
        best = min(best, float(np.min(lip_pair[lip_pair >= best], initial=best)))
        best = min(best, float(np.min(pair)))
    return best


def prove_play(g: PairGeometry, offsets, spread: float, tol: float, *, reach: float, margin: float, budget: int = 0):
    """The tight case's signed play, measured at ``g``'s positions and refined where the bound
    between them cannot settle the verdict: (geometry at every position measured, play there,
    :class:`Certificate`).

    Each measured position c covers the driver angles up to half way to its neighbours (h); its
    bound (:func:`_tube`) proves a free turn 2Δ wide over all of them, a play of at least
    2Δ·E/(1 + k_max) there, and neighbours' free turns overlap (the follower passes from one to
    the next).  A position whose bound falls under the margin (or whose free turn does not reach
    its neighbour's) has the intervals either side halved, until every one keeps the margin, one
    is narrower than a millionth of the cycle, or the budget (:data:`BUDGET` times the first
    positions) runs out: then the certificate is not ``proven``, names the interval and says the
    play short of the margin by the resolution, max(tol, 1e-4·m) (what a fit search then adds).  A
    measured position under the margin proves the pair jams; the intervals about the least play
    are then halved :data:`JAM_HALVINGS` times to say how far short it falls."""
    if g.first is not None:  # the certificate's own even start along the pitch curve
        g = g.at(g.first)
    n0 = len(g.phi1)
    budget = budget or BUDGET * n0
    narrowest = 1e-6 * g.cycle
    e = g.center_distance + spread
    geos, plays = [g], []
    sites, signed = _sites(g, offsets, spread, tol, reach)
    plays.append(signed)
    tubes: dict[int, tuple[float, float]] = {}  # site id -> (h, Δ) last computed
    jammed = 0
    while True:
        order = sorted(range(len(sites)), key=lambda i: sites[i].phi)
        phi = np.array([sites[i].phi for i in order])
        gap = (np.roll(phi, -1) - phi) % g.cycle  # to the next
        half = 0.5 * np.maximum(gap, np.roll(gap, 1))  # the wider half-interval either side
        table = g.ratio(phi - half, phi + half)
        bound = np.empty(len(order))
        delta = np.empty(len(order))
        for j, i in enumerate(order):
            h = float(half[j])
            if tubes.get(i, (None,))[0] != h:
                tubes[i] = (h, _tube(sites[i], h, e, tuple(float(t[j]) for t in table)))
            delta[j] = tubes[i][1]
            arm = min(sites[i].arm, g.center_distance / (1 + float(table[0][j])))
            bound[j] = 2 * delta[j] * arm if delta[j] >= 0 else -math.inf
        t0 = np.array([sites[i].t0 for i in order])
        joined = np.abs(np.roll(t0, -1) - t0) <= np.maximum(delta, 0) + np.maximum(np.roll(delta, -1), 0)
        measured = np.array([sites[i].play for i in order])
        least = float(np.min(measured))
        if least < margin:  # it jams, proven by a measured position: pin the least down a little
            jammed += 1
            low_site = measured < least + 8 * max(tol, 1e-4 * g.module)
            split = (low_site | np.roll(low_site, -1)) & (jammed <= JAM_HALVINGS)
        else:
            weak = bound < margin
            split = weak | np.roll(weak, -1) | ~joined  # the gaps either side of a weak position
        split &= gap > narrowest
        certified = float(np.min(np.where(joined, bound, -math.inf))) if least >= margin else least
        proven = least < margin or certified >= margin
        if not proven:  # not settled: short of the margin by the resolution (what a fit adds)
            certified = min(margin - max(tol, 1e-4 * g.module), least)
        if not split.any() or len(sites) + int(split.sum()) > budget:  # (at least one more each)
            worst = int(np.argmin(np.where(joined, bound, -math.inf)))
            cert = Certificate(
                lower=certified,
                positions=len(sites),
                slack=least - certified,
                proven=proven,
                open=(0.0, 0.0) if proven else (float(phi[worst] - half[worst]), float(phi[worst] + half[worst])),
                kind="theorem",
            )
            geo = _joined(geos)
            return geo, np.concatenate(plays), cert
        # how many new positions each gap takes: where a weak position's bound would keep the
        # margin over a narrower interval (looked at without measuring), enough to reach it
        pieces = np.where(split, 2, 1)
        if least >= margin:
            for j in np.flatnonzero(bound < margin):
                i, h = order[j], float(half[j])
                arm = g.center_distance / (1 + float(table[0][j]))
                for _ in range(6):
                    h /= 2
                    near = tuple(float(t[0]) for t in g.ratio(np.array([phi[j] - h]), np.array([phi[j] + h])))
                    if 2 * _tube(sites[i], h, e, near) * min(sites[i].arm, arm) >= margin:
                        break
                need = int(min(16, math.ceil(float(half[j]) / h)))
                for gj in (j, (j - 1) % len(order)):
                    pieces[gj] = max(pieces[gj], need if split[gj] else 1)
        steps = [phi[j] + gap[j] * np.arange(1, pieces[j]) / pieces[j] for j in np.flatnonzero(pieces > 1)]
        mids = np.concatenate(steps) % g.cycle
        if len(sites) + len(mids) > budget:  # the budget: say what is left open
            mids = (phi[split] + gap[split] / 2) % g.cycle
            if len(sites) + len(mids) > budget:
                budget = len(sites)  # the next look ends it
                continue
        sub = g.at(mids)
        more, signed = _sites(sub, offsets, spread, tol, reach)
        sites += more
        geos.append(sub)
        plays.append(signed)


def _joined(parts: list[PairGeometry]) -> PairGeometry:
    cat = np.concatenate
    g = parts[0]
    return replace(
        g,
        phi1=cat([p.phi1 for p in parts]),
        phi2=cat([p.phi2 for p in parts]),
        r1=cat([p.r1 for p in parts]),
        teeth=cat([p.teeth for p in parts]),
    )
