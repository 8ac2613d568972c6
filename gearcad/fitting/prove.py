"""The proven certificate of a pair's least play between the driver positions measured
(``output.certificate = "theorem"``, the default; docs/fit.md, "How the least play is
certified"): the bound of :mod:`.tube` over each driver interval — a theorem, not the slope
estimate of :mod:`.certify` — refined where it cannot keep the margin (:func:`prove_play`)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import shapely

from ..geometry.outline import place_each
from .certify import Certificate
from .corners import outlines
from .play import _WINDOW, PairGeometry, _signed_from, _windows, contacts, play_between, signed_play
from .tube import Site
from .tube import tubes as tube_of

__all__ = ["Measures", "PAIRS", "prove_lazily", "prove_play"]


BUDGET = 12
"""The work budget: this many times the first positions."""
JAM_HALVINGS = 1
"""Once a measured position jams, the intervals about the least play are halved this many times
more to say how far short it falls (the verdict is settled)."""


SLACK = 0.001
"""Once the margin is proven, the positions whose bound lies more than this (mm) under the least
measured play have their intervals halved too, :data:`TIGHTEN` of the lowest bounds at a time,
for up to :data:`TIGHT_BUDGET` times the first positions more than it took: the least
play is then known to a micrometre — between the proven lower bound and the least
measured lies the truth — not only shown to keep the margin (issue 33: the report within 1 µm
of the written files); the certificate's ``slack`` says how near it came."""
TIGHTEN = 8
TIGHT_BUDGET = 1

BEYOND = 0.5
"""Gear 1's window for the bound reaches this many modules beyond gear 2's (:data:`~.play._WINDOW`):
the cut edges of the two windows then lie apart, and only the real outlines come near."""


def _sites(g: PairGeometry, offsets, spread: float, tol: float, reach: float) -> tuple[list[Site], np.ndarray]:
    """Measure ``g``'s positions: the signed play and, where free, the windows as the bound needs them.

    Each gear's window (:data:`~.play._WINDOW` modules about the contact, what the play is
    measured on) is cut from a wider one (:data:`BEYOND` more), made once: the bound checks each
    narrow window's vertices against the other's wide one (docs/fit.md)."""
    contact, own = contacts(g)
    wide_r = (_WINDOW + BEYOND) * g.module
    wide1 = _windows(g.rings[0], contact, wide_r, offsets[0], tol)
    wide2 = _windows(g.rings[1], own, wide_r, offsets[1], tol)
    narrow1, narrow2 = narrow_windows(wide1, contact, g.module), narrow_windows(wide2, own, g.module)
    halves: list[np.ndarray] = []
    play, start = play_between(g, offsets, spread, tol, reach=reach, halves=halves, windows=(narrow1, narrow2))
    signed = _signed_from(g, play, start, offsets, spread, tol, reach=reach)
    up, down = halves
    t0 = start + (up - down) / 2
    free = np.flatnonzero(~np.isnan(play))
    sites = [Site(float(p), float(s)) for p, s in zip(g.phi1, signed)]
    if not len(free):
        return sites, signed
    # gear 2's windows placed at the middle of its free turn
    phi1 = g.phi1[free]
    pivot = (g.center_distance + spread) * np.column_stack([np.cos(phi1), np.sin(phi1)])
    turned = phi1 + g.phi2[free] + t0[free]
    wide1, narrow1 = wide1[free], narrow1[free]
    wide2, narrow2 = (_placed(w[free], turned, pivot) for w in (wide2, narrow2))
    apart = ~(shapely.intersects(narrow1, wide2) | shapely.intersects(narrow2, wide1))
    k = g.slope(phi1)
    dk = (g.slope(phi1 + 1e-5) - g.slope(phi1 - 1e-5)) / 2e-5
    kept = np.flatnonzero(apart)
    ones, twos = outlines(narrow1[kept], wide1[kept]), outlines(narrow2[kept], wide2[kept])
    for j, a, b in zip(kept.tolist(), ones, twos):
        i = int(free[j])
        s = sites[i]
        s.t0, s.cap, s.k, s.dk = float(t0[i]), float((up[i] + down[i]) / 2), float(k[j]), float(dk[j])
        s.arm = float(g.center_distance - g.r1[i])
        s.a, s.b = a, b
    return sites, signed


