"""How far a generating rack would cut beyond an outline where the pitch curve turns concave.

The outline of :mod:`.gear` is the rack's local envelope: every rack point is kept at the
instant its normal passes through the pitch point.  On a convex stretch the rack stands clear of
the gear at every other instant, so the envelope is what a rack cutter leaves.  On a concave
stretch of radius ρ the rolling line dips into the gear on both sides of the contact, x²/(2ρ)
deep at x from it, and a rack tooth carries that dip into the flanks and roots it generated a
moment before or after: a rack (or a hob, a long rack) removes material the outline keeps.

The rack is placed as :func:`~.gear.cut_teeth` places it (rack coordinate u at
C(s) + (u − s)·T(s) + v·N(s) at the pose s) and measured against the outline:

* **one rack tooth** over its own generating window, the poses |s − U| ≤ W at which some point of
  the tooth centred at U generates the outline (W = w₀ + h_a/(sin α·cos α): its flank's tip);
* **a long rack or hob** (:data:`REACH` teeth either side of the contact), every tooth at every
  pose at which it reaches the gear's blank.

A rack point inside the outline is as deep as its distance to it; the deepest over the rack's
sampled boundary is the overcut (the material removed is a crescent whose deepest point lies
on the rack's boundary).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from .depth_probe import DepthProbe
from .rack import Rack

__all__ = [
    "Overcut",
    "RackOvercut",
    "REACH",
    "PROCESSES",
    "generating_window",
    "rack_cell",
    "rack_overcut",
    "concave_spans",
]

PROCESSES = ("laser", "waterjet", "printing", "wire EDM", "shaper cutter")
"""Processes that make an outline as drawn (a shaper cutter of pitch radius well under the
smallest concave radius, as for an internal gear)."""

REACH = 24
"""Rack teeth either side of the contact that a long rack or hob brings to the gear."""

POSES = 200_000
"""Most tooth poses searched (bounded time on a curve with many concave stretches and teeth):
beyond it the hob's reach shrinks, to no less than two generating windows."""

STEPS = 8
"""Poses per pitch of the first search; the deepest are then refined on grids 8 and 64 times finer."""


@dataclass(frozen=True)
class Overcut:
    """The deepest cut of a rack beyond the outline, and where it is."""

    depth: float
    """mm (0 where the rack stays outside)."""
    phi: float
    """Polar angle of the deepest point about the pivot, rad (NaN where there is none)."""
    arc: float
    """Arc length of the pitch curve at that angle, mm from φ = 0."""
    height: float
    """The deepest point's radial distance from the pitch curve, mm (negative: below it)."""
    space: int
    """The tooth space whose rack tooth cuts there (−1 where none does)."""
    offset: float
    """How far that tooth was from its own generating contact, mm (pose − U)."""
    zone: str
    """What part of the rack cuts: "root" (its tip and fillet), "flank" or "land"."""
    point: tuple[float, float] = (math.nan, math.nan)
    """The deepest point in the gear's frame (about its pivot), mm."""

    def where(self) -> dict | None:
        """The place as a report's dict (None where nothing is cut)."""
        return (
            None
            if self.space < 0
            else {k: v for k, v in vars(self).items() if k != "depth"} | {"point": list(self.point)}
        )


NONE = Overcut(0.0, math.nan, math.nan, math.nan, -1, math.nan, "")


@dataclass(frozen=True)
class RackOvercut:
    """What a rack cutter would take off beyond a gear's outline on its concave stretches."""

    tooth: Overcut
    """One rack tooth within its own generating window: what any rack cutter removes."""
    flank: Overcut
    """The same, where the rack's straight flanks cut."""
    hob: Overcut
    """A long rack or hob: every tooth at every pose at which it reaches the blank."""
    window: float
    """W: half the generating window of one tooth, mm."""
    tolerance: float
    """The writing tolerance the depths are judged by, mm."""

    @property
    def cannot(self) -> tuple[str, ...]:
        """The rack processes that would cut beyond the outline by more than the tolerance."""
        return tuple(n for n, o in (("rack", self.tooth), ("hob", self.hob)) if o.depth > self.tolerance)

    def as_dict(self) -> dict:
        """The report's ``gears[].rack_overcut``."""
        rack = tuple(n for n in ("rack", "hob") if n not in self.cannot)
        return {
            "depth": self.tooth.depth,
            "where": self.tooth.where(),
            "flank_depth": self.flank.depth,
            "flank_where": self.flank.where(),
            "hob_depth": self.hob.depth,
            "hob_where": self.hob.where(),
            "window": self.window,
            "processes_as_drawn": [*PROCESSES, *rack],
            "not": list(self.cannot),
        }

    def sentence(self, name: str) -> str:
        """One line for the page's details and the ``rack-overcut`` warning."""
        t, h = self.tooth, self.hob
        where = f" at φ = {math.degrees(t.phi):.2f}° ({t.zone}, space {t.space})" if t.space >= 0 else ""
        made = "laser, waterjet, printing, wire EDM or a shaper cutter"
        verdict = (
            f"make it as drawn by {made}, not by {' or '.join(self.cannot)}"
            if self.cannot
            else "a rack makes it as drawn"
        )
        return (
            f"{name}: a rack tooth within its generating window would cut {_size(t.depth)} beyond the outline"
            f"{where}, a hob {_size(h.depth)}; {verdict}"
        )


