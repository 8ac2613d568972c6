"""The bound between two driver positions of the proven certificate (:mod:`.prove`;
docs/fit.md, "How the least play is certified"): the largest turn of gear 2 proven free over a
driver interval about a measured position (:func:`tube`).

In gear 1's frame gear 2 is placed by the driver angle φ and its own turn t beyond the rolling
angle: a point of it is X(φ, t) = C(φ) + R(φ + φ2(φ) + t)·q, C = E'(cos φ, sin φ) its pivot.  Its
speeds are ∂φX = ω·J(X − I) (ω = 1 + k, k = dφ2/dφ, I = k/(1+k)·C the instant centre) and ∂tX =
J(X − C); its second derivatives are exact at the position and its third bounded from |k'|, |k''|,
ω, |I'|, |I''| and ρ = |X − I|.  Measured at a position c, gear 2 turns freely over [t0 − Δc, t0 +
Δc]; placed at (c, t0) the windows are apart.  Over the box φ ∈ [c − h, c + h], t ∈ [t0 − Δ, t0 +
Δ] no vertex of either window reaches an edge of the other when, for each (vertex, edge), either
its distance to the edge's segment less the most the vertex can move, or one of a few linear
functionals of its place that bound that distance from below (:func:`_safe_turn`) stays ≥ 0 by
its Taylor bound; then the windows never touch (two polygons moving continuously first meet
vertex on edge, and not at a vertex that is reflex: :func:`.corners.corners`), so every driver angle of
the interval has a free turn 2Δ wide.  Gear 1's vertices against gear 2's moving edges are the
same bound in gear 2's frame (the relative motion inverted: the same ω, |I'|)."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Site", "tube", "tubes"]


@dataclass
class Site:
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
    """Gear 1's window: (vertices, edge starts, edge ends, (a k-d tree of the edges' pieces'
    middles, their largest half-length, each piece's edge), the vertices' normals)
    (:func:`.corners.outlines`)."""
    b: tuple | None = None
    """Gear 2's window at (φ, t0): the same."""
    pivot: np.ndarray | None = None
    """A general motion's (:mod:`.moving`): gear 2's pivot C at φ in gear 1's frame (mm); None: a
    gear pair's, E'(cos φ, sin φ)."""
    instant: np.ndarray | None = None
    """With ``pivot``: the instant centre I there (mm)."""
    turning: np.ndarray | None = None
    """With ``pivot``: I' there (mm/rad)."""


def _one_sided_min(b: np.ndarray, c: np.ndarray, a) -> np.ndarray:
    """min of b·x + c·x²/2 over 0 ≤ x ≤ a (elementwise)."""
    end = b * a + 0.5 * c * a * a
    inside = (c > 0) & (b < 0) & (-b < c * a)
    vertex = np.full_like(end, np.inf)
    vertex[inside] = -0.5 * b[inside] ** 2 / c[inside]
    return np.minimum(np.minimum(end, 0.0), vertex)


