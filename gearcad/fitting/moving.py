"""The proven least play of a mesh whose gear 2 moves in gear 1's frame by a general
one-parameter rigid motion — a roller on a toothed body, its axle running along the parallel of
the body's pitch curve — by :func:`.prove.prove_play` with the bound of :func:`.tube.tube`
(docs/fit.md, "Rollers").

In gear 1's frame gear 2 is placed by the parameter τ (the body's turn) and its own turn t beyond
the rolling angle: a point of it is X(τ, t) = C(τ) + R(A(τ) + t)·q, C its pivot.  With ω = A' and
the instant centre I = C + J·C'/ω (so C' = ωJ(C − I)), ∂τX = C' + ωJ(X − C) = ωJ(X − I), and
then ∂ττX = ω'J(X − I) − ω²(X − I) − ωJI', ∂τtX = −ω(X − C), ∂tX = J(X − C), ∂ttX = −(X − C), and
|∂τττX| ≤ |ω''|ρ + |ω'|(3|ω|ρ + 2|I'|) + ω²(|ω|ρ + |I'|) + |ω||I''| (ρ = |X − I|), |∂ττtX| ≤
(|ω'| + ω²)|X − C|, |∂τttX| ≤ |ω||X − C|, |∂tttX| = |X − C|: the derivatives and bounds the
tube is written in.  They hold for any such motion, not only a pivot on a circle (a gear pair is
the case C = E'(cos φ, sin φ), A = φ + φ2(φ)).  Gear 1's points, seen from gear 2, move about the
same instant centre, which runs along gear 2's centrode at the same speed |I'| (the two centrodes
roll on each other: in gear 2's frame I₂ = R(−A)(I − C), I₂' = R(−A)·I') with acceleration
|I₂''| = |I'' − ωJI'| ≤ |I''| + |ω||I'| (the tube counts that term), and their distance from gear
2's pivot changes by at most |C'|·h over an interval (a gear pair's E'·h).

So the tube needs, at each measured position, C, I, I', ω and ω' (five-point stencils of the
placement, ±1e-3 rad: exact to far below a nanometre), and over each interval the largest |ω|,
|ω'|, |ω''|, |I'|, |I''| and |C'|: from :data:`SAMPLES` even samples of the cycle, differenced,
each raised by the largest step between neighbours, as a gear pair's are from its angle map
(:func:`~.pair_geometry.follower_speed`).  The play is measured as :mod:`.band_mesh` measures
any mesh (gear 2 turned each way about its pivot until it touches), and the proof's windows are
those of :mod:`.prove` (three modules about the contact against three and a half).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..threads import side_by_side
from .band import Band, _margin, band_of
from .band_mesh import _WINDOW, MeshGeometry, _windows, clip, contacts, mesh_play, signed_mesh_play
from .certify import certify
from .corners import outlines
from .pair_geometry import interval_maxima
from .prove import BEYOND, Measures, _placed, narrow_windows, prove_play
from .tube import Site

__all__ = ["MovingMesh", "MovingMeasures", "moving_band"]

SAMPLES = 8192
"""Even samples of the cycle the bounds over an interval are taken from."""
SIDE_CASES = 36
"""The first positions the nominal and wide cases are measured at (about)."""
PER_PASS = 4
"""Positions a tooth pass (a tooth of gear 1 past the contact) the proof starts from: a roller
turns about ten times as fast as the body, and the bound held over a quarter of a body tooth where
half a tooth left every interval open (roller_body_m3 under a laser: from two a tooth 453
positions and 24 CPU-s, from four 458 and 16)."""
BITTEN = 0.19
"""Where the parts may bite (no process: the outlines, moved in by the tolerance, are proven
apart, :func:`~.prove.prove_play`) they keep only 4·tol/cos α, and the proof starts from
BITTEN/√tol (mm) positions a tooth pass, at least three: the bound's loss grows as the square of the
interval (roller_body_m3 at tol 0.001 from four a pass: 811 positions and 1528 bounds, 29 CPU-s;
from six, 719 positions, 18 CPU-s; at 0.01 from three, 333 positions, 3.5 CPU-s)."""
ROUNDING = 1e-6
"""What the differences of :func:`bounds` may miss, relative: a central difference of a wave of ν
a radian at steps δ errs by (νδ)²/6 of it, far under the largest step between neighbours (νδ)
wherever the series changes; this covers one that does not (a pivot on a circle: |C'| = E is
2.4e-8 under at 8192 steps a half turn)."""
STENCIL = 1e-3
"""The step (rad) of the five-point stencils that give the motion's derivatives at a position."""


