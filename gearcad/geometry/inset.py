"""Rings moved inwards along their mitred bisectors: the chamfer's inset, one vertex per vertex."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import shapely

from ..errors import DesignError
from .outline import Outline

__all__ = ["inset_ring", "inset", "chamfer_fits", "check_chamfer"]


def inset_ring(ring: np.ndarray, distance: float) -> np.ndarray:
    """:func:`inset` without the dropped segments."""
    return inset(ring, distance)[0]


def inset(ring: np.ndarray, distance: float) -> tuple[np.ndarray, np.ndarray]:
    """Each vertex moved ``distance`` into the material along its mitred bisector (material
    lies left of every ring: outer rings run counter-clockwise, holes clockwise).

    Where a segment is shorter than the inset eats (beside a sharp corner) its inset copy turns
    round: such a segment is dropped, as CAD offsetters do, and its vertices go where the inset
    lines of the segments either side of it meet (the exact mitred inset); passes repeat until no
    segment is inverted.  The ring keeps one inset vertex per vertex for the loft.  Returns the
    inset ring and which segments (vertex k to k + 1) were dropped, (n,) bool.
    """
    ring = np.asarray(ring, dtype=float)
    n = len(ring)
    step = np.roll(ring, -1, axis=0) - ring  # segment k: vertex k to k + 1
    unit = step / np.linalg.norm(step, axis=1, keepdims=True)
    normal = np.column_stack([-unit[:, 1], unit[:, 0]])  # into the material
    base = ring + distance * normal  # a point of each segment's inset line
    prev, nxt = np.roll(normal, 1, axis=0), normal
    bisector = prev + nxt
    # mitre length 1/cos of the half angle, clamped at 2 (as CAD offsetters do)
    scale = np.minimum(2.0 / np.maximum(np.einsum("ij,ij->i", bisector, bisector), 1e-12), 4.0)
    moved = ring + distance * bisector * scale[:, None]
    live = np.ones(n, dtype=bool)
    for _ in range(n):
        seg = np.roll(moved, -1, axis=0) - moved
        inverted = live & (np.einsum("ij,ij->i", seg, step) <= 0)
        if not np.any(inverted) or np.count_nonzero(live & ~inverted) < 3:
            break
        live &= ~inverted
        kept = np.nonzero(live)[0]
        vertices = np.nonzero(~live | ~np.roll(live, 1))[0]  # beside a dropped segment
        after = kept[np.searchsorted(kept, vertices) % len(kept)]  # the live segment leaving
        before = kept[np.searchsorted(kept, vertices) - 1]  # and the one arriving
        moved[vertices] = _meet(base[before], unit[before], base[after], unit[after])
    return moved, ~live


def _meet(p: np.ndarray, d: np.ndarray, q: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Where the lines p + t·d and q + u·e meet, (n, 2); the midpoint of p and q where parallel."""
    cross = d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0]
    w = q - p
    t = np.divide(w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0], cross, out=np.zeros(len(p)), where=np.abs(cross) > 1e-12)
    meet = p + t[:, None] * d
    return np.where((np.abs(cross) > 1e-12)[:, None], meet, 0.5 * (p + q))


def chamfer_fits(outer: np.ndarray, holes: Sequence[np.ndarray], chamfer: float) -> bool:
    """Whether a solid's cap takes ``chamfer``: ``outer`` and ``holes`` inset by it still bound
    a valid polygon (the test :func:`~gearcad.export.loft.loft` makes of its end sections), and no
    inset drops the whole stretch between two corners (a tooth's tip land: knife edges)."""
    insets = []
    for ring in (outer, *holes):
        ring = np.asarray(ring, dtype=float)
        moved, dropped = inset(ring, chamfer)
        if _corners_eaten(ring, dropped) >= 2:
            return False
        insets.append(moved)
    return shapely.Polygon(insets[0], insets[1:]).is_valid


def check_chamfer(
    outline: Outline, thickness: float, chamfer: float, *, name: str, sections: Sequence[np.ndarray] = ()
) -> None:
    """Refuse a chamfer the part cannot take: half the thickness or more, or an inset that crosses
    itself (teeth too thin for it) — of the outline, or of ``sections`` (other outer rings of the
    solid's caps, e.g. a helical gear's end sections, with the outline's holes).  The refusal
    suggests 90 % of the largest chamfer whose caps fit, rounded down to 0.01 mm: the walls
    between a cap and the next section can fold a little before the cap does (a herringbone's
    sections also move with the chamfer)."""
    if chamfer <= 0:
        return
    if 2 * chamfer >= thickness:
        raise DesignError(f"output.chamfer = {chamfer:g}: must be under half the thickness {thickness:g}")
    rings = [np.asarray(r, dtype=float) for r in outline.rings]
    outers = [rings[0], *(np.asarray(r, dtype=float) for r in sections)]

    def fits(c: float) -> bool:
        return all(chamfer_fits(outer, rings[1:], c) for outer in outers)

    if fits(chamfer):
        return
    good, bad = 0, math.ceil(chamfer / 1e-3)  # in thousandths of a mm: no chamfer always fits
    while bad - good > 1:
        mid = (good + bad) // 2
        good, bad = (mid, bad) if fits(mid * 1e-3) else (good, mid)
    raise DesignError(
        f"output.chamfer = {chamfer:g}: too large for the teeth of {name} "
        "(the inset crosses itself or eats their tip lands); "
        f"use output.chamfer ≤ {math.floor(0.9 * good / 10) / 100:.2f} mm"
    )


CORNER = np.radians(20)
"""A vertex turning more than this is a corner (a tooth's tip corner turns ~60°; sampled curves
turn a few degrees a vertex)."""


def _corners_eaten(ring: np.ndarray, dropped: np.ndarray) -> int:
    """The most corners in one run of consecutive dropped segments (its end vertices included)."""
    if not np.any(dropped) or np.all(dropped):
        return int(np.any(dropped)) * len(ring)
    step = np.roll(ring, -1, axis=0) - ring
    back = np.roll(step, 1, axis=0)
    turn = np.abs(np.arctan2(back[:, 0] * step[:, 1] - back[:, 1] * step[:, 0], np.einsum("ij,ij->i", back, step)))
    corner = turn > CORNER
    start = int(np.argmin(dropped))  # a kept segment: no run wraps past it
    dropped, corner = np.roll(dropped, -start), np.roll(corner, -start)
    most, count = 0, 0
    for k in range(len(ring)):  # segment k joins vertices k and k + 1
        if dropped[k]:
            count += int(corner[k]) if count == 0 or not dropped[k - 1] else 0
            count += int(corner[(k + 1) % len(ring)])
            most = max(most, count)
        else:
            count = 0
    return most
