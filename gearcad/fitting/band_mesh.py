"""The backlash band of any placed mesh: a carrier train's (the ring included) or a roller's on
its toothed body, measured as :mod:`.band` measures a gear pair's.

A mesh is given in gear 1's own frame at each position of its cycle: where gear 2's pivot sits,
how far it is turned, the pitch point, and the way gear 2's pivot moves when a centre-distance
error takes play (:class:`MeshGeometry`).  For an external mesh that is towards gear 1's pivot
(the centres closer); for an internal one (a pinion in a ring) away from it, the centres farther
apart: the pinion then sits deeper in the ring's tooth spaces.  (On the operating pitch circles
a ring's space and a pinion's tooth are 2r'(e/2r + inv α − inv α') and 2r'(s/2r + inv α − inv α'),
so the play is 2a'(inv α − inv α'): it falls as a' = a·cos α/cos α' grows — the sign opposite to
an external pair's 2a'(inv α' − inv α).)  A roller's axle moves along the common normal towards
the body.  Both parts are offset by the edge (shapely's buffer; a ring's teeth grow into its
spaces), gear 2 placed with the error, and turned each way about its pivot until it touches gear 1
(found exactly, :mod:`~..geometry.sweep`): the two free turns times gear 2's pitch radius at the
contact are the play, mm on its pitch curve.  Where the parts overlap as placed, the shrink ε that
frees them counts −4ε/cos α.  Only a window of three modules about the contact is offset.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely

from ..geometry.depth import inradius, overlap_exceeds
from ..geometry.outline import place_each
from ..geometry.sweep import free_turns
from ..threads import side_by_side
from .band import Band, band_of
from .play import cut_about

__all__ = ["MeshGeometry", "clip", "mesh_band", "mesh_play", "signed_mesh_play"]

_WINDOW = 3.0
"""Radius of the window about the contact, modules: contact stays within about one pitch."""


@dataclass(frozen=True)
class MeshGeometry:
    """A mesh in gear 1's frame (mm, rad), at n positions over its cycle."""

    shapes: tuple[shapely.Geometry, shapely.Geometry]
    """Both parts as drawn about their pivots (a ring: a polygon with its toothed hole)."""
    phi1: np.ndarray
    """(n,) gear 1's turn from the assembly at each position (reported as the driver angle)."""
    centre2: np.ndarray
    """(n, 2) gear 2's pivot."""
    angle2: np.ndarray
    """(n,) gear 2's turn: its own coordinates are turned so, then moved to ``centre2``."""
    contact: np.ndarray
    """(n, 2) the pitch point."""
    tighter: np.ndarray
    """(n, 2) unit vector: gear 2's pivot moved this way takes play (a centre-distance error)."""
    module: float
    pressure_angle: float
    teeth: np.ndarray
    """(n,) gear 1's tooth at the contact (index from its first)."""
    pair: object | None = None
    """What the proven certificate measures: the same mesh as a :class:`~.play.PairGeometry` about
    fixed centres (a carrier train's; its gear 1 the one that is not a ring), or as a
    :class:`~.moving.MovingMesh` (a roller's, its axle moving along the body); None: neither."""

    def at(self, keep: np.ndarray) -> MeshGeometry:
        """The same mesh at the positions ``keep`` (a boolean mask) only."""
        fields = ("phi1", "centre2", "angle2", "contact", "tighter", "teeth")
        return replace(self, **{f: getattr(self, f)[keep] for f in fields})


def _rotate(points: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]])


