"""A solid lofted through transverse sections: the helical and herringbone gears' solids.

Every section has the same number of vertices, vertex j of each the same point of the same tooth
(``teeth/correspond.py``).  Consecutive sections are joined by a strip of quads, each split along its
shorter diagonal (the one that follows the twist: a triangle then spans the larger of the
section's chord and the twist's sideways step, never their sum); the end sections are capped with
manifold3d's triangulation; bores are straight walls from bottom to top.  manifold3d checks the
result, whose status must be ``NoError``.
"""

from __future__ import annotations

from collections.abc import Sequence

import manifold3d as m3d
import numpy as np
import shapely

from ..errors import DesignError
from ..geometry.diagonals import rising_diagonals
from ..geometry.inset import inset_ring
from .mesh import Solid, cap_triangles, checked_solid

__all__ = ["loft"]


def _strip(lo: np.ndarray, hi: np.ndarray, lo_xy: np.ndarray, hi_xy: np.ndarray) -> np.ndarray:
    """Triangles joining two rings of equal length (vertex indices ``lo`` and ``hi``, one height
    each), facing out for a ring with its material on its left; each quad split along its
    shorter diagonal."""
    nxt = np.roll(np.arange(len(lo)), -1)
    a, b, c, d = lo, lo[nxt], hi[nxt], hi
    rise = rising_diagonals(lo_xy, hi_xy)[:, None]
    first = np.where(rise, np.column_stack([a, b, c]), np.column_stack([a, b, d]))
    second = np.where(rise, np.column_stack([a, c, d]), np.column_stack([b, c, d]))
    return np.vstack([first, second])


def _chamfered(rings: np.ndarray, z: np.ndarray, holes: list, chamfer: float, name: str):
    """The sections inset by the chamfer at each height, and the heights and insets of the holes'
    rings (their ends chamfered too); a chamfer too large for the thickness or the teeth refuses."""
    levels = len(z)
    bottom, top = float(z[0]), float(z[-1])
    if chamfer > 0:
        if 2 * chamfer >= top - bottom:
            raise DesignError(f"output.chamfer = {chamfer:g}: must be under half the thickness {top - bottom:g}")
        depth = np.maximum(0.0, np.maximum(chamfer - (z - bottom), chamfer - (top - z)))
        rings = np.stack([inset_ring(r, d) if d > 0 else r for r, d in zip(rings, depth)])
        hole_z = np.array([bottom, bottom + chamfer, top - chamfer, top])
        hole_depth = np.array([chamfer, 0.0, 0.0, chamfer])
        for k in (0, levels - 1):
            cap = shapely.Polygon(rings[k], [inset_ring(h, chamfer) for h in holes])
            if not cap.is_valid:
                raise DesignError(
                    f"output.chamfer = {chamfer:g}: too large for the teeth of {name} (the inset crosses itself)"
                )
    else:
        hole_z, hole_depth = np.array([bottom, top]), np.zeros(2)
    return rings, hole_z, hole_depth


def loft(
    heights: Sequence[float] | np.ndarray,
    rings: np.ndarray,
    *,
    name: str,
    holes: Sequence[np.ndarray] = (),
    chamfer: float = 0.0,
) -> Solid:
    """The solid through ``rings[k]`` (counter-clockwise, (n, m, 2) mm) at ``heights[k]``
    (increasing), with straight ``holes`` (clockwise rings, mm) through it.

    With ``chamfer`` > 0 every top and bottom edge is cut at 45°: the section at height z is inset
    by max(0, chamfer − z, z − (b − chamfer)), so sections at z = chamfer and b − chamfer should be
    among ``heights`` (``section_heights(..., chamfer=)`` puts them there).
    """
    z = np.asarray(heights, dtype=float)
    rings = np.asarray(rings, dtype=float)
    levels, m = rings.shape[:2]
    if levels != len(z) or levels < 2 or np.any(np.diff(z) <= 0):
        raise DesignError(f"{name}: a loft needs two or more sections at increasing heights")
    holes = [np.asarray(h, dtype=float) for h in holes]
    rings, hole_z, hole_depth = _chamfered(rings, z, holes, chamfer, name)
    verts = [np.column_stack([rings.reshape(-1, 2), np.repeat(z, m)])]
    tris = []
    index = np.arange(levels * m).reshape(levels, m)
    for k in range(levels - 1):
        tris.append(_strip(index[k], index[k + 1], rings[k], rings[k + 1]))
    base = levels * m
    hole_index = []
    for h in holes:
        rows = [inset_ring(h, d) if d > 0 else h for d in hole_depth]
        level_xyz = [np.column_stack([r, np.full(len(h), hz)]) for r, hz in zip(rows, hole_z)]
        idx = base + np.arange(len(hole_z) * len(h)).reshape(len(hole_z), len(h))
        for k in range(len(hole_z) - 1):
            tris.append(_strip(idx[k], idx[k + 1], rows[k], rows[k + 1]))
        verts.extend(level_xyz)
        hole_index.append(idx)
        base += idx.size
    vertices = np.vstack(verts)
    # caps: the bottom and top sections with the holes' end rings, each triangulated (facing
    # down at the bottom, up at the top)
    for level, end, down in ((0, 0, True), (levels - 1, -1, False)):
        ids = np.concatenate([index[level]] + [idx[end] for idx in hole_index])
        tri = ids[cap_triangles([vertices[i, :2] for i in [index[level]] + [idx[end] for idx in hole_index]])]
        tris.append(tri[:, ::-1] if down else tri)
    mesh = m3d.Mesh64(vert_properties=vertices, tri_verts=np.vstack(tris).astype(np.uint64))
    return checked_solid(m3d.Manifold(mesh), name)
