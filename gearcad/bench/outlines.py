"""Outlines as written, read back, and how far they are from a reference.

Distances are between curves, not vertex sets: every point of one outline to the other ring
and back (the larger of the two is the Hausdorff distance of the two polylines, up to the
sampling of the curves).  Arcs in a DXF are flattened to 1e-6 mm before measuring, with points
on their circles (ezdxf's own flattening goes through cubic Béziers, which stray 4.1e-5 mm from
a 45° arc of radius 10 mm: forty times the chord error asked for).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from ..geometry import bulge as B
from ..geometry.verify import to_segments

__all__ = [
    "DxfOutline",
    "dxf_outlines",
    "flattened",
    "largest_outline",
    "deviation",
    "deviations",
    "segment_deviations",
    "signed_depth",
]

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

    found = []
    for entity in ezdxf.readfile(path).modelspace().query("LWPOLYLINE"):
        if not entity.closed or (layer is not None and entity.dxf.layer != layer):
            continue
        xyb = np.array(entity.get_points("xyb"), dtype=float).reshape(-1, 3)
        found.append(DxfOutline(entity.dxf.layer, len(xyb), int(np.count_nonzero(xyb[:, 2])), flattened(xyb)))
    return found


def flattened(xyb: np.ndarray, chord_error: float = FLATTEN_MM) -> np.ndarray:
    """A closed ring of vertices and bulges ((n, 3): x, y, bulge, mm) as points on it ((m, 2) mm):
    each arc split into equal steps on its circle whose chords stray at most ``chord_error`` from
    it (a chord of angle δ lies r·(1 − cos(δ/2)) inside an arc of radius r), each line its start."""
    v, bulge = xyb[:, :2], xyb[:, 2]
    arc = bulge != 0
    theta = np.zeros(len(v))
    theta[arc] = B.sweep(bulge[arc])
    centre, r = v.copy(), np.zeros(len(v))
    centre[arc], r[arc] = B.centres(v[arc], np.roll(v, -1, axis=0)[arc], theta[arc])
    steps = np.ones(len(v), dtype=int)
    step = 2 * np.arccos(np.clip(1 - chord_error / r[arc], -1.0, 1.0))
    steps[arc] = np.maximum(1, np.ceil(np.abs(theta[arc]) / step))
    first = np.repeat(np.cumsum(steps) - steps, steps)
    fraction = (np.arange(first.size) - first) / np.repeat(steps, steps)
    start = np.arctan2(*(v - centre)[:, ::-1].T)  # the lines' (r = 0) points are their starts
    angle = np.repeat(start, steps) + fraction * np.repeat(theta, steps)
    return np.repeat(centre, steps, axis=0) + np.repeat(r, steps)[:, None] * np.column_stack(
        [np.cos(angle), np.sin(angle)]
    )


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
    ahead = to_segments(p, ring[near], ring[(near + 1) % n])
    behind = to_segments(p, ring[(near - 1) % n], ring[near])
    return np.minimum(ahead, behind).min(axis=1)


def segment_deviations(written: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """How far each segment of the closed polyline ``written`` ((n, 2) mm; segment i from vertex
    i to i + 1) strays from ``reference``: the largest distance of its points :data:`_ALONG`
    apart (a polyline simplified from exact points has its error between them), (n,) mm."""
    written = np.asarray(written, dtype=float)
    ends = np.roll(written, -1, axis=0)
    pieces = np.maximum(1, np.ceil(np.hypot(*(ends - written).T) / _ALONG)).astype(int)
    return np.maximum.reduceat(_to_ring(_densified(written, _ALONG), reference), np.cumsum(pieces) - pieces)


def deviation(written: np.ndarray, reference: np.ndarray, where: np.ndarray | None = None) -> float:
    """Largest distance between the closed polylines ``written`` and ``reference`` ((n, 2) mm),
    ``written`` measured along its segments (:func:`segment_deviations`).

    ``where`` (a boolean mask over ``written``'s vertices) limits the measure to part of the
    outline, one way: ``written`` there (its segments starting there) to ``reference``."""
    if where is None:
        return deviations(written, reference)["all"]
    return _largest(segment_deviations(written, reference), where)


def deviations(written: np.ndarray, reference: np.ndarray, regions: dict[str, np.ndarray] | None = None) -> dict:
    """:func:`deviation` of the whole outline (key ``"all"``) and of each of ``regions`` (name:
    mask over ``written``'s vertices, one way), every point of ``written`` measured once."""
    far = segment_deviations(written, reference)
    out = {"all": float(max(far.max(), _to_ring(reference, written).max()))}
    return out | {name: _largest(far, where) for name, where in (regions or {}).items()}


def _largest(far: np.ndarray, where: np.ndarray) -> float:
    where = np.asarray(where, dtype=bool)
    return float(far[where].max()) if np.any(where) else float("nan")


def signed_depth(points: np.ndarray, pitch: np.ndarray) -> np.ndarray:
    """Distance of each point from the pitch curve ``pitch`` ((m, 2) mm, dense), negative inside."""
    distance = _to_ring(points, pitch)
    inside = shapely.contains_xy(shapely.Polygon(pitch), points[:, 0], points[:, 1])
    return np.where(inside, -distance, distance)
