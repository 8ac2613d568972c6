"""Rings moved inwards along their mitred bisectors: the chamfer's inset, one vertex per vertex."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import shapely

from ..errors import DesignError
from .outline import Outline

__all__ = ["inset_ring", "chamfer_fits", "check_chamfer"]


def inset_ring(ring: np.ndarray, distance: float) -> np.ndarray:
    """Each vertex moved ``distance`` into the material along its mitred bisector (material
    lies left of every ring: outer rings run counter-clockwise, holes clockwise).

    Where a segment is shorter than the inset eats (beside a sharp corner) its inset copy turns
    round; such inverted segments are collapsed to their midpoint until none is left, as CAD
    offsetters do, so the ring keeps one inset vertex per vertex for the loft.
    """
    prev = ring - np.roll(ring, 1, axis=0)
    nxt = np.roll(ring, -1, axis=0) - ring
    n1 = np.column_stack([-prev[:, 1], prev[:, 0]]) / np.linalg.norm(prev, axis=1, keepdims=True)
    n2 = np.column_stack([-nxt[:, 1], nxt[:, 0]]) / np.linalg.norm(nxt, axis=1, keepdims=True)
    bisector = n1 + n2
    # mitre length 1/cos of the half angle, clamped at 2 (as CAD offsetters do)
    scale = np.minimum(2.0 / np.maximum(np.einsum("ij,ij->i", bisector, bisector), 1e-12), 4.0)
    inset = ring + distance * bisector * scale[:, None]
    for _ in range(50):
        seg = np.roll(inset, -1, axis=0) - inset
        inverted = np.einsum("ij,ij->i", seg, nxt) <= 0
        if not np.any(inverted):
            break
        i = np.nonzero(inverted)[0]
        j = (i + 1) % len(inset)
        mid = 0.5 * (inset[i] + inset[j])
        inset[i], inset[j] = mid, mid
    return inset


def chamfer_fits(outer: np.ndarray, holes: Sequence[np.ndarray], chamfer: float) -> bool:
    """Whether a solid's cap takes ``chamfer``: ``outer`` and ``holes`` inset by it still bound
    a valid polygon (the test :func:`~gearcad.export.loft.loft` makes of its end sections)."""
    return shapely.Polygon(inset_ring(outer, chamfer), [inset_ring(h, chamfer) for h in holes]).is_valid


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
        f"output.chamfer = {chamfer:g}: too large for the teeth of {name} (the inset crosses itself); "
        f"use output.chamfer ≤ {math.floor(0.9 * good / 10) / 100:.2f} mm"
    )
