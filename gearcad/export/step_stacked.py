"""A part of two stacked straight bands as one STEP solid (a carrier-less set's axial retention,
docs/mechanisms.md): the upper band's rings are the lower's turned over (:func:`mirrored_ring`),
the two prisms fused in OpenCASCADE (:func:`stacked_solid`)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..geometry.arcfit import ArcRing
from .step_brep import StepSolid, _face, ring_area

__all__ = ["mirrored_ring", "stacked_solid"]


def mirrored_ring(ring: ArcRing, angle: float) -> ArcRing:
    """``ring`` mirrored about the line through the origin at ``angle`` (rad), its direction kept
    (reversed after the mirror): segment j of the result is segment n − 2 − j of ``ring`` run
    backwards, its bulge's sign flipped twice (by the mirror and by the reversal)."""
    c, s = np.cos(2 * angle), np.sin(2 * angle)
    v = np.asarray(ring.vertices, dtype=float)
    mirrored = np.column_stack([c * v[:, 0] + s * v[:, 1], s * v[:, 0] - c * v[:, 1]])[::-1]
    n = len(v)
    return ArcRing(mirrored, np.asarray(ring.bulges, dtype=float)[(n - 2 - np.arange(n)) % n])


def stacked_solid(lower: Sequence[ArcRing], upper: Sequence[ArcRing], thickness: float, *, name: str) -> StepSolid:
    """Two straight bands: ``lower``'s rings extruded from z = 0 to half the ``thickness`` and
    ``upper``'s from there to the top, fused into one solid (OpenCASCADE's Boolean union, its
    coplanar faces merged); the volume is the bands' own, the rings' exact areas × half the
    thickness each.  The union is told that the two touch only where their mid-plane faces
    partly coincide (OpenCASCADE's "glue" for shifted coinciding faces: 2.6 s for the square set's
    ring, 4.3 s without)."""
    from OCP.BOPAlgo import BOPAlgo_GlueShift
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec
    from OCP.OCP.collections import List_TopoDS_Shape
    from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain

    half = thickness / 2
    below, above = List_TopoDS_Shape(), List_TopoDS_Shape()
    below.Append(BRepPrimAPI_MakePrism(_face(lower), gp_Vec(0.0, 0.0, half)).Shape())
    above.Append(BRepPrimAPI_MakePrism(_face(upper, half), gp_Vec(0.0, 0.0, half)).Shape())
    fuse = BRepAlgoAPI_Fuse()
    fuse.SetArguments(below)
    fuse.SetTools(above)
    fuse.SetGlue(BOPAlgo_GlueShift)
    fuse.Build()
    if not fuse.IsDone():
        raise RuntimeError(f"STEP: OpenCASCADE could not join {name}'s two bands")
    unify = ShapeUpgrade_UnifySameDomain(fuse.Shape(), True, True, False)
    unify.Build()
    return StepSolid(name, unify.Shape(), half * sum(ring_area(r) for r in (*lower, *upper)))