@dataclass(frozen=True)
class MovingMesh:
    """A mesh whose gear 2 moves in gear 1's frame by a one-parameter rigid motion, as the proof
    measures it: the mesh at the positions measured (``mesh``) and at any others (``place``)."""

    mesh: MeshGeometry
    place: Callable[[np.ndarray], MeshGeometry]
    """τ (rad) -> the mesh there; its placements continuous in τ (gear 2's turn not wrapped), and
    the same mesh a cycle on (gear 2 then turned by whole teeth of an outline that repeats so)."""
    cycle: float
    """The parameter's turn after which the mesh repeats (rad): the positions wrap there."""
    passes: int
    """Tooth passes a cycle (gear 1's teeth past the contact): the proof starts from ``per_pass``
    positions each, evenly over the cycle."""
    arm: float | None
    """Gear 2's pitch radius at the contact (mm; a roller's, the same everywhere): the play is the
    free turn times it.  None: it changes along the cycle (a noncircular mesh), the distance from
    gear 2's pivot to the pitch point, at its least over each interval (:func:`bounds`)."""

    per_pass: float = PER_PASS
    """Positions a tooth pass the proof starts from."""

    @property
    def first(self) -> np.ndarray:
        """The parameters the proof starts from (rad)."""
        return np.linspace(0.0, self.cycle, round(self.per_pass * self.passes), endpoint=False)

    @property
    def phi1(self) -> np.ndarray:
        return self.mesh.phi1

    @property
    def teeth(self) -> np.ndarray:
        return self.mesh.teeth

    @property
    def module(self) -> float:
        return self.mesh.module

    @property
    def pressure_angle(self) -> float:
        return self.mesh.pressure_angle

    def at(self, phi) -> MovingMesh:
        """The same mesh at the parameters ``phi``."""
        return replace(self, mesh=self.place(np.asarray(phi, dtype=float)))


def _j(v: np.ndarray) -> np.ndarray:
    """Each row turned a quarter turn counter-clockwise."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _pose(m: MeshGeometry, shift: float) -> tuple[np.ndarray, np.ndarray]:
    """Gear 2's pivot (moved ``shift`` mm the tight way) and turn at each position."""
    return m.centre2 + shift * m.tighter, m.angle2


def local(place, tau: np.ndarray, shift: float) -> tuple[np.ndarray, ...]:
    """At each τ: gear 2's pivot C, ω, ω', the instant centre I and I' (five-point stencils)."""
    n, h = len(tau), STENCIL
    grid = (np.asarray(tau, dtype=float)[:, None] + h * np.arange(-2, 3)[None, :]).ravel()
    centre, angle = _pose(place(grid), shift)
    centre, angle = centre.reshape(n, 5, 2), angle.reshape(n, 5)
    angle = angle[:, 2:3] + np.remainder(angle - angle[:, 2:3] + math.pi, 2 * math.pi) - math.pi

    def d1(f):
        return (f[:, 0] - 8 * f[:, 1] + 8 * f[:, 3] - f[:, 4]) / (12 * h)

    def d2(f):
        return (-f[:, 0] + 16 * f[:, 1] - 30 * f[:, 2] + 16 * f[:, 3] - f[:, 4]) / (12 * h * h)

    omega, domega = d1(angle), d2(angle)
    c0, c1, c2 = centre[:, 2], d1(centre), d2(centre)
    instant = c0 + _j(c1) / omega[:, None]
    turning = c1 + _j(c2) / omega[:, None] - _j(c1) * (domega / omega**2)[:, None]
    return c0, omega, domega, instant, turning