def _dot(a, b):
    """Dot products of 2-vectors along the last axis (what ``np.sum(a * b, -1)`` gives, bit for
    bit, without a reduction over an axis of two)."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _closest_on(x, a, b):
    """The point of each segment [a, b] nearest each x (rows)."""
    ab = b - a
    t = np.clip(_dot(x - a, ab) / np.maximum(_dot(ab, ab), 1e-300), 0.0, 1.0)
    return a + t[:, None] * ab


def _parting(a0, a1, p, q, fallback, fallback_at):
    """(unit normals, points on [p, q]): for each pair of segments [a0, a1] and [p, q] the
    direction from the nearest point of [p, q] to the nearest of [a0, a1] and that point — [p, q]
    lies behind the line through it across that direction (nearest points of two convex sets), so
    n·(x − point) bounds any x's distance to [p, q] from below where positive.  Where they cross
    (or touch), ``fallback`` and ``fallback_at``."""
    cands = [
        (a0, _closest_on(a0, p, q)),
        (a1, _closest_on(a1, p, q)),
        (_closest_on(p, a0, a1), p),
        (_closest_on(q, a0, a1), q),
    ]
    on_path = np.stack([c[0] for c in cands])
    on_seg = np.stack([c[1] for c in cands])
    gaps = np.hypot(*(on_path - on_seg).transpose(2, 0, 1))
    best = np.argmin(gaps, axis=0)
    rows = np.arange(len(best))
    gap = gaps[best, rows]
    at = on_seg[best, rows]
    n = (on_path[best, rows] - at) / np.maximum(gap, 1e-300)[:, None]
    cross = (gap < 1e-12) | _crossing(a0, a1, p, q)
    return np.where(cross[:, None], fallback, n), np.where(cross[:, None], fallback_at, at)


def _crossing(a0, a1, p, q):
    """Whether each pair of segments [a0, a1], [p, q] crosses."""

    def orient(o, x, y):
        return (x[:, 0] - o[:, 0]) * (y[:, 1] - o[:, 1]) - (x[:, 1] - o[:, 1]) * (y[:, 0] - o[:, 0])

    return (orient(a0, a1, p) * orient(a0, a1, q) < 0) & (orient(p, q, a0) * orient(p, q, a1) < 0)


def _safe_turn(d, f0, derivs, terms, h: float, best: float) -> np.ndarray:
    """For each (vertex, edge) pair, the largest turn Δ ≤ ``best`` (rad) of gear 2 about t0 over
    which one of the linear functionals ``d`` (directions, (functionals, pairs, 2); values at (c,
    t0) ``f0``) stays ≥ 0 in every quadrant of the box |φ − c| ≤ h, |t − t0| ≤ Δ (−inf: none).
    ``derivs``: the vertex's ∂φ, ∂t, ∂φφ, ∂tt, ∂φt at (c, t0); ``terms``: the third derivatives'
    bounds ∂φφφ, ∂φφt, ∂φtt, ∂ttt.

    Over a quadrant a functional is at least lead − b·y − c·y² − e·y³ for a turn y ≤ Δ (its Taylor
    polynomial, each term a bound: the turn's own curvature counted only where it closes the gap;
    the driver's part minimised over 0 ≤ ±(φ − c) ≤ h).  That polynomial is increasing in y, so
    with Y = min(best, lead/b) ≥ its root, y = lead/(b + c·Y + e·Y²) keeps it ≥ 0."""
    v_p, v_t, v_pp, v_tt, v_pt = derivs
    m_ppp, m_ppt, m_ptt, m_ttt = terms
    d = d[:, None]  # (functionals, 1, pairs, 2)
    f0 = f0[:, None]
    sp = np.array([1.0, 1.0, -1.0, -1.0])[None, :, None]  # the quadrants: the signs of φ − c
    st = np.array([1.0, -1.0, 1.0, -1.0])[None, :, None]  # and of t − t0
    f_p, f_t = _dot(d, v_p), _dot(d, v_t)
    f_pp, f_tt, f_pt = _dot(d, v_pp), _dot(d, v_tt), _dot(d, v_pt)
    # the driver's part depends on the sign of φ − c alone: worked out for two quadrants, not four
    f_p, f_pp = np.broadcast_arrays(sp[:, 1:3] * f_p, f_pp)
    lead = (f0 + _one_sided_min(f_p, f_pp, h) - m_ppp * h**3 / 6)[:, [0, 0, 1, 1]]
    b1 = np.maximum(0.0, -st * f_t) + np.maximum(0.0, -sp * st * f_pt) * h + m_ppt * h * h / 2
    c1 = np.maximum(0.0, -f_tt) / 2 + m_ptt * h / 2
    e1 = m_ttt / 6
    with np.errstate(divide="ignore", invalid="ignore"):
        top = np.where(b1 > 0, np.minimum(best, lead / b1), best)
        turn = np.minimum(best, lead / (b1 + top * (c1 + top * e1)))
    safe = np.where(lead >= 0, np.nan_to_num(turn, nan=best, posinf=best), -np.inf)
    return np.min(np.max(safe, axis=0), axis=0)


def tube(s: Site, h: float, e: float, bounds, slope: float = 0.0) -> float:
    """The half-width Δ (rad) of gear 2's turn about ``s.t0 + slope·(φ − s.phi)`` proven free at
    every driver angle φ within ``h`` of ``s.phi`` (module docstring; −inf: none), gear 2's pivot
    ``e`` mm from gear 1's; ``bounds``: over the interval, the largest k, |I'|/E', |k'|, |k''| and
    |I''|/E'.  A site of a general motion (its ``pivot`` given, :mod:`.moving`) carries C, I and
    I' itself, ``e`` is not used, and ``bounds`` are the largest |ω| − 1, |I'|, |ω'|, |ω''|, |I''|
    (mm) and sixth the pivot's largest speed |C'| (a gear pair's: E'; it bounds how far gear 1's
    vertices move from gear 2's pivot).

    ``slope``: the box is sheared to follow the free turn's middle as it drifts with the driver
    (any slope gives a proof; the drift's own, from the neighbours, the widest Δ).  In u = φ − c,
    y = t − t0 − slope·u the vertex's derivatives are ∂u = ∂φ + s·∂t, ∂uu = ∂φφ + 2s·∂φt + s²·∂tt,
    ∂uy = ∂φt + s·∂tt, ∂yy = ∂tt, and its third derivatives' bounds grow alike (|s| for s); its
    turn over the box reaches |s|·h + Δ."""
    return float(tubes([s], [h], e, [tuple(bounds)], [slope])[0])


def tubes(sites, h, e: float, bounds, slope) -> np.ndarray:
    """:func:`tube` for many sites at once, each over its own interval: ``h``, ``slope`` one
    each, ``bounds`` a row each (the work of all in a few array operations, not a loop of small
    ones)."""
    n = len(sites)
    out = np.full(n, -math.inf)
    if not n:
        return out
    h = np.broadcast_to(np.asarray(h, dtype=float), (n,))
    slope = np.broadcast_to(np.asarray(slope, dtype=float), (n,))
    bounds = np.asarray(bounds, dtype=float).reshape(n, -1)
    w = 1.0 + bounds[:, 0]
    live = np.flatnonzero(np.array([s.a is not None for s in sites]) & (w * h < 0.5))
    if not len(live):
        return out
    sites = [sites[i] for i in live]
    h, slope, w, (_, unit_speed, dk, ddk, unit_accel, *more) = h[live], slope[live], w[live], bounds[live].T
    general = np.array([s.pivot is not None for s in sites])
    phi, k, dk0 = (np.array([getattr(s, f) for s in sites]) for f in ("phi", "k", "dk"))
    cosp, sinp = np.cos(phi), np.sin(phi)
    u, du = k / (1 + k), dk0 / (1 + k) ** 2
    centre = e * np.column_stack([cosp, sinp])
    instant = u[:, None] * centre
    turning = e * np.column_stack([du * cosp - u * sinp, du * sinp + u * cosp])  # I'(c)
    sigma, sigma2, pivot_speed = e * unit_speed, e * unit_accel, np.full(len(sites), float(e))
    if general.any():  # a general motion's sites carry C, I and I' (and the bounds are in mm)
        for name, field in ((centre, "pivot"), (instant, "instant"), (turning, "turning")):
            name[general] = [getattr(s, field) for s in np.array(sites, dtype=object)[general]]
        sigma, sigma2 = np.where(general, unit_speed, sigma), np.where(general, unit_accel, sigma2)
        pivot_speed = np.where(general, more[0] if more else np.nan, pivot_speed)
    omega = 1.0 + k
    cap = np.array([s.cap for s in sites])
    best = cap.copy()
    a = np.abs(slope)
    for moving in (True, False):
        mine = [s.b if moving else s.a for s in sites]
        other = [s.a if moving else s.b for s in sites]
        sizes = np.array([len(m[0]) for m in mine])
        sv = np.repeat(np.arange(len(sites)), sizes)  # each vertex's site
        xy = np.concatenate([m[0] for m in mine])
        own = np.concatenate([m[4] for m in mine])
        r0 = np.hypot(*(xy - centre[sv]).T)
        rho0 = np.hypot(*(xy - instant[sv]).T)
        hv, av, wv = h[sv], a[sv], w[sv]
        if moving:  # gear 2's vertices: |X − C| is fixed; ρ grows with the motion itself
            rbar = r0
            rho = (rho0 + r0 * (cap[sv] + av * hv) + sigma[sv] * hv) / (1 - wv * hv)
        else:  # gear 1's, seen from gear 2: |w − I(φ)| and |w − C(φ)| move with φ only
            rbar = r0 + pivot_speed[sv] * hv
            rho = rho0 + sigma[sv] * hv
        rbar = np.maximum(rbar, 1e-12)  # (a vertex on gear 2's pivot: its turn does not move it)
        move = (wv * rho + rbar * av) * hv  # the most a vertex moves over the driver interval (sheared)
        # the (vertex, edge) pairs the segment's bound leaves open: the edge within the vertex's
        # reach, best·r̄ + its move (a k-d tree query a site, not every pair: the edges with a
        # piece's middle within the reach and a half-length, more than needed (an edge may come
        # twice), the exact test below keeps those within; a vertex with no edge so near is kept
        # apart over the whole box by its distance alone)
        bv = best[sv]
        reach = np.where(np.isfinite(bv), bv * rbar + move, np.inf)
        reach = reach * (1 + 1e-9) + 1e-12  # the tree's distance and ours may differ in the last bits
        first = np.concatenate([[0], np.cumsum(sizes)])
        vis, ps, qs = [], [], []
        for j in np.flatnonzero((best > -np.inf) & (sizes > 0)).tolist():  # (−inf: no turn is left to prove)
            rows = np.arange(first[j], first[j + 1])
            tree, half, edge = other[j][3]
            near = tree.query_ball_point(xy[rows], reach[rows] + half)
            counts = np.fromiter(map(len, near), dtype=np.intp, count=len(rows))
            vi = np.repeat(np.arange(len(rows)), counts)
            ei = edge[np.fromiter(itertools.chain.from_iterable(near), dtype=np.intp, count=int(counts.sum()))]
            vis.append(rows[vi])
            ps.append(other[j][1][ei])
            qs.append(other[j][2][ei])
        if not vis:
            continue
        vi = np.concatenate(vis)
        if not len(vi):
            continue
        p, q = np.concatenate(ps), np.concatenate(qs)
        sp = sv[vi]  # each pair's site
        seg = q - p
        length = np.maximum(np.hypot(*seg.T), 1e-300)
        unit = seg / length[:, None]
        normal = np.column_stack([-unit[:, 1], unit[:, 0]])
        v = xy[vi]
        rx, ry = v[:, 0] - p[:, 0], v[:, 1] - p[:, 1]
        side = rx * normal[:, 0] + ry * normal[:, 1]
        ahead = rx * unit[:, 0] + ry * unit[:, 1]
        beyond = np.maximum(ahead - length, 0.0) + np.maximum(-ahead, 0.0)
        dseg = np.hypot(side, beyond)
        rn, rb = rho[vi], rbar[vi]
        lip_pair = (dseg - move[vi]) / rb
        open_ = lip_pair < best[sp]
        if not np.any(open_):
            continue
        vi, sp, side, ahead, lip_pair = vi[open_], sp[open_], side[open_], ahead[open_], lip_pair[open_]
        p, normal, unit, length, v, rn, rb = (x[open_] for x in (p, normal, unit, length, v, rn, rb))
        hp, ap, wp, bp = h[sp], a[sp], w[sp], best[sp]
        n_line = np.where(side[:, None] < 0, -1.0, 1.0) * normal
        past = np.where(ahead > length, ahead - length, -ahead)
        n_end = np.where((ahead > length)[:, None], 1.0, -1.0) * unit
        xi = v - instant[sp]  # from the instant centre
        xc = v - centre[sp]  # from gear 2's pivot
        jxi = np.stack([-xi[:, 1], xi[:, 0]], -1)
        jxc = np.stack([-xc[:, 1], xc[:, 0]], -1)
        jturn = np.column_stack([-turning[sp, 1], turning[sp, 0]])
        sign = 1.0 if moving else -1.0  # gear 1's vertices move against gear 2's edges
        om = omega[sp][:, None]
        accel = sign * dk0[sp][:, None] * jxi - om**2 * xi - sign * om * jturn
        big = np.maximum(rn, rb)
        sg, sg2 = sigma[sp], sigma2[sp]
        m_ppp = ddk[sp] * rn + dk[sp] * (3 * wp * rn + 2 * sg) + wp * wp * (wp * rn + sg) + wp * (sg2 + wp * sg)
        m_ppt = (dk[sp] + wp * wp) * big + wp * sg
        m_ptt = wp * big
        m_ttt = rb
        # the sheared box's derivatives (tube's docstring; a slope of 0 leaves them as they are)
        m_ppp = m_ppp + ap * (3 * m_ppt + ap * (3 * m_ptt + ap * m_ttt))
        m_ppt = m_ppt + ap * (2 * m_ptt + ap * m_ttt)
        m_ptt = m_ptt + ap * m_ttt
        # linear functionals of the vertex's place, each a lower bound on its distance to the
        # segment where positive (the segment lies behind the line across the functional's
        # direction): the distance to the segment's line; how far the vertex lies past the
        # segment's nearer end along it; and, exact at (c, t0), the distance across the direction
        # from its nearest point on the segment to the vertex (past a polygon's corner neither of
        # the first two holds for long)
        foot = p + np.clip(ahead, 0.0, length)[:, None] * unit
        gap = np.maximum(np.hypot(*(v - foot).T), 1e-300)
        n_near = (v - foot) / gap[:, None]
        s_ = slope[sp][:, None]
        v_t, v_tt, v_pt = sign * jxc, -xc, -om * (xc if moving else xi)
        v_p = sign * om * jxi + s_ * v_t
        accel = accel + s_ * (2 * v_pt + s_ * v_tt)
        derivs = (v_p, v_t, accel, v_tt, v_pt + s_ * v_tt)
        terms = (m_ppp, m_ppt, m_ptt, m_ttt)
        # the exact direction first: most pairs it keeps apart over the whole turn sought
        pair = _safe_turn(n_near[None], gap[None], derivs, terms, hp, bp)
        o = np.flatnonzero(pair < bp)
        if len(o):
            # the vertex's own outline's normal, either way: where a corner of the mate slides
            # past the vertex, the gap across the vertex's own flank, not across the corner's
            # short edges, is what the motion closes slowly
            n_own = own[vi[o]]
            lo = np.minimum(_dot(n_own, p[o]), _dot(n_own, p[o] + length[o, None] * unit[o]))
            hi = np.maximum(_dot(n_own, p[o]), _dot(n_own, p[o] + length[o, None] * unit[o]))
            at_v = _dot(n_own, v[o])
            flip = hi - at_v > at_v - lo  # the segment lies on the normal's side: turn it round
            n_own = np.where(flip[:, None], -n_own, n_own)
            pair[o] = _safe_turn(
                np.stack([n_line[o], n_end[o], n_near[o], n_own]),
                np.stack([np.abs(side[o]), past[o], gap[o], np.where(flip, lo - at_v, at_v - hi)]),
                tuple(x[o] for x in derivs),
                tuple(x[o] for x in terms),
                hp[o],
                bp[o],
            )
        o = np.flatnonzero(pair < bp)
        if len(o):
            # two more where those leave it open, one for each way the driver turns: the
            # direction that parts the vertex's path over the interval (its chord, to second
            # order) from the segment, where they do not cross (a vertex that slides past the
            # segment's end within a few µm)
            # and two for each way gear 2 turns: its chord over the turn sought (a vertex that
            # the turn carries along an edge and past its end)
            ends = (p[o], p[o] + length[o, None] * unit[o])
            ho = hp[o][:, None]
            y = np.where(np.isfinite(bp[o]), bp[o], cap[sp[o]])[:, None]
            ways = [
                _parting(v[o], v[o] + w_ * ho * derivs[0][o] + 0.5 * ho * ho * accel[o], *ends, n_near[o], foot[o])
                for w_ in (1.0, -1.0)
            ] + [
                _parting(v[o], v[o] + w_ * y * v_t[o] + 0.5 * y * y * v_tt[o], *ends, n_near[o], foot[o])
                for w_ in (1.0, -1.0)
            ]
            more_turn = _safe_turn(
                np.stack([n for n, _ in ways]),
                np.stack([_dot(n, v[o] - at) for n, at in ways]),
                tuple(x[o] for x in derivs),
                tuple(x[o] for x in terms),
                hp[o],
                bp[o],
            )
            pair[o] = np.maximum(pair[o], more_turn)
        pair = np.maximum(pair, lip_pair)
        np.minimum.at(best, sp, pair)
    out[live] = best
    return out
