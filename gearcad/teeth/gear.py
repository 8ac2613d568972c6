"""Tooth outlines: the envelope of a generating rack rolled without slip along a pitch curve.

The rack's rolling line touches the pitch curve at C(s) with the rack displaced so that its
coordinate u = s there (displacement = arc length).  A rack point (u, v) shapes the gear at the
instant its profile normal passes through the pitch point (equation of meshing), which gives
the contact parameter s* in closed form for every part of the rack:

* straight flanks, normal (±cos α, −sin α):      s* = u ± v·cot α
* tip fillet of radius ρ about (u_c, v_c):        s* = u_c − v_c·cot β (β the normal's angle)
* flat tip (normal straight down):               s* = u

and the gear point is P = C(s*) + (u − s*)·T(s*) + v·N(s*).  On a circle the flank is exactly
the involute of the base circle r·cos α.  Where the flank envelope folds back (it does once
v < −ρ_c·sin²α, ρ_c the pitch curve's radius of curvature) the trochoid of the rack tip cuts
into it: the loop is removed, leaving what a real rack would leave (undercut).
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
import shapely

from ..errors import DesignError
from ..geometry.outline import Outline, ring_area
from .frame import ArcFrame
from .loops import remove_loops, remove_loops_each
from .rack import Rack
from .sampling import MAX_POINTS, sample_curves

__all__ = ["ToothedGear", "cut_teeth", "remove_loops"]


@dataclass(frozen=True)
class ToothedGear:
    """A gear's toothed outline and what was measured while cutting it."""

    outline: Outline
    teeth: int
    rack: Rack
    phase: float
    """Arc length (mm) of the centre of tooth space 0; spaces every pitch from there."""
    undercut_depth: np.ndarray
    """(2·teeth,) how far each flank's straight rack part reaches below its fold point, mm
    (positive = undercut): |v_low| − ρ_c·sin²α.  Order: space k's left flank, right flank."""
    flank_phi: np.ndarray
    """(2·teeth,) polar angle of each flank at the pitch curve, rad."""
    tip_thickness: np.ndarray
    """(teeth,) chord across each tooth's tip land, mm; ≤ 0 where the flanks cross below it."""
    tooth_phi: np.ndarray
    """(teeth,) polar angle of each tooth centre, rad."""
    space_loops: np.ndarray
    """(teeth,) how many loops the rack's path made in each tooth space (trimmed away)."""
    space_root: np.ndarray
    """(teeth,) index in the outline ring of the vertex nearest each space's root centre."""
    under_root: np.ndarray
    """(teeth, 2) a point a module below each space's root: solid material, mm."""

    @property
    def undercut(self) -> bool:
        return bool(np.any(self.space_loops > 0) or np.any(self.undercut_depth > 0))

    @property
    def pointed(self) -> np.ndarray:
        """Indices of teeth whose flanks meet below the tip curve."""
        return np.nonzero(self.tip_thickness <= 0)[0]


PARTS = ("left flank", "left fillet", "root", "right fillet", "right flank", "tip")
"""The rack's parts in the order the outline runs through a space and on over the next tooth."""