def narrow_windows(wide: np.ndarray, centres: np.ndarray, module: float) -> np.ndarray:
    """The narrow windows (:data:`~.play._WINDOW` modules about ``centres``, on which the play is
    measured) cut from a gear's ``wide`` ones (:data:`BEYOND` modules more, against which the
    mate's vertices are checked)."""
    return shapely.intersection(wide, shapely.buffer(shapely.points(centres), _WINDOW * module, quad_segs=16))


def _placed(windows: np.ndarray, turn: np.ndarray, pivot: np.ndarray) -> np.ndarray:
    """Gear 2's ``windows`` (in its own frame) turned by ``turn`` about its pivot, placed at ``pivot``."""
    xy, which = shapely.get_coordinates(windows, return_index=True)
    return shapely.set_coordinates(windows.copy(), place_each(xy, which, turn, pivot))


class Measures:
    """How :func:`prove_play` measures a geometry and bounds it between positions: a gear pair's
    (:class:`~.play.PairGeometry`, :data:`PAIRS`); a mesh under a general motion has its own
    (:class:`.moving.MovingMeasures`)."""

    tighten: float = TIGHT_BUDGET
    """Once proven, how many times the first positions more may pin the least down (:data:`SLACK`)."""

    first_split: int = 2
    """Where the first positions show no jam, each interval between them is split in this many
    (the new positions measured) before any bound is taken: over a whole first interval the
    vertices move twice as far as over half of it, more of the mate's edges lie within their
    reach, and at a steep contact the bound rarely keeps the margin there anyway — the laser
    focus pair's first bounds kept it at half of its 82 first positions, at 11.8 ms a position;
    over the 164 halves, at 4.6 ms a position, every one kept it.  Twelve printed and cut example
    pairs' checks: 155 → 132 CPU-s (docs/speed.md)."""

    def sites(self, g, offsets, spread: float, tol: float, reach: float) -> tuple[list[Site], np.ndarray]:
        """The signed play at ``g``'s positions and the :class:`~.tube.Site` of each."""
        return _sites(g, offsets, spread, tol, reach)

    def signed(self, g, offsets, spread: float, tol: float, reach: float) -> np.ndarray:
        """The signed play at ``g``'s positions."""
        return signed_play(g, offsets, spread, tol, reach=reach)

    def ratio(self, g, spread: float):
        """(lo, hi) -> the bounds :func:`~.tube.tube` takes over each driver interval."""
        return g.ratio

    def extent(self, g, spread: float) -> float:
        """What :func:`~.tube.tube` takes as ``e``: gear 2's pivot's distance from gear 1's (mm)."""
        return g.center_distance + spread

    def arm(self, g, bounds: tuple) -> float:
        """Gear 2's least radius at the contact over an interval, from :meth:`ratio`'s ``bounds``
        there (mm; a pair's: E/(1 + k) at the largest k)."""
        return g.center_distance / (1 + bounds[0])

    def joined(self, parts: list):
        """The geometries measured, one after another."""
        return _joined(parts)


PAIRS = Measures()