def _size(depth: float) -> str:
    return f"{depth:.3g} mm" if depth >= 0.1 else f"{depth * 1e3:.3g} µm"


def concave_spans(frame, intervals) -> list[tuple[float, float]]:
    """Concave stretches given by polar angle (φ_from, φ_to), rad, as arc lengths on ``frame``."""
    return [tuple(float(a) for a in frame.arc(np.array(pair, dtype=float))) for pair in intervals]


def generating_window(rack: Rack) -> float:
    """W: a rack tooth centred at U shapes the gear at poses U − W … U + W (its flank's point at
    the tip height h_a is generated at s* = U ± (w₀ + h_a·(tan α + cot α)), the farthest of any)."""
    a = rack.params.pressure_angle
    return rack.half_width + rack.v_tip / (math.sin(a) * math.cos(a))


def rack_cell(rack: Rack, *, step: float) -> tuple[np.ndarray, np.ndarray]:
    """One pitch of the rack's cutting boundary about a tooth centred at u = 0: (n, 2) points in
    (u, v) no farther apart than ``step`` mm, and each point's zone (0 land, 1 flank, 2 root)."""
    k = rack
    land = k.v_tip + 0.25 * k.params.module
    beta = np.linspace(-math.pi / 2, k.fillet_start, 64)
    fillet = np.column_stack([k.fillet_u + k.radius * np.cos(beta), k.fillet_v + k.radius * np.sin(beta)])
    top = k.half_width + land * k.tan_a
    right = np.vstack([[[0.0, k.v_root]], fillet, [[top, land], [k.pitch / 2, land]]])
    half = shapely.get_coordinates(shapely.segmentize(shapely.LineString(right), step))
    points = np.vstack([half[:0:-1] * [-1.0, 1.0], half])
    zone = np.where(points[:, 1] >= land - 1e-12, 0, np.where(points[:, 1] > k.v_low + 1e-12, 1, 2))
    return points, zone


def _place(frame, cell: np.ndarray, centre: float, poses: np.ndarray) -> np.ndarray:
    """The cell of the tooth centred at ``centre`` at each pose: (poses, n, 2) in the gear frame."""
    c, t, n = frame.frame(poses)
    u = centre + cell[:, 0] - poses[:, None]
    return c[:, None, :] + u[..., None] * t[:, None, :] + cell[:, 1][None, :, None] * n[:, None, :]


def _around(spans, perimeter: float, a: np.ndarray, b) -> np.ndarray:
    """Whether a concave span (arc lengths, any turn) lies between ``a`` and ``b``."""
    hit = np.zeros(np.broadcast(a, b).shape, dtype=bool)
    for lo, hi in spans:
        for turn in (-perimeter, 0.0, perimeter):
            hit |= (np.minimum(a, b) < hi + turn) & (np.maximum(a, b) > lo + turn)
    return hit


