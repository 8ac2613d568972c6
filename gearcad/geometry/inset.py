"""Rings moved inwards along their mitred bisectors: the chamfer's inset, one vertex per vertex."""

from __future__ import annotations

import numpy as np
import shapely

from ..errors import DesignError
from .outline import Outline

__all__ = ["inset_ring", "check_chamfer"]


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


def check_chamfer(outline: Outline, thickness: float, chamfer: float, *, name: str) -> None:
    """Refuse a chamfer the part cannot take: half the thickness or more, or an inset that crosses
    itself (teeth too thin for it)."""
    if chamfer <= 0:
        return
    if 2 * chamfer >= thickness:
        raise DesignError(f"output.chamfer = {chamfer:g}: must be under half the thickness {thickness:g}")
    insets = [inset_ring(np.asarray(r, dtype=float), chamfer) for r in outline.rings]
    if not shapely.Polygon(insets[0], insets[1:]).is_valid:
        raise DesignError(f"output.chamfer = {chamfer:g}: too large for the teeth of {name} (the inset crosses itself)")