def prove_play(
    g: PairGeometry,
    offsets,
    spread: float,
    tol: float,
    *,
    reach: float,
    margin: float,
    budget: int = 0,
    measures: Measures = PAIRS,
):
    """The tight case's signed play, measured at ``g``'s positions and refined where the bound
    between them cannot settle the verdict: (geometry at every position measured, play there,
    :class:`Certificate`).

    Each measured position c covers the driver angles up to half way to its neighbours (h); its
    bound (:func:`.tube.tube`) proves a free turn 2Δ wide over all of them, a play of at least
    2Δ·E/(1 + k_max) there, and neighbours' free turns overlap (the follower passes from one to
    the next).  A position whose bound falls under the margin (or whose free turn does not reach
    its neighbour's) has the intervals either side halved, until every one keeps the margin, one
    is narrower than a millionth of the cycle, or the budget (:data:`BUDGET` times the first
    positions) runs out: then the certificate is not ``proven``, names the interval and says the
    play short of the margin by the resolution, max(tol, 1e-4·m) (what a fit search then adds).  A
    measured position under the margin proves the pair jams; the intervals about the least play
    are then halved :data:`JAM_HALVINGS` times to say how far short it falls.  Once proven, the
    least is pinned down (:data:`SLACK`).  ``measures``: how ``g`` is measured and bounded
    (:class:`Measures`; a gear pair's by default)."""
    if margin < 0:  # exact parts may bite: the outlines, each moved in by what it may lose, apart
        return _bitten(g, offsets, spread, tol, reach=reach, margin=margin, budget=budget, measures=measures)
    _, finish = prove_lazily(g, offsets, spread, tol, reach=reach, margin=margin, budget=budget, measures=measures)
    return finish()


def prove_lazily(
    g: PairGeometry,
    offsets,
    spread: float,
    tol: float,
    *,
    reach: float,
    margin: float,
    budget: int = 0,
    measures: Measures = PAIRS,
):
    """(found, finish): :func:`prove_play` (a margin of 0 or more) stopped as soon as the verdict
    is settled — ``found`` its (geometry, play, :class:`Certificate`), the least not yet pinned
    down (:data:`SLACK`; a jam: at the first position measured under the margin, its intervals
    not yet halved, :data:`JAM_HALVINGS`) — and finish() -> the same proof carried on until it
    is, from where it stopped (what a search for the backlash skips on every cut but the one it
    keeps: half the laser focus pair's CPU; a cut that jams, a tenth of a printed pair's)."""
    proof = _proof(g, offsets, spread, tol, reach=reach, margin=margin, budget=budget, measures=measures)
    found = next(proof)
    done: list = []

    def finish():
        if not done:
            jams = found[2].proven and found[2].lower < margin  # (unproven: the budget ran out, as it stands)
            fits = found[2].proven and not jams and measures.tighten > 0
            try:
                done.append(proof.send(measures.tighten) if jams or fits else found)
            except StopIteration:  # nothing was left to carry on: the first answer is the whole proof
                done.append(found)
            proof.close()
        return done[0]

    return found, finish