def contacts(g: MeshGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The contact at each position in gear 1's frame, and in gear 2's own (mm): the centres of
    the windows :func:`mesh_play` measures with."""
    return g.contact, _rotate(g.contact - g.centre2, -g.angle2)


def clip(g: MeshGeometry, grow: float) -> tuple[np.ndarray, np.ndarray]:
    """Each part about the contact at each position, in its own coordinates: cut once, wide
    enough for any offset up to ``grow`` mm, and then only offset and trimmed (:func:`mesh_play`)."""
    big = _WINDOW * g.module * 7 / 6 + grow
    own = _rotate(g.contact - g.centre2, -g.angle2)  # the contact in gear 2's own coordinates
    return tuple(cut_about(shape, centres, big) for shape, centres in ((g.shapes[0], g.contact), (g.shapes[1], own)))


def _windows(pieces: np.ndarray, centres: np.ndarray, radius: float, offset, tol: float) -> np.ndarray:
    """``pieces`` grown by ``offset`` mm (scalar or per centre), trimmed to ``radius`` about each centre."""
    largest = float(np.max(np.abs(offset)))
    if largest:
        steps = max(2, int(math.ceil(math.pi / 4 / math.acos(max(1 - tol / largest, -1.0)))))
        pieces = shapely.buffer(pieces, offset, quad_segs=steps)
    return shapely.intersection(pieces, shapely.buffer(shapely.points(centres), radius, quad_segs=16))


def mesh_play(
    g: MeshGeometry,
    offsets: tuple,
    shift: float,
    tol: float,
    *,
    reach: float,
    steps: int = 1,
    pieces: tuple[np.ndarray, np.ndarray] | None = None,
    halves: list | None = None,
    windows: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Free play at each position (mm on gear 2's pitch curve); NaN where the parts overlap as
    placed.  ``offsets`` grow gear 1 and gear 2 (mm, scalars or per position), ``shift`` moves
    gear 2's pivot along ``g.tighter`` (mm; negative: the other way), ``reach`` bounds the play
    sought; ``pieces`` the parts cut about the contact (:func:`clip`; default: cut here);
    ``halves`` (a list): the free turn each way (rad, 0 where they overlap) is appended to it;
    ``windows``: each part's window about the contact, made already (gear 2's in its own frame,
    :func:`contacts`).

    Each way, gear 2 is turned until it touches gear 1, found exactly as the least turn at which
    a vertex of either window meets an edge of the other (:func:`~..geometry.sweep.free_turns`);
    ``steps`` 0: only whether they are free (0 where they are)."""
    if windows is None:
        radius = _WINDOW * g.module
        if pieces is None:
            pieces = clip(g, float(max(np.max(np.abs(o)) for o in offsets)))
        contact, own = contacts(g)
        w1 = _windows(pieces[0], contact, radius, offsets[0], tol)
        w2 = _windows(pieces[1], own, radius, offsets[1], tol)
    else:
        w1, w2 = windows
    shapely.prepare(w1)
    coords, which = shapely.get_coordinates(w2, return_index=True)
    centre = g.centre2 + shift * g.tighter
    place = _placer(w2, coords, which, g.angle2, centre)
    arm = np.hypot(*(g.contact - g.centre2).T)  # gear 2's pitch radius at the contact
    limit = min(reach, 1.2 * math.pi * g.module) / arm  # more than a pitch never frees a tooth
    zero = np.zeros_like(g.phi1)
    placed = place(zero)[0]
    free = ~overlap_exceeds(w1, placed, 1e-9 * g.module**2)
    if not steps or not free.any():  # only whether they are free: no play to measure
        return np.where(free, 0.0, np.nan)
    live = np.flatnonzero(free)  # where they overlap the play is NaN: only the free positions are turned
    up, down = np.zeros_like(g.phi1), np.zeros_like(g.phi1)
    up[live], down[live] = free_turns(w1[live], placed[live], centre[live], limit[live])
    if halves is not None:
        halves += [up, down]
    return np.where(free, (up + down) * arm, np.nan)


def _placer(w2, coords: np.ndarray, which: np.ndarray, angle2: np.ndarray, centre: np.ndarray):
    """place(turn) -> gear 2's windows ``w2`` (their ``coords`` by window ``which``) turned by
    ``angle2 + turn`` about ``centre``, one of each per window, and their coordinates."""

    def place(turn):
        xy = place_each(coords, which, angle2 + turn, centre)
        return shapely.set_coordinates(w2.copy(), xy), xy

    return place


def signed_mesh_play(g: MeshGeometry, pieces, edge: float, shift: float, tol: float, *, reach: float) -> np.ndarray:
    """:func:`mesh_play` with both parts grown by ``edge``, negative where jammed: the least
    shrink ε of both parts that frees it counts −4ε/cos α (a rack-cut flank moved ε along its
    normal moves ε/cos α along the pitch curve, so the play grows by 4ε/cos α as both parts
    shrink by ε).

    A jammed position's ε is the inradius of the parts' overlap as placed
    (:func:`~..geometry.depth.inradius`: the shrunk parts share a point exactly while the overlap
    holds a disc of radius ε) — one overlay and a bisection on that small overlap, as a gear
    pair's (:func:`~.play.signed_play`); an overlap that reaches its window's rim (a bite wider
    than the window, whose rim is no outline) has the shrink bisected on the parts' offsets
    instead (:func:`_shrink_to_free`)."""
    play = mesh_play(g, (edge, edge), shift, tol, reach=reach, pieces=pieces)
    jammed = np.isnan(play)
    if not jammed.any():
        return play
    sub, cut = g.at(jammed), (pieces[0][jammed], pieces[1][jammed])
    most, radius = 0.5 * g.module, _WINDOW * g.module
    contact, own = contacts(sub)
    w1 = _windows(cut[0], contact, radius, edge, tol)
    w2 = _windows(cut[1], own, radius, edge, tol)
    coords, which = shapely.get_coordinates(w2, return_index=True)
    placed = _placer(w2, coords, which, sub.angle2, sub.centre2 + shift * sub.tighter)(np.zeros_like(sub.phi1))[0]
    lap = shapely.intersection(w1, placed)
    # within both windows' rims (gear 2's disc moves with its pivot's shift)
    rims = [
        shapely.buffer(shapely.points(c), 0.95 * radius, quad_segs=16) for c in (contact, contact + shift * sub.tighter)
    ]
    inside = shapely.within(lap, rims[0]) & shapely.within(lap, rims[1])
    shrink = np.full(len(sub.phi1), most)
    shrink[inside] = np.minimum(inradius(lap[inside], 1e-6 * g.module), most)
    wide = np.flatnonzero(~inside)
    if len(wide):
        shrink[wide] = _shrink_to_free(
            sub.at(wide), (cut[0][wide], cut[1][wide]), edge, shift, tol, reach=reach, most=most
        )
    play[jammed] = -4 * shrink / math.cos(g.pressure_angle)
    return play


def _shrink_to_free(g: MeshGeometry, pieces, edge: float, shift: float, tol: float, *, reach: float, most: float):
    """The least shrink (mm, to a quarter tolerance or 2 % of itself; at most ``most``) of both
    parts grown by ``edge`` under which they are free as placed: doubled until free, then its
    play extrapolated back (4ε/cos α), two quick looks either side confirming it (free just past
    it, jammed just short), bisected where they do not (a tip in a root, where the relation is
    not linear)."""
    cos_a = math.cos(g.pressure_angle)

    def free(shrink: np.ndarray, at: np.ndarray | None = None, steps: int = 0) -> np.ndarray:
        """The play with both parts shrunk (at the positions ``at``: default all)."""
        few, part = (g, pieces) if at is None else (g.at(at), (pieces[0][at], pieces[1][at]))
        return mesh_play(few, (edge - shrink, edge - shrink), shift, tol, reach=reach, steps=steps, pieces=part)

    # what the stack adds (the edge, the shift's share along the flanks) frees the drawn parts
    start = max(edge, 0.0) + abs(shift) * math.sin(g.pressure_angle) + 2 * tol
    shrink = np.full(len(g.phi1), min(most, start))
    for _ in range(12):
        stuck = np.isnan(free(shrink))
        if not stuck.any() or np.all(shrink[stuck] >= most):
            break
        shrink = np.where(stuck, np.minimum(2 * shrink, most), shrink)
    need = np.clip(shrink - free(shrink, steps=1) * cos_a / 4, 0.0, shrink)  # NaN where even `most` jams
    lo, hi = np.zeros_like(shrink), np.where(np.isnan(need), most, need)
    measured = np.flatnonzero(~np.isnan(need))
    step = tol / 4
    past = ~np.isnan(free(need[measured] + step, measured))
    short = (need[measured] <= step) | np.isnan(free(np.maximum(need[measured] - step, 0.0), measured))
    # not free just past it: between there and the shrink that freed it; free just short: below
    lo[measured[~past]], hi[measured[~past]] = need[measured[~past]] + step, shrink[measured[~past]]
    lo[measured[~short]], hi[measured[~short]] = 0.0, need[measured[~short]] - step
    doubtful = measured[~(past & short)]
    for _ in range(14):  # to a quarter tolerance, or 2 % of a deep jam's shrink (its verdict is settled)
        doubtful = doubtful[hi[doubtful] - lo[doubtful] > np.maximum(step, 0.02 * hi[doubtful])]
        if not len(doubtful):
            break
        mid = 0.5 * (lo[doubtful] + hi[doubtful])
        ok = ~np.isnan(free(mid, doubtful))
        hi[doubtful], lo[doubtful] = np.where(ok, mid, hi[doubtful]), np.where(ok, lo[doubtful], mid)
    return hi


def mesh_band(
    g: MeshGeometry, *, edge: tuple[float, float, float], spread: float, tol: float, name: str, backlash: float = 0.0
) -> Band:
    """The band of one mesh: the play as drawn, with every edge at its largest and gear 2's pivot
    ``spread`` mm towards the tight side, and at its smallest with it as far the other way;
    ``tol`` the outline tolerance (the worst case keeps twice it free), ``backlash`` the play the
    teeth are cut with (bounds the search with the stack)."""
    alpha = g.pressure_angle
    reach = backlash + 4 * max(abs(e) for e in edge) / math.cos(alpha) + 2 * spread * math.tan(alpha) + 0.5 * g.module
    cases = [(edge[0], 0.0), (edge[2], spread), (edge[1], -spread)]
    if not any(edge) and not spread:  # exact parts: the three cases are one
        cases = cases[:1]
    pieces = clip(g, max(abs(e) for e in edge) + 0.5 * g.module)  # the bisection shrinks up to half a module
    with side_by_side() as pool:  # GEOS releases the GIL: the cases side by side
        jobs = [pool.submit(signed_mesh_play, g, pieces, e, s, tol, reach=reach) for e, s in cases]
        plays = [job.result() for job in jobs]
    nominal, tight, wide = (plays * 3)[:3] if len(plays) == 1 else plays
    return band_of(name, (nominal, tight, wide), g.teeth, g.phi1, edge=edge, spread=spread, tol=tol, alpha=alpha)
