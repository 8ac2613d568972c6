"""The one intermediate representation of a part's shape: closed rings in mm, placed by one
function (:func:`place`) and converted to shapely in one place (:meth:`Outline.polygon`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Outline", "ring_area", "rotate", "place", "place_each", "arc_steps", "mirrored", "turn_repeats"]


def arc_steps(radius: float, tolerance: float, sweep: float = 2 * np.pi) -> int:
    """How many chords an arc of ``radius`` and ``sweep`` (rad) needs so that none strays more
    than ``tolerance`` from it: each chord may subtend 2·acos(1 − tol/r)."""
    if tolerance >= radius:
        return 1
    return max(1, int(np.ceil(sweep / (2 * np.arccos(1 - tolerance / radius)))))


def ring_area(ring: np.ndarray) -> float:
    """Signed area (shoelace) of an open ring: positive when counter-clockwise, mm²."""
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def rotate(points: np.ndarray, angle: float, center=(0.0, 0.0)) -> np.ndarray:
    """Points rotated by ``angle`` (rad, counter-clockwise) about ``center``: (n, 2) float."""
    c, s = np.cos(angle), np.sin(angle)
    p = np.asarray(points, dtype=float) - center
    return np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]]) + center


def turn_repeats(ring: np.ndarray, within: float = 1e-9) -> int:
    """The most times d that the open ring is its own vertices turned by 2π/d about the origin
    (vertex i onto vertex i + n/d, to ``within`` of its size), each turn's share at least 8
    vertices: a toothed gear's outline drawn tooth by tooth gives its tooth count; 1 for a ring
    that does not repeat."""
    xy = np.asarray(ring, dtype=float)
    n = len(xy)
    size = float(np.max(np.abs(xy))) if n else 0.0
    for d in sorted((d for d in range(2, n // 8 + 1) if n % d == 0), reverse=True):
        turned = rotate(xy, 2 * np.pi / d)
        if float(np.max(np.abs(turned - np.roll(xy, -(n // d), axis=0)))) <= within * size:
            return d
    return 1


def place(points: np.ndarray, angle: float = 0.0, offset=(0.0, 0.0)) -> np.ndarray:
    """Points of a part turned by ``angle`` (rad, counter-clockwise) about its pivot at the
    origin, then moved by ``offset`` (mm): where a placement puts them, (n, 2) float."""
    return rotate(points, angle) + np.asarray(offset, dtype=float)


def place_each(points: np.ndarray, owner: np.ndarray, angle: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """Many placements at once: row k of ``points`` turned by ``angle[owner[k]]`` (rad,
    counter-clockwise) about the origin, then moved by ``offset[owner[k]]`` ((m, 2) mm): (n, 2)
    float.  The sines and cosines are taken once per placement, not once per point."""
    c, s, off = np.cos(angle)[owner], np.sin(angle)[owner], np.asarray(offset, dtype=float)[owner]
    x, y = points[:, 0], points[:, 1]
    return np.column_stack([c * x - s * y + off[:, 0], s * x + c * y + off[:, 1]])


def _frozen(ring) -> np.ndarray:
    a = np.array(ring, dtype=np.float64)  # a copy: the caller's array stays the caller's
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError(f"a ring must be an (n, 2) array, got shape {a.shape}")
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Outline:
    """A part's cut shape: ``rings[0]`` the outer boundary (counter-clockwise), the rest holes
    (clockwise); each ring an open (n, 2) float64 array in mm, read-only, its pivot at the origin."""

    rings: tuple[np.ndarray, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "rings", tuple(_frozen(r) for r in self.rings))

    @property
    def outer(self) -> np.ndarray:
        return self.rings[0]

    @property
    def area(self) -> float:
        return sum(ring_area(r) for r in self.rings)

    @property
    def vertex_count(self) -> int:
        return sum(len(r) for r in self.rings)

    def polygon(self, angle: float = 0.0, offset=(0.0, 0.0)):
        """The outline as a ``shapely.Polygon``, placed by :func:`place` (outer ring, holes)."""
        import shapely

        moved = angle != 0 or any(offset)
        rings = [place(r, angle, offset) if moved else r for r in self.rings]
        return shapely.Polygon(rings[0], rings[1:])


def mirrored(outline: Outline, angle: float) -> Outline:
    """The outline mirrored about the line through its pivot at ``angle`` (rad): the part turned
    over about that line.  Each ring is reversed, so the outer ring stays counter-clockwise."""
    c, s = np.cos(2 * angle), np.sin(2 * angle)
    return Outline(
        tuple(np.column_stack([c * r[:, 0] + s * r[:, 1], s * r[:, 0] - c * r[:, 1]])[::-1] for r in outline.rings)
    )