def _proof(g: PairGeometry, offsets, spread: float, tol: float, *, reach: float, margin: float, budget: int, measures):
    """:func:`prove_play`'s work, a generator: it yields the proof once the verdict is settled,
    and, sent how many times the first positions more may pin the least down, yields it again
    when they have."""
    tighten = 0.0
    if g.first is not None:  # the certificate's own even start along the pitch curve
        g = g.at(g.first)
    n0 = len(g.phi1)
    budget = budget or BUDGET * n0
    narrowest = 1e-6 * g.cycle
    e = measures.extent(g, spread)
    ratio = measures.ratio(g, spread)
    geos, plays = [g], []
    sites, signed = measures.sites(g, offsets, spread, tol, reach)
    plays.append(signed)
    phi = np.sort(g.phi1 % g.cycle)
    gap = _gaps(phi, g.cycle)
    phi, gap = phi[gap > narrowest], gap[gap > narrowest]  # (a position given twice: split once)
    if 1 < measures.first_split and n0 * measures.first_split <= budget and len(phi) and np.min(signed) >= margin:
        # (a jam is told at the first positions; a budget under the split's positions is kept)
        k = measures.first_split
        sub = g.at(np.concatenate([phi + gap * j / k for j in range(1, k)]) % g.cycle)
        more, signed = measures.sites(sub, offsets, spread, tol, reach)
        sites += more
        geos.append(sub)
        plays.append(signed)
    tubes: dict[int, tuple[float, float, float]] = {}  # site id -> (h, slope, Δ) last computed
    jammed = 0
    told = False  # whether a jam was yielded before its intervals were halved
    settled = None  # how many positions were measured when the margin was first proven
    while True:
        order = sorted(range(len(sites)), key=lambda i: sites[i].phi)
        phi = np.array([sites[i].phi for i in order])
        gap = _gaps(phi, g.cycle)  # to the next
        half = 0.5 * np.maximum(gap, np.roll(gap, 1))  # the wider half-interval either side
        table = ratio(phi - half, phi + half)
        measured = np.array([sites[i].play for i in order])
        least = float(np.min(measured))
        t0 = np.array([sites[i].t0 for i in order])
        slope = _drift(phi, t0, np.array([sites[i].cap for i in order]), g.cycle)
        bound = np.full(len(order), -math.inf)
        delta = np.full(len(order), -math.inf)
        if least >= margin:  # (a measured jam settles it: no bound)
            rows = np.column_stack(table)
            stale = [j for j, i in enumerate(order) if tubes.get(i, (None,))[:2] != (half[j], slope[j])]
            if stale:
                got = tube_of([sites[order[j]] for j in stale], half[stale], e, rows[stale], slope[stale])
                for j, d in zip(stale, got.tolist()):
                    tubes[order[j]] = (half[j], slope[j], d)
            delta = np.array([tubes[i][2] for i in order])
            arm = np.minimum([sites[i].arm for i in order], measures.arm(g, table))
            bound = np.where(delta >= 0, 2 * delta * arm, -math.inf)
        # neighbours' free turns meet half way between them (each sheared box's middle there)
        ahead = t0 + slope * gap / 2
        behind = np.roll(t0, -1) - np.roll(slope, -1) * gap / 2
        joined = np.abs(behind - ahead) <= np.maximum(delta, 0) + np.maximum(np.roll(delta, -1), 0)
        if least < margin:  # it jams, proven by a measured position: pin the least down a little
            if not told and JAM_HALVINGS and settled is None:  # the verdict first (a search's cut needs no more)
                told = True
                cert = Certificate(lower=least, positions=len(sites), slack=0.0, proven=True, kind="theorem")
                if (yield measures.joined(geos), np.concatenate(plays), cert) is None:
                    return
            jammed += 1
            low_site = measured < least + 8 * max(tol, 1e-4 * g.module)
            split = (low_site | np.roll(low_site, -1)) & (jammed <= JAM_HALVINGS)
        else:
            weak = bound < margin
            if not weak.any() and joined.all():  # proven: then the least pinned down, lowest first
                settled = len(sites) if settled is None else settled
                loose = np.flatnonzero(bound < least - SLACK)
                weak[loose[np.argsort(bound[loose])][:TIGHTEN]] = len(sites) < settled + tighten * n0
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
            more = yield measures.joined(geos), np.concatenate(plays), cert
            if more is not None and more > tighten:  # carry on: pin the least down
                tighten = more
                continue
            return
        # how many new positions each gap takes: where a weak position's bound would keep the
        # margin over a narrower interval (looked at without measuring), enough to reach it
        pieces = np.where(split, 2, 1)
        if least >= margin:
            weak = np.flatnonzero(bound < margin)
            h = half[weak].copy()
            arm = np.minimum([sites[order[j]].arm for j in weak], measures.arm(g, tuple(t[weak] for t in table)))
            open_ = np.ones(len(weak), bool)
            for _ in range(6):  # halved together, each until it keeps the margin
                if not open_.any():
                    break
                h[open_] /= 2
                j = weak[open_]
                near = np.column_stack(ratio(phi[j] - h[open_], phi[j] + h[open_]))
                got = tube_of([sites[order[i]] for i in j], h[open_], e, near, slope[j])
                open_[np.flatnonzero(open_)[2 * got * arm[open_] >= margin]] = False
            need = np.minimum(16, np.ceil(half[weak] / h)).astype(int)
            for j, n in zip(weak.tolist(), need.tolist()):
                for gj in (j, (j - 1) % len(order)):
                    pieces[gj] = max(pieces[gj], n if split[gj] else 1)
        steps = [phi[j] + gap[j] * np.arange(1, pieces[j]) / pieces[j] for j in np.flatnonzero(pieces > 1)]
        mids = np.concatenate(steps) % g.cycle
        if len(sites) + len(mids) > budget:  # the budget: say what is left open
            mids = (phi[split] + gap[split] / 2) % g.cycle
            if len(sites) + len(mids) > budget:
                budget = len(sites)  # the next look ends it
                continue
        sub = g.at(mids)
        more, signed = measures.sites(sub, offsets, spread, tol, reach)
        sites += more
        geos.append(sub)
        plays.append(signed)