def rack_overcut(
    frame, rack: Rack, teeth: int, phase: float, ring: np.ndarray, concave, *, tolerance: float
) -> RackOvercut | None:
    """How far the rack that cut ``teeth`` spaces (space k centred at arc length phase + k·pitch
    on ``frame``) reaches past ``ring`` (the gear's outline, counter-clockwise, mm) about the
    ``concave`` stretches ((s_from, s_to) arc-length pairs, mm); None where there are none.
    ``tolerance`` (mm) is what the depths are judged by (:attr:`RackOvercut.cannot`).

    Only a tooth with a concave stretch between its pose and its own contact can cut beyond the
    envelope (over a convex arc the rolling line lifts it clear).
    Every such tooth is searched at :data:`STEPS` poses a pitch with a coarse rack; the two
    deepest of each kind are refined with a fine one.
    """
    if not len(concave):
        return None
    p, perimeter, m = rack.pitch, frame.perimeter, rack.params.module
    w = generating_window(rack)
    coarse, coarse_zone = rack_cell(rack, step=m / 12)
    probe = DepthProbe(ring, m / 20)
    reach = min(perimeter / 2, REACH * p)
    spans = [(lo, hi if hi > lo else hi + perimeter) for lo, hi in concave]
    centres = phase + p * np.arange(teeth)
    near = _around(spans, perimeter, centres - reach, centres + reach)
    if np.count_nonzero(near) * 2 * reach / p * STEPS > POSES:  # many teeth on many concave stretches
        reach = max(POSES / (np.count_nonzero(near) * 2 * STEPS) * p, 2 * w)
    kinds = {"tooth": coarse_zone >= 0, "flank": coarse_zone == 1, "hob": coarse_zone >= 0}
    found: dict[str, list[tuple[float, int, float]]] = {key: [] for key in kinds}
    for k in np.nonzero(near)[0]:
        centre = centres[k]
        poses = centre + np.arange(-reach, reach + p / STEPS / 2, p / STEPS)
        poses = poses[_around(spans, perimeter, poses, centre)]
        sparse = _place(frame, coarse[::4], centre, poses)  # first drop the poses that cut nothing
        poses = poses[np.unique(probe.inside(sparse.reshape(-1, 2)) // len(sparse[0]))]
        own = np.abs(poses - centre) <= w
        if own.any():
            poses = np.r_[poses, centre - w, centre + w]
            own = np.r_[own, True, True]
        if not len(poses):
            continue
        placed = _place(frame, coarse, centre, poses)
        xy, caps = placed.reshape(-1, 2), probe.caps(placed)
        for key, zones in kinds.items():
            keep = zones[None, :] & (own[:, None] if key != "hob" else True)
            d, i = probe.deepest(xy, np.where(keep, caps, -np.inf).ravel(), _second(found[key]))
            if i >= 0:
                found[key].append((d, int(k), float(poses[i // len(coarse)])))
    cell, zone = rack_cell(rack, step=m / 50)
    best = {}
    for key, items in found.items():
        keep = zone >= 0 if key != "flank" else zone == 1
        clip = w if key != "hob" else reach
        refined = [
            _refine(frame, probe, (cell[keep], zone[keep]), k, centres[k], pose, p / STEPS, clip)
            for _, k, pose in sorted(items, reverse=True)[:2]
        ]
        best[key] = max(refined, key=lambda o: o.depth, default=NONE)
    return RackOvercut(best["tooth"], best["flank"], best["hob"], w, tolerance)


def _second(items) -> float:
    """The second deepest found (0 before two are): a tooth less deep cannot be refined."""
    return sorted(d for d, _, _ in items)[-2] if len(items) >= 2 else 0.0


def _refine(frame, probe: DepthProbe, cell, k: int, centre: float, pose: float, step: float, clip: float) -> Overcut:
    """The deepest point of the rack cell (points, zones) about ``pose``, on a grid of poses
    eight times finer, twice over (within ``clip`` of the contact)."""
    points, zones = cell
    depth, at = 0.0, -1
    for _ in range(2):
        poses = np.clip(pose + step * np.arange(-8, 9) / 8, centre - clip, centre + clip)
        step /= 8
        placed = _place(frame, points, centre, poses)
        d, i = probe.deepest(placed.reshape(-1, 2), probe.caps(placed).ravel(), depth)
        if d > depth:
            depth, at, pose = d, i % len(points), float(poses[i // len(points)])
    if at < 0:
        return NONE
    point = _place(frame, points[at : at + 1], centre, np.array([pose]))[0, 0]
    phi = float(math.atan2(point[1], point[0]) % (2 * math.pi))
    curve = getattr(frame, "curve", None)  # a pitch curve polar about the pivot (an ArcFrame)
    radius = float(curve.r(np.array([phi]))[0]) if curve is not None else math.nan
    return Overcut(
        depth=depth,
        phi=phi,
        arc=float(frame.arc(phi)) if curve is not None else math.nan,
        height=float(np.hypot(*point)) - radius,
        space=int(k),
        offset=pose - centre,
        zone=("land", "flank", "root")[int(zones[at])],
        point=(float(point[0]), float(point[1])),
    )
