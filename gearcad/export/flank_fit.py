"""A twisted part's flank as B-splines fitted to its transverse sections (numpy and scipy only;
``export/step_brep.py`` makes OpenCASCADE faces of them): cubic round the section with knots
common to every section and corners kept, fitted within a quarter of the tolerance, then up the
face; knot insertion to split a face; the closed-form volume inside a band of them."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = [
    "CORNER",
    "SMOOTH",
    "FlankFit",
    "fit_rings",
    "fit_heights",
    "greville",
    "insert_knot",
    "split_spans",
    "band_volume",
]

CORNER = 0.35
"""A section vertex whose tangent turns by more than this (rad, 20°) is a corner (a tip corner, an
undercut crossing): the fitted flank keeps it (a knot of full multiplicity there)."""


SMOOTH = 1e-3
"""Weight of a piece's poles' second differences against its vertices' misses in its fit: small
(a smooth flank's poles bend by far less than a vertex may miss), but never nothing."""


def turning(rings: np.ndarray) -> np.ndarray:
    """|turn| of the tangent at every vertex, the largest over the rings (k, m, 2): (m,) rad."""
    d_in = rings - np.roll(rings, 1, axis=1)
    d_out = np.roll(rings, -1, axis=1) - rings
    cross = d_in[..., 0] * d_out[..., 1] - d_in[..., 1] * d_out[..., 0]
    return np.max(np.abs(np.arctan2(cross, np.einsum("...i,...i->...", d_in, d_out))), axis=0)


def piece_fit(t: np.ndarray, points: np.ndarray, inner: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """The cubic B-spline, clamped at the piece's ends (its first and last points), through
    ``points`` ((k, p, 2): k rings, p points at parameters ``t``) by least squares with the
    interior knots ``inner``: its poles (k, q, 2) and its points at ``t`` and halfway between
    (k, 2p − 1, 2)."""
    from scipy.interpolate import BSpline

    knots = np.concatenate([np.full(4, t[0]), np.sort(inner), np.full(4, t[-1])])
    both = np.empty(2 * len(t) - 1)
    both[0::2], both[1::2] = t, (t[:-1] + t[1:]) / 2
    every = BSpline.design_matrix(both, knots, 3).toarray()
    basis = every[0::2]  # (p, q)
    k, p = points.shape[:2]
    q = basis.shape[1]
    # least squares, and a hair of the poles' second differences (a pole no vertex pins, in a
    # span between two vertices, goes where the curve stays smooth rather than anywhere)
    bend = np.diff(np.eye(q), 2, axis=0) * SMOOTH  # (q − 2, q)
    rows = np.vstack([basis, bend])
    fixed = np.concatenate([points[:, :1], points[:, -1:]], axis=1)  # (k, 2, 2)
    target = np.concatenate([points, np.zeros((k, q - 2, 2))], axis=1) - np.einsum(
        "jq,nqk->njk", rows[:, [0, -1]], fixed
    )
    inside = np.linalg.lstsq(rows[:, 1:-1], target.transpose(1, 0, 2).reshape(p + q - 2, -1), rcond=None)[0]
    poles = np.concatenate([points[:, :1], inside.reshape(q - 2, k, 2).transpose(1, 0, 2), points[:, -1:]], axis=1)
    return poles, np.einsum("jq,nqk->njk", every, poles)


def normal_error(points: np.ndarray, fitted: np.ndarray) -> np.ndarray:
    """How far each fitted point lies off its ring across the ring (the part of the miss normal to
    the ring's tangent there; a slip along the ring moves no surface): (k, p) mm."""
    tangent = np.gradient(points, axis=1)
    tangent /= np.maximum(np.linalg.norm(tangent, axis=2, keepdims=True), 1e-300)
    miss = fitted - points
    return np.abs(miss[..., 0] * tangent[..., 1] - miss[..., 1] * tangent[..., 0])


def chord_error(points: np.ndarray, halfway: np.ndarray) -> np.ndarray:
    """How far the fitted points ``halfway`` ((k, p − 1, 2)) between consecutive ``points`` ((k, p,
    2)) lie off the chord between them: (k, p − 1) mm (0 for a chord of no length)."""
    chord = points[:, 1:] - points[:, :-1]
    off = halfway - points[:, :-1]
    length = np.linalg.norm(chord, axis=2)
    cross = np.abs(chord[..., 0] * off[..., 1] - chord[..., 1] * off[..., 0])
    return np.where(length > 0, cross / np.maximum(length, 1e-300), np.linalg.norm(off, axis=2))


@dataclass(frozen=True)
class FlankFit:
    """Closed rings fitted by cubic B-splines of one knot vector (u in mm of mean chord length)."""

    knots: np.ndarray
    """Distinct knots, (r,)."""
    mults: np.ndarray
    """Their multiplicities, (r,): 4 at the ends, 3 at a corner, 1 between."""
    poles: np.ndarray
    """(k, q, 2) each ring's poles, the first equal to the last (a corner, where the ring starts)."""
    start: int
    """The rings' vertex at u = 0."""
    error: float
    """Largest distance across its ring of a ring vertex from its fitted curve, mm."""
    t: np.ndarray
    """(m + 1,) u of every vertex from the start round to it again."""
    pieces: tuple
    """(first vertex, last vertex, interior knots) of every piece between corners."""

    def parts(self) -> list[tuple[int, int, tuple, slice]]:
        """Every piece between corners: its first and last vertex, interior knots, poles' slice."""
        out, pole = [], 0
        for a, b, inner in self.pieces:
            count = len(inner) + 4
            out.append((a, b, inner, slice(pole, pole + count)))
            pole += count - 1
        return out

    def poles_of(self, rings: np.ndarray) -> np.ndarray:
        """Other rings ((k, m, 2), the same vertices) fitted with these knots: (k, q, 2)."""
        closed = np.roll(rings, -self.start, axis=1)
        closed = np.concatenate([closed, closed[:, :1]], axis=1)
        poles = [closed[:, :1]]
        for a, b, inner in self.pieces:
            poles.append(piece_fit(self.t[a : b + 1], closed[:, a : b + 1], inner)[0][:, 1:])
        return np.concatenate(poles, axis=1)


def fit_rings(rings: np.ndarray, targets: np.ndarray) -> FlankFit:
    """One cubic B-spline per ring ((k, m, 2), vertex j of each the same tooth point), all with
    the same knots, each ring within ``targets[i]`` (mm, across the ring) of its own vertices.

    The rings are cut at their corners into pieces (a knot of multiplicity 3: the curve passes
    through the corner, tangents free either side); a piece gets interior knots one at a time, at
    the middle vertex of the span where it strays most (a second and third at one vertex where a
    span has no vertex inside: a kink), until every ring is within its target."""
    k, m = rings.shape[:2]
    corners = np.nonzero(turning(rings) > CORNER)[0]
    start = int(corners[0]) if len(corners) else 0
    closed = np.roll(rings, -start, axis=1)
    closed = np.concatenate([closed, closed[:, :1]], axis=1)
    cuts = np.unique(np.concatenate([[0, m], (corners - start) % m]))
    t = np.concatenate([[0.0], np.cumsum(np.mean(np.linalg.norm(np.diff(closed, axis=1), axis=2), axis=0))])
    knots, mults, poles, worst, pieces = [0.0], [4], [closed[:, :1]], 0.0, []
    for a, b in zip(cuts[:-1], cuts[1:]):
        ts, points = t[a : b + 1], closed[:, a : b + 1]
        inner: list[float] = []
        stuck = np.zeros(len(ts), dtype=bool)  # vertices no further knot can help
        while True:
            piece, fitted = piece_fit(ts, points, inner)
            error = normal_error(points, fitted[:, 0::2])
            # halfway between vertices: off the chord by at most the chord's own sag (< the target)
            # and the target; a loop between two vertices would be far off
            between = chord_error(points, fitted[:, 1::2]) / (2 * targets[:, None])
            over = np.maximum(np.max(error / targets[:, None], axis=0), np.pad(np.max(between, axis=0), (0, 1)))
            over[stuck] = 0.0
            if np.max(over) <= 1.0:
                break
            j = int(np.argmax(over))
            lo = max([ts[0], *(u for u in inner if u <= ts[j])])
            hi = min([ts[-1], *(u for u in inner if u > ts[j])])
            inside = np.nonzero((ts > lo) & (ts < hi))[0]
            if len(inside) >= 3:
                inner.append(float(ts[inside[len(inside) // 2]]))
            elif 0 < j < len(ts) - 1 and inner.count(float(ts[j])) < 3:
                inner.append(float(ts[j]))
            else:
                stuck[j] = True
        worst = max(worst, float(np.max(error)))
        pieces.append((int(a), int(b), tuple(inner)))
        for u in sorted(set(inner)):
            knots.append(u)
            mults.append(inner.count(u))
        knots.append(float(ts[-1]))
        mults.append(3)
        poles.append(piece[:, 1:])
    mults[-1] = 4
    return FlankFit(np.array(knots), np.array(mults), np.concatenate(poles, axis=1), start, worst, t, tuple(pieces))


def fit_heights(rings: np.ndarray, z: np.ndarray, target: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Every vertex's path up a band of sections (rings (n, m, 2) at heights z (n,)) as one
    B-spline in z of degree ≤ 3, through the end sections, least squares between, with as few
    control rings (evenly spaced knots) as keep every section within ``target`` (mm, across it):
    the control rings (r, m, 2), the distinct knots, their multiplicities and the degree."""
    from scipy.interpolate import BSpline

    n = len(z)
    # the fewest control rings first, the higher degree first among as many
    options = sorted(((d, c) for d in range(1, min(3, n - 1) + 1) for c in range(n - d)), key=lambda o: (sum(o), -o[0]))
    for degree, inner in options:
        between = np.linspace(z[0], z[-1], inner + 2)[1:-1]
        knots = np.concatenate([np.full(degree + 1, z[0]), between, np.full(degree + 1, z[-1])])
        basis = BSpline.design_matrix(z, knots, degree).toarray()  # (n, r)
        r = basis.shape[1]
        ends = np.einsum("k,mj->kmj", basis[:, 0], rings[0]) + np.einsum("k,mj->kmj", basis[:, -1], rings[-1])
        rows = [rings[:1]]
        if r > 2:
            inside = np.linalg.lstsq(basis[:, 1:-1], (rings - ends).reshape(n, -1), rcond=None)[0]
            rows.append(inside.reshape(r - 2, *rings.shape[1:]))
        rows = np.concatenate([*rows, rings[-1:]])
        if np.max(normal_error(rings, np.einsum("kr,rmj->kmj", basis, rows))) <= target:
            break
    distinct, mults = np.unique(knots, return_counts=True)
    return rows, distinct, mults, degree


def greville(knots: np.ndarray, mults: np.ndarray, degree: int) -> np.ndarray:
    """The Greville abscissae of a knot vector (distinct knots and multiplicities): the height of
    each control row that makes z = v on the surface."""
    flat = np.repeat(knots, mults)
    return np.array([np.mean(flat[i + 1 : i + 1 + degree]) for i in range(len(flat) - degree - 1)])


def insert_knot(flat: np.ndarray, poles: np.ndarray, u: float) -> tuple[np.ndarray, np.ndarray]:
    """The cubic B-spline (clamped knots ``flat``, poles (…, q, 2) along axis 1) with the knot
    ``u`` inserted once (Boehm): the same curve."""
    k = int(np.searchsorted(flat, u, side="right")) - 1
    alpha = np.ones(poles.shape[1] + 1)
    for i in range(k - 2, k + 1):
        alpha[i] = (u - flat[i]) / (flat[i + 3] - flat[i])
    alpha[k + 1 :] = 0.0
    before = np.concatenate([poles[:, :1], poles], axis=1)  # P[i − 1]
    after = np.concatenate([poles, poles[:, -1:]], axis=1)  # P[i]
    mixed = (1 - alpha)[None, :, None] * before + alpha[None, :, None] * after
    mixed[:, : k - 2] = poles[:, : k - 2]
    return np.insert(flat, k + 1, u), mixed


def split_spans(flat: np.ndarray, poles: np.ndarray, spans: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """A cubic B-spline piece (clamped knots ``flat``, poles (r, q, 2)) cut into pieces of at most
    ``spans`` knot spans, each cut a knot of multiplicity 3 (the curve unchanged, a pole shared)."""
    inner = np.unique(flat[4:-4])
    cuts = inner[spans - 1 :: spans]
    cuts = cuts[cuts < flat[-1]]
    for u in cuts:
        while np.count_nonzero(flat == u) < 3:
            flat, poles = insert_knot(flat, poles, float(u))
    out = []
    for u in cuts:
        j = int(np.searchsorted(flat, u, side="left"))
        out.append((np.concatenate([flat[: j + 3], [u]]), poles[:, :j]))
        flat, poles = np.concatenate([[u], flat[j:]]), poles[:, j - 1 :]
    out.append((flat, poles))
    return out


def band_volume(fit: FlankFit, rows: np.ndarray, vknots: np.ndarray, vmults: np.ndarray, vdegree: int) -> float:
    """The volume inside a flank band (mm³), in closed form: its section at height z is the
    closed cubic B-spline of poles P(z) = Σ_i B_i(z)·P_i, of area ½∮(x y′ − y x′) du, a polynomial
    in u on every knot span and in z on every span up the band: Gauss–Legendre rules of 3 points
    a span round the section and degree + 1 up it integrate it exactly."""
    from scipy.interpolate import BSpline

    def rule(flat: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
        knots = np.unique(flat)
        nodes, weights = np.polynomial.legendre.leggauss(count)
        half = np.diff(knots)[:, None] / 2
        return ((knots[:-1, None] + knots[1:, None]) / 2 + half * nodes).ravel(), (half * weights).ravel()

    flat = np.repeat(fit.knots, fit.mults)
    u, wu = rule(flat, 3)
    value = BSpline.design_matrix(u, flat, 3)  # (p, q) sparse
    # N′_j = 3·(M_j / (t_(j+3) − t_j) − M_(j+1) / (t_(j+4) − t_(j+1))), M the quadratic basis on the same knots
    lower = BSpline.design_matrix(u, flat, 2).toarray()  # (p, q + 1)
    with np.errstate(divide="ignore"):
        left = np.where(flat[3:] > flat[:-3], 3 / (flat[3:] - flat[:-3]), 0.0)  # (q + 1,)
    slope = lower[:, :-1] * left[:-1] - lower[:, 1:] * left[1:]  # (p, q)
    poles = fit.poles_of(rows)  # (r, q, 2)
    vflat = np.repeat(vknots, vmults)
    z, wz = rule(vflat, vdegree + 1)
    height = BSpline.design_matrix(z, vflat, vdegree).toarray()  # (s, r)
    at = np.einsum("sr,rqk->sqk", height, poles)  # (s, q, 2): each node's section poles
    x, y = value @ at[..., 0].T, value @ at[..., 1].T  # (p, s)
    dx, dy = slope @ at[..., 0].T, slope @ at[..., 1].T
    return 0.5 * float(wu @ (x * dy - y * dx) @ wz)