def _gaps(phi: np.ndarray, cycle: float) -> np.ndarray:
    """From each of the driver angles ``phi`` (ascending) to the next, round the cycle (rad): a
    lone position's is the whole cycle (its own next, one turn on), not 0."""
    return (np.roll(phi, -1) - phi) % cycle if len(phi) > 1 else np.full(len(phi), cycle)


def _drift(phi: np.ndarray, t0: np.ndarray, cap: np.ndarray, cycle: float) -> np.ndarray:
    """How fast the middle of gear 2's free turn drifts with the driver at each position (rad per
    rad), from its neighbours either side (0 where one of them is jammed): the slope each bound's
    box is sheared by (:func:`~.tube.tube`; any slope is sound, this one keeps the box on the free
    turn)."""
    if len(phi) < 3:
        return np.zeros(len(phi))
    span = (np.roll(phi, -1) - np.roll(phi, 1)) % cycle
    slope = (np.roll(t0, -1) - np.roll(t0, 1)) / np.maximum(span, 1e-300)
    free = np.isfinite(cap) & np.roll(np.isfinite(cap), 1) & np.roll(np.isfinite(cap), -1)
    return np.where(free & (span > 0), slope, 0.0)


def _bitten(g, offsets, spread: float, tol: float, *, reach: float, margin: float, budget: int, measures: Measures):
    """:func:`prove_play` for a margin under 0: exact parts may bite by −``margin`` (the shrink ε
    that frees a jammed position counts −4ε/cos α, :func:`~.play.signed_play`).  Where the first
    positions keep twice the tolerance free, the outlines as drawn are proven apart (a margin of
    0; the bound is then their least play); otherwise, or where that fails, the outlines, each
    moved in by ε = −margin·cos α/4, are: proven apart, the play is at least ``margin``
    everywhere (the certificate's ``lower``; their plays, not these, are measured as drawn), and a
    position of theirs that jams jams by ε more as drawn (its play less −margin)."""
    first = g.at(g.first) if g.first is not None else g
    if float(np.min(measures.signed(first, offsets, spread, tol, reach))) >= 2 * tol:
        found = prove_play(g, offsets, spread, tol, reach=reach, margin=0.0, budget=budget, measures=measures)
        if found[2].proven and found[2].lower >= 0:
            return found
    give = -margin * math.cos(g.pressure_angle) / 4
    inward = tuple(o - give for o in offsets)
    geo, _, cert = prove_play(g, inward, spread, tol, reach=reach, margin=0.0, budget=budget, measures=measures)
    lower = cert.lower + margin if cert.lower < 0 else margin
    drawn = measures.signed(geo, offsets, spread, tol, reach)
    return geo, drawn, replace(cert, lower=lower, slack=float(np.min(drawn)) - lower)


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