def bounds(place, cycle: float, shift: float, samples: int = SAMPLES):
    """ratio(lo, hi) -> per interval [lo, hi] (rad; either end may pass the cycle) the largest
    |ω| − 1, |I'|, |ω'|, |ω''|, |I''| and |C'| (what :func:`~.tube.tube` takes for a general
    motion) and the least distance from gear 2's pivot (unshifted) to the pitch point (the arm
    the free turn is measured with), from ``samples`` even parameters over the cycle, each raised
    (the arm lowered) by the largest step between neighbours and by :data:`ROUNDING` of itself."""
    step = cycle / samples
    tau = np.arange(-3, samples + 4) * step  # three more each side: the differences' ends
    placed = place(tau)
    centre, angle = _pose(placed, shift)
    omega = np.gradient(np.unwrap(angle), step)
    domega = np.gradient(omega, step)
    ddomega = np.gradient(domega, step)
    speed = np.gradient(centre, step, axis=0)
    instant = centre + _j(speed) / omega[:, None]
    turning = np.gradient(instant, step, axis=0)
    bend = np.gradient(turning, step, axis=0)
    inner = slice(3, 3 + samples + 1)  # the cycle and its first sample again (the step across the wrap)
    series = [
        np.abs(omega[inner]),
        np.hypot(*turning[inner].T),
        np.abs(domega[inner]),
        np.abs(ddomega[inner]),
        np.hypot(*bend[inner].T),
        np.hypot(*speed[inner].T),
        -np.hypot(*(placed.contact - placed.centre2)[inner].T),
    ]
    maxima = interval_maxima(series, step)

    def ratio(lo, hi) -> tuple[np.ndarray, ...]:
        *most, arm = maxima(lo, hi)
        largest, *rest = (x * (1 + ROUNDING) for x in most)
        return (largest - 1.0, *rest, -arm * (1 - ROUNDING))  # the tube takes the largest "k", |ω| = 1 + k

    return ratio


class MovingMeasures(Measures):
    """How :func:`~.prove.prove_play` measures a :class:`MovingMesh` and bounds it between
    positions (the module docstring)."""

    tighten = 0.0
    """(A body's rollers: hundreds of positions already; the least is not pinned down further.)"""

    first_split = 1
    """(Their first positions are close enough for the bound: split, a body's rollers took twice
    the positions for the same proof, 771 → 1526 on the plain roller body.)"""

    def __init__(self):
        self._ratios: dict[float, Callable] = {}
        self._signed: dict[tuple, dict[float, float]] = {}

    def _pieces(self, m: MeshGeometry, offsets):
        if offsets[0] != offsets[1]:
            raise ValueError("a moving mesh is measured with both parts grown alike")
        return clip(m, abs(offsets[0]) + 0.5 * m.module)  # the shrink that frees a jam: up to half a module

    def signed(self, g: MovingMesh, offsets, spread: float, tol: float, reach: float) -> np.ndarray:
        known = self._signed.setdefault((*offsets, spread, tol, reach), {})  # (each position measured once)
        new = np.array([phi not in known for phi in g.phi1.tolist()], dtype=bool)
        if new.any():
            m = g.mesh.at(new)
            found = signed_mesh_play(m, self._pieces(m, offsets), offsets[0], spread, tol, reach=reach)
            known.update(zip(m.phi1.tolist(), found.tolist()))
        return np.array([known[phi] for phi in g.phi1.tolist()])

    def sites(self, g: MovingMesh, offsets, spread: float, tol: float, reach: float):
        m = g.mesh
        pieces = self._pieces(m, offsets)
        # each part's window and a wider one (:mod:`.prove`), made once: the play is measured on the narrow ones
        contact, own = contacts(m)
        wide_r = (_WINDOW + BEYOND) * m.module
        wide1 = _windows(pieces[0], contact, wide_r, offsets[0], tol)
        wide2 = _windows(pieces[1], own, wide_r, offsets[1], tol)
        narrow1, narrow2 = narrow_windows(wide1, contact, m.module), narrow_windows(wide2, own, m.module)
        halves: list[np.ndarray] = []
        play = mesh_play(m, offsets, spread, tol, reach=reach, halves=halves, windows=(narrow1, narrow2))
        signed = play.copy()
        jammed = np.isnan(play)
        if jammed.any():
            cut = (pieces[0][jammed], pieces[1][jammed])
            signed[jammed] = signed_mesh_play(m.at(jammed), cut, offsets[0], spread, tol, reach=reach)
        sites = [Site(float(p), float(s)) for p, s in zip(m.phi1, signed)]
        free = np.flatnonzero(~jammed)
        if not len(free):
            return sites, signed
        up, down = halves
        t0, cap = (up - down) / 2, (up + down) / 2
        # gear 2's windows placed at the middle of its free turn
        centre, omega, domega, instant, turning = local(g.place, m.phi1[free], spread)
        turned = m.angle2[free] + t0[free]
        wide1, narrow1 = wide1[free], narrow1[free]
        wide2, narrow2 = (_placed(w[free], turned, centre) for w in (wide2, narrow2))
        apart = ~(shapely.intersects(narrow1, wide2) | shapely.intersects(narrow2, wide1))
        kept = np.flatnonzero(apart)
        ones, twos = outlines(narrow1[kept], wide1[kept]), outlines(narrow2[kept], wide2[kept])
        for j, a, b in zip(kept.tolist(), ones, twos):
            i = int(free[j])
            s = sites[i]
            s.t0, s.cap, s.k, s.dk = float(t0[i]), float(cap[i]), float(omega[j] - 1.0), float(domega[j])
            s.arm = g.arm if g.arm is not None else float(np.hypot(*(m.contact[i] - m.centre2[i])))
            s.pivot, s.instant, s.turning = centre[j], instant[j], turning[j]
            s.a, s.b = a, b
        return sites, signed

    def ratio(self, g: MovingMesh, spread: float):
        if spread not in self._ratios:
            self._ratios[spread] = bounds(g.place, g.cycle, spread)
        return self._ratios[spread]

    def extent(self, g: MovingMesh, spread: float) -> float:
        return 0.0  # (a general motion's site carries its pivot: the tube does not take it)

    def arm(self, g: MovingMesh, bounds: tuple) -> float:
        return g.arm if g.arm is not None else bounds[6]

    def joined(self, parts: list[MovingMesh]) -> MovingMesh:
        fields = ("phi1", "centre2", "angle2", "contact", "tighter", "teeth")
        cat = {f: np.concatenate([getattr(p.mesh, f) for p in parts]) for f in fields}
        return replace(parts[0], mesh=replace(parts[0].mesh, **cat))