class _Generator:
    """Closed-form gear points of each part of every rack tooth."""

    def __init__(self, frame: ArcFrame, rack: Rack, centres: np.ndarray):
        self.f, self.k, self.U = frame, rack, centres

    def _point(self, u, v, s):
        c, t, n = self.f.frame(s)
        return c + (u - s)[..., None] * t + v[..., None] * n

    def _rack(self, part: int, ids, x):
        """(u, v, s*) of rack ``part`` (see :data:`PARTS`) of space (or tooth) ``ids`` at its
        parameter x: v on a flank, the normal's angle β on a fillet, u on the root, s on the tip."""
        k = self.k
        side = -1 if part < 2 else 1
        if part in (0, 4):  # flank: s* = u ± v·cot α
            u = self.U[ids] + side * (k.half_width + x * k.tan_a)
            return u, x, u + side * x * k.cot_a
        if part in (1, 3):  # fillet: s* = u_c − v_c·cot β
            uc = self.U[ids] + side * k.fillet_u
            u = uc + side * k.radius * np.cos(x)
            return u, k.fillet_v + k.radius * np.sin(x), uc - side * k.fillet_v / np.tan(x)
        return x, np.full_like(x, k.v_root if part == 2 else k.v_tip), x  # root, tip: s* = u

    def parts(self, part, ids, x):
        """Gear points of rack parts ``part`` (an array of :data:`PARTS` indices) of spaces
        ``ids`` at parameters x, the frame evaluated once for all of them."""
        u, v, s = np.empty_like(x), np.empty_like(x), np.empty_like(x)
        for j in np.unique(part):
            at = part == j
            u[at], v[at], s[at] = self._rack(int(j), ids[at], x[at])
        return self._point(u, v, s)

    def tip(self, s):
        c, _, n = self.f.frame(s)
        return c + self.k.v_tip * n

    def meet_tip(self, ids, side, iterations: int = 12):
        """(v, s) where each flank crosses the tip curve (``side`` per element: −1 the left
        flank of space ``ids``, +1 the right): Newton with the envelope's exact derivative
        dP/dv = side·(tan α + vκ/(sin α cos α))·T + (1 + vκ/sin²α)·N and dQ/ds = (1 + h·κ)·T
        for the tip curve Q = C + h·N, one frame evaluation a step for both curves; each side
        stops once all of its steps are below 1e-12."""
        k = self.k
        sa, ca = math.sin(k.params.pressure_angle), math.cos(k.params.pressure_angle)
        v = np.full(len(ids), k.v_tip)
        s = self.U[ids] + side * (k.half_width + k.v_tip * k.tan_a)
        live = np.arange(len(ids))
        for _ in range(iterations):
            i, g, m = ids[live], side[live], len(live)
            u = self.U[i] + g * (k.half_width + v[live] * k.tan_a)
            star = u + g * v[live] * k.cot_a
            c, t, n, kappa = self.f.frame_curvature(np.concatenate([star, s[live]]))
            (c, cq), (t, tq), (n, nq), (kappa, kq) = (np.split(x, [m]) for x in (c, t, n, kappa))
            vl = v[live]
            p = c + (u - star)[:, None] * t + vl[:, None] * n
            dp = (g * (k.tan_a + vl * kappa / (sa * ca)))[:, None] * t + (1 + vl * kappa / sa**2)[:, None] * n
            dq = (1 + k.v_tip * kq)[:, None] * tq
            f = p - (cq + k.v_tip * nq)
            det = dp[:, 0] * (-dq[:, 1]) - dp[:, 1] * (-dq[:, 0])
            dv = (f[:, 0] * (-dq[:, 1]) - f[:, 1] * (-dq[:, 0])) / det
            ds = (dp[:, 0] * f[:, 1] - dp[:, 1] * f[:, 0]) / det
            v[live], s[live] = vl - dv, s[live] - ds
            step = np.abs(dv) + np.abs(ds)
            done = [h for h in np.unique(g) if np.max(step[g == h]) < 1e-12]
            live = live[~np.isin(g, done)]
            if not len(live):
                break
        return v, s


def _newton2(residual, x, y, *, h=1e-7, iterations=30):
    """Solve residual(x, y) = 0 (a 2-vector per element) by Newton with finite differences.

    ``residual`` is asked once a step, of the point and its four neighbours stacked: element
    i of arrays five times as long is element i mod len(x) of the problem."""
    m = len(x)
    for _ in range(iterations):
        r = residual(np.concatenate([x, x + h, x - h, x, x]), np.concatenate([y, y, y, y + h, y - h]))
        f, xp, xm, yp, ym = (r[j * m : (j + 1) * m] for j in range(5))
        fx = (xp - xm) / (2 * h)
        fy = (yp - ym) / (2 * h)
        det = fx[:, 0] * fy[:, 1] - fx[:, 1] * fy[:, 0]
        dx = (f[:, 0] * fy[:, 1] - f[:, 1] * fy[:, 0]) / det
        dy = (fx[:, 0] * f[:, 1] - fx[:, 1] * f[:, 0]) / det
        x, y = x - dx, y - dy
        if np.max(np.abs(dx) + np.abs(dy)) < 1e-12:
            break
    return x, y


