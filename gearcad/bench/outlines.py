"""Outlines as written, read back, and how far they are from a reference.

Distances are between curves, not vertex sets: every point of one outline to the other ring
and back (the larger of the two is the Hausdorff distance of the two polylines, up to the
sampling of the curves).  Arcs in a DXF are flattened to 1e-6 mm before measuring.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

__all__ = ["DxfOutline", "dxf_outlines", "largest_outline", "deviation", "signed_depth"]

FLATTEN_MM = 1e-6
"""Chord error of arcs flattened for measuring, mm (three orders under the finest tolerance)."""


@dataclass(frozen=True)
class DxfOutline:
    layer: str
    vertices: int
    """Vertices of the closed polyline as written (an arc segment is one vertex with a bulge)."""
    arcs: int
    """Segments that are arcs (non-zero bulge)."""
    points: np.ndarray
    """(n, 2) float, mm: the curve flattened to :data:`FLATTEN_MM`."""


def dxf_outlines(path: Path, layer: str | None = None) -> list[DxfOutline]:
    """Every closed LWPOLYLINE of ``path`` (on ``layer`` if given), read back with ezdxf."""
    import ezdxf
    import ezdxf.path

    found = []
    for entity in ezdxf.readfile(path).modelspace().query("LWPOLYLINE"):
        if not entity.closed or (layer is not None and entity.dxf.layer != layer):
            continue
        bulges = [b for *_, b in entity.get_points("xyb")]
        pts = np.array([(v.x, v.y) for v in ezdxf.path.make_path(entity).flattening(FLATTEN_MM)])
        if len(pts) > 1 and np.allclose(pts[0], pts[-1]):
            pts = pts[:-1]
        found.append(DxfOutline(entity.dxf.layer, len(entity), sum(1 for b in bulges if b), pts))
    return found


def largest_outline(path: Path, layer: str | None = None) -> DxfOutline:
    """The outline with the most vertices (the toothed one, not a pilot hole or a mark)."""
    outlines = dxf_outlines(path, layer)
    if not outlines:
        raise ValueError(f"{path}: no closed polyline on layer {layer!r}")
    return max(outlines, key=lambda o: (o.vertices, len(o.points)))


_LONGEST = 0.05
"""mm: segments of a ring measured to are split to at most this, so that the foot of every
point lies on a segment next to one of its nearest vertices."""


_ALONG = 0.01
"""mm: a written polyline is measured at points this far apart along its segments (the largest
chord error of a segment up to 0.3 mm long is found to 0.1 %)."""


def _densified(ring: np.ndarray, longest: float) -> np.ndarray:
    """``ring`` with every segment longer than ``longest`` split evenly (closed, (m, 2) mm)."""
    ends = np.roll(ring, -1, axis=0)
    pieces = np.maximum(1, np.ceil(np.hypot(*(ends - ring).T) / longest)).astype(int)
    start = np.repeat(ring, pieces, axis=0)
    step = np.repeat((ends - ring) / pieces[:, None], pieces, axis=0)
    offset = np.arange(len(start)) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    return start + step * offset[:, None]


def _to_segments(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    d = b - a
    t = np.clip(np.sum((points - a) * d, axis=-1) / np.maximum(np.sum(d * d, axis=-1), 1e-300), 0.0, 1.0)
    return np.hypot(*np.moveaxis(points - (a + t[..., None] * d), -1, 0))


def _to_ring(points: np.ndarray, ring: np.ndarray, k: int = 4) -> np.ndarray:
    """Distance of each point to the closed polyline ``ring``: to the segments on either side
    of its ``k`` nearest vertices (a k-d tree; all 10⁵ × 10⁵ segment distances would take
    minutes).  Along a smooth curve the foot of a point lies on a segment next to its nearest
    vertex, and no segment is longer than :data:`_LONGEST`."""
    from scipy.spatial import cKDTree

    ring = _densified(np.asarray(ring, dtype=float), _LONGEST)
    n = len(ring)
    _, near = cKDTree(ring).query(points, k=min(k, n))
    near = near.reshape(len(points), -1)
    p = np.asarray(points, dtype=float)[:, None, :]
    ahead = _to_segments(p, ring[near], ring[(near + 1) % n])
    behind = _to_segments(p, ring[(near - 1) % n], ring[near])
    return np.minimum(ahead, behind).min(axis=1)


def deviation(written: np.ndarray, reference: np.ndarray, where: np.ndarray | None = None) -> float:
    """Largest distance between the closed polylines ``written`` and ``reference`` ((n, 2) mm).

    ``written`` is measured along its segments, not only at its vertices (split to
    :data:`_ALONG`): a polyline simplified from exact points has its error between them.
    ``where`` (a boolean mask over ``written``'s vertices) limits the measure to part of the
    outline, one way: ``written`` there (its segments starting there) to ``reference``."""
    written = np.asarray(written, dtype=float)
    ends = np.roll(written, -1, axis=0)
    pieces = np.maximum(1, np.ceil(np.hypot(*(ends - written).T) / _ALONG)).astype(int)
    along = _densified(written, _ALONG)
    if where is not None:
        chosen = np.repeat(np.asarray(where, dtype=bool), pieces)
        return float(_to_ring(along[chosen], reference).max()) if np.any(chosen) else float("nan")
    return float(max(_to_ring(along, reference).max(), _to_ring(reference, written).max()))


def signed_depth(points: np.ndarray, pitch: np.ndarray) -> np.ndarray:
    """Distance of each point from the pitch curve ``pitch`` ((m, 2) mm, dense), negative inside."""
    distance = _to_ring(points, pitch)
    inside = shapely.contains_xy(shapely.Polygon(pitch), points[:, 0], points[:, 1])
    return np.where(inside, -distance, distance)