def moving_band(
    g: MovingMesh,
    *,
    edge: tuple[float, float, float],
    spread: float,
    tol: float,
    backlash: float,
    name: str,
    certificate: str = "theorem",
) -> Band:
    """The band of a mesh under a general motion, as :func:`~.band.pair_band` gives a pair's: the
    tight case (every edge at its largest, gear 2's pivot ``spread`` mm the tight way) certified
    between positions — proven (``certificate`` "theorem", :func:`~.prove.prove_play` with
    :class:`MovingMeasures`) or estimated ("estimate", :func:`~.certify.certify`) — and the
    nominal and wide cases measured at :data:`SIDE_CASES` of the first positions (they bound no
    verdict: the play as drawn, and the most it may reach)."""
    alpha = g.pressure_angle
    reach = backlash + 4 * max(abs(e) for e in edge) / math.cos(alpha) + 2 * spread * math.tan(alpha) + 0.5 * g.module
    margin = _margin(edge, spread, tol, alpha)
    if margin < 0:  # exact parts: the outlines moved in keep only 4·tol/cos α, proven at finer steps
        g = replace(g, per_pass=max(3, math.ceil(BITTEN / math.sqrt(tol))))
    measures = MovingMeasures()
    tight_edges = (edge[2], edge[2])

    def tight():
        if certificate == "theorem":
            return prove_play(g, tight_edges, spread, tol, reach=reach, margin=margin, measures=measures)

        def measure(phi):
            return measures.signed(g.at(phi), tight_edges, spread, tol, reach)

        phi, play, cert = certify(measure, g.first, g.cycle, module=g.module, tol=tol, margin=margin)
        return g.at(phi), play, cert

    if edge[0] == edge[1] == edge[2] and not spread:  # no stack: one case, not three alike
        geo, low, cert = tight()
        cases = (low, low, low)
    else:
        every = max(1, len(g.first) // SIDE_CASES)
        few = g.at(g.first[::every]).mesh
        pieces = clip(few, max(abs(e) for e in edge))
        with side_by_side() as pool:  # GEOS releases the GIL: the cases side by side
            job = pool.submit(tight)
            nominal = mesh_play(few, (edge[0], edge[0]), 0.0, tol, reach=reach, pieces=pieces)
            wide = mesh_play(few, (edge[1], edge[1]), -spread, tol, reach=reach, pieces=pieces)
            geo, low, cert = job.result()
        cases = [np.full(len(low), np.nan), low, np.full(len(low), np.nan)]
        cases[0][: len(g.first) : every], cases[2][: len(g.first) : every] = nominal, wide
    return band_of(name, cases, geo.teeth, geo.phi1, edge=edge, spread=spread, tol=tol, alpha=alpha, certificate=cert)