RESIZE = "a smaller teeth.module or a larger teeth.count"
"""What to change when the teeth overlap, as a gear pair's profile says it."""


def _tooth_ends(gen: _Generator, ids: np.ndarray, nxt: np.ndarray, wrap: np.ndarray):
    """Where each tooth's flanks meet its tip curve: tooth k begins on space k's right flank and
    ends on space k+1's left flank (in their crossing where they cross below the tip): the flank
    parameters, the tip's arc lengths, the tip thickness and which teeth come to a point."""
    teeth = len(ids)
    v_meet, s_meet = gen.meet_tip(np.concatenate([ids, nxt]), np.repeat([1.0, -1.0], teeth))
    v_start, v_end = v_meet[:teeth], v_meet[teeth:]
    s_start, s_end = s_meet[:teeth], s_meet[teeth:] + wrap
    a_pt, b_pt = np.split(gen.tip(np.concatenate([s_start, s_end])), [teeth])
    thickness = np.hypot(*(b_pt - a_pt).T) * np.sign(s_end - s_start)
    pointed = thickness <= 0
    if np.any(pointed):  # flanks cross below the tip: the tooth ends in their crossing

        def crossing(v1, v2):  # tooth k's right flank (space k) less its left (space k+1)
            n = len(v1)
            at = np.concatenate([np.resize(ids[pointed], n), np.resize(nxt[pointed], n)])
            p = gen.parts(np.repeat([4, 0], n), at, np.concatenate([v1, v2]))
            return p[:n] - p[n:]

        v1, v2 = _newton2(crossing, v_start[pointed] * 0.5, v_end[pointed] * 0.5)
        v_start[pointed], v_end[pointed] = v1, v2
    return v_start, v_end, s_start, s_end, thickness, pointed


def _sampled_parts(gen, rack: Rack, centres, ids, ends, tolerance: float, stop):
    """Every part of every space and tooth sampled together, (part, space, from, to) per curve:
    by part number (0 left flank, 1 and 3 the fillets, 2 the root, 4 right flank) a list over
    the spaces, and each tooth's tip by its number (the pointed ones have none)."""
    v_start, v_end, s_start, s_end, _, pointed = ends
    teeth = len(ids)
    left_top = v_end[(ids - 1) % teeth]
    land = np.nonzero(~pointed)[0]
    b0, quarter, v_low = np.full(teeth, rack.fillet_start), np.full(teeth, -np.pi / 2), np.full(teeth, rack.v_low)
    curves = [
        (0, ids, left_top, v_low),  # space k's left flank starts where tooth k−1 ends
        (1, ids, b0, quarter),
        (2, ids, centres - rack.fillet_u, centres + rack.fillet_u),
        (3, ids, quarter, b0),
        (4, ids, v_low, v_start),
        (5, land, s_start[land], s_end[land]),
    ]
    if rack.fillet_u <= 0:
        del curves[2]
    part = np.concatenate([np.full(len(c[1]), c[0]) for c in curves])
    space = np.concatenate([c[1] for c in curves])
    sampled = sample_curves(
        lambda c, x: gen.parts(part[c], space[c], x),
        np.concatenate([c[2] for c in curves]),
        np.concatenate([c[3] for c in curves]),
        tolerance,
        max_points=MAX_POINTS * len(curves),  # each part its own bound, as when sampled one by one
        stop=stop,
    )
    of = {c[0]: sampled[sum(len(d[1]) for d in curves[:j]) :][: len(c[1])] for j, c in enumerate(curves)}
    of.setdefault(2, [np.empty((0, 2))] * teeth)
    return of, dict(zip(land, of[5]))


def _joined(of: dict, tip_of: dict, root_centre: np.ndarray):
    """The ring of spaces and tips joined, each space's loops removed: the ring, the loops removed
    per space and the index of each space's point nearest its root centre."""
    teeth = len(root_centre)
    left, lfil, root, rfil, right = of[0], of[1], of[2], of[3], of[4]
    parts, start, space_root = [], 0, np.empty(teeth, dtype=int)
    loops = np.zeros(teeth, dtype=int)
    spaces = remove_loops_each(
        [np.vstack([left[k], lfil[k][1:], root[k][1:], rfil[k][1:], right[k][1:]]) for k in range(teeth)]
    )
    for k, (space, removed) in enumerate(spaces):
        loops[k] = removed
        parts.append(space[:-1])
        space_root[k] = start + int(np.argmin(np.hypot(*(space[:-1] - root_centre[k]).T)))
        start += len(space) - 1
        if k in tip_of:
            parts.append(tip_of[k][:-1])
            start += len(tip_of[k]) - 1
    return np.vstack(parts), loops, space_root


def _undercut_depth(frame: ArcFrame, rack: Rack, centres: np.ndarray) -> np.ndarray:
    """Undercut by the fold criterion at the lowest straight-flank point of every flank: how deep
    each flank folds (−inf where the pitch curve bends the other way)."""
    fold = math.sin(rack.params.pressure_angle) ** 2
    s_low = np.stack(
        [
            centres - rack.half_width - rack.v_low * (rack.tan_a + rack.cot_a),
            centres + rack.half_width + rack.v_low * (rack.tan_a + rack.cot_a),
        ],
        axis=1,
    ).ravel()
    kappa = frame.curvature(s_low)
    return np.where(kappa > 0, -rack.v_low - fold / np.where(kappa > 0, kappa, 1.0), -np.inf)


def cut_teeth(
    frame: ArcFrame,
    rack: Rack,
    teeth: int,
    phase: float,
    *,
    tolerance: float,
    resize: str = RESIZE,
    stop: threading.Event | None = None,
) -> ToothedGear:
    """Cut ``teeth`` evenly spaced teeth, space k centred at arc length phase + k·pitch.

    The perimeter must be exactly teeth × pitch (the caller chooses the module so).  Setting
    ``stop`` (from another thread) ends the cut with :class:`~.sampling.Stopped`.
    """
    p = rack.pitch
    if not math.isclose(frame.perimeter, teeth * p, rel_tol=1e-9):
        raise DesignError(f"perimeter {frame.perimeter:.9g} mm is not {teeth} × π·m = {teeth * p:.9g} mm")
    centres = phase + p * np.arange(teeth)
    gen = _Generator(frame, rack, centres)
    ids = np.arange(teeth)
    nxt = (ids + 1) % teeth
    wrap = np.where(nxt == 0, frame.perimeter, 0.0)  # space k+1 seen from tooth k, unwrapped
    ends = _tooth_ends(gen, ids, nxt, wrap)
    thickness = ends[4]
    of, tip_of = _sampled_parts(gen, rack, centres, ids, ends, tolerance, stop)
    both = np.concatenate([centres, centres])  # each space's root centre and a module below it
    v_root = np.repeat([rack.v_root, rack.v_root - rack.params.module], teeth)
    root_centre, under_root = np.split(gen._point(both, v_root, both), [teeth])
    ring, loops, space_root = _joined(of, tip_of, root_centre)
    _check_ring(ring, resize)
    flank_s = np.stack([centres - rack.half_width, centres + rack.half_width], axis=1).ravel()
    return ToothedGear(
        outline=Outline((ring,)),
        teeth=teeth,
        rack=rack,
        phase=phase,
        undercut_depth=_undercut_depth(frame, rack, centres),
        flank_phi=frame.angle(flank_s) % (2 * np.pi),
        tip_thickness=thickness,
        tooth_phi=frame.angle(centres + p / 2) % (2 * np.pi),
        space_loops=loops,
        space_root=space_root,
        under_root=under_root,
    )


def _check_ring(ring: np.ndarray, resize: str = RESIZE) -> None:
    """A toothed outline must be one simple counter-clockwise ring: never a wrong shape."""
    if not np.all(np.isfinite(ring)):
        raise DesignError("the tooth outline is not finite (the rack cannot follow this pitch curve)")
    polygon = shapely.Polygon(ring)
    if not polygon.is_valid or ring_area(ring) <= 0:
        raise DesignError(f"the teeth overlap each other: they are too large for this pitch curve; choose {resize}")
