"""The wheel-walker's leg and shoe (seed 002, eqs. 1–6), and the vehicle's speed.

The leg, as the paper's eqs. 3–4 describe it (hub at the origin, hub angle φ, stance
φ ∈ [−π/4, π/4], ground below): the crank axis sits a from the hub along the post direction
e = (sin φ, −cos φ); the crank pin B1 is b from it at (sin 2φ, cos 2φ) — the crank turns twice
as fast as the hub and the other way; the post and shoe hang rigidly from B1 along e.  The shoe
surface is traced by Y1 along the post from B1 to C, then Y2 from C straight down to the ground
contact K1, Y2 being the surface normal at the hub angle φ to the post (eqs. 1–2):

    Y1 = 4b·cos φ − a,    Y2 = a − 2b(1 + cos²φ) + c.

In the leg's own frame (origin B1, post along −y) the shoe point whose normal makes the angle φ
with the post is (x, y) = (−Y2·sin φ, −(Y1 + Y2·cos φ)).  It is the envelope of those normals
because Y1'·cos φ + Y2' = 0, its radius of curvature is K − 3b·cos 2φ (K = a − b + c, the
support function p = Y1·cos φ + Y2 plus p''), and placing the leg turned by φ about B1 puts
it at height −K below the hub with a horizontal tangent: Y01 = K (eq. 5).  Rolling the convex
shoe on the ground moves the hub by K + 3b·cos 2φ per radian (eq. 6).

The vehicle speed is v = ω_H·dX01/dφ with ω/ω_H the drive's ratio: constant only if the ratio
is i·(K + 3b·cos 2φ)/K; with round gears (i = 4) it follows dX01/dφ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry.outline import arc_steps
from ..pitch.walker import WalkerGeometry, shoe_functions
from ..roots import brentq

__all__ = [
    "STANCE",
    "ShoeProfile",
    "shoe_profile",
    "crank_pin",
    "shoe_ring",
    "stance_check",
    "ring_stance_check",
    "speed_comparison",
]

STANCE = math.pi / 4
"""Half the stance range of one leg (four legs share a turn), rad of hub angle."""


@dataclass(frozen=True)
class ShoeProfile:
    """The shoe surface over hub angles ``phi``: (n,) arrays, mm and rad."""

    phi: np.ndarray
    Y1: np.ndarray
    Y2: np.ndarray
    x: np.ndarray
    """Across the post, in the leg's frame (origin B1, post along −y)."""
    y: np.ndarray
    """Along the post (negative: below B1)."""
    rho: np.ndarray
    """Distance from B1."""
    alpha: np.ndarray
    """Angle of the radius vector from the post axis (positive towards +x), rad."""
    curvature_radius: np.ndarray
    """K − 3b·cos 2φ, mm."""

    def as_dict(self) -> dict:
        return {
            "phi_deg": np.degrees(self.phi).tolist(),
            "X": self.x.tolist(),
            "Y": (-self.y).tolist(),
            "rho": self.rho.tolist(),
            "alpha_deg": np.degrees(self.alpha).tolist(),
        }


def _points(g: WalkerGeometry, phi):
    f = shoe_functions(phi, g)
    phi = np.asarray(phi, dtype=float)
    return f["Y1"], f["Y2"], -f["Y2"] * np.sin(phi), -(f["Y1"] + f["Y2"] * np.cos(phi))


def shoe_profile(g: WalkerGeometry, phi=None, *, samples: int = 181) -> ShoeProfile:
    """The shoe surface (eqs. 1–2) at hub angles ``phi`` (default: the stance, ``samples``)."""
    phi = np.linspace(-STANCE, STANCE, samples) if phi is None else np.asarray(phi, dtype=float)
    y1, y2, x, y = _points(g, phi)
    return ShoeProfile(
        phi=phi,
        Y1=y1,
        Y2=y2,
        x=x,
        y=y,
        rho=np.hypot(x, y),
        alpha=np.arctan2(x, -y),
        curvature_radius=g.K - 3 * g.b * np.cos(2 * phi),
    )


def crank_pin(g: WalkerGeometry, phi) -> np.ndarray:
    """B1 relative to the hub at hub angle φ: a·(sin φ, −cos φ) + b·(sin 2φ, cos 2φ), (n, 2) mm.

    With the leg part turned by φ about its origin and moved here, it stands as the paper draws
    it (the :class:`Placement` of the shoe at hub angle φ is ``(φ, crank_pin(φ))``).
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    return np.column_stack([g.a * np.sin(phi) + g.b * np.sin(2 * phi), -g.a * np.cos(phi) + g.b * np.cos(2 * phi)])


def shoe_ring(
    g: WalkerGeometry, *, tolerance: float, post_width: float = 20.0, half_range: float = STANCE
) -> np.ndarray:
    """The leg as a part: the shoe's sole over the stance, its straight back (the chord between
    the sole's ends), and a post of ``post_width`` up to B1 with a round end about B1.

    Counter-clockwise (n, 2) ring in mm, origin B1, post along −y; chords of the sole and of the
    round end stray at most ``tolerance`` from the curves.
    """
    if not 0 < half_range <= math.pi / 2:
        raise ValueError(f"half_range must be in (0, 90°], got {math.degrees(half_range):g}°")
    if g.K - 3 * g.b <= 0:
        raise ValueError(f"the shoe is not convex: K − 3b = {g.K - 3 * g.b:g} mm (K = a − b + c)")
    # the sole's tangent turns by dφ per dφ of hub angle; a chord's sag grows with the bend
    # radius K − 3b·cos 2φ, largest at the ends of the range
    rho_max = g.K - 3 * g.b * math.cos(2 * half_range)
    n = max(8, arc_steps(rho_max, tolerance, 2 * half_range))
    _, _, x, y = _points(g, np.linspace(half_range, -half_range, n + 1))  # left end → bottom → right end
    w = 0.5 * post_width
    back = y[0]
    if not (-x[0] > w and x[-1] > w and back < -w):
        raise ValueError(f"post_width {post_width:g} mm does not fit the shoe (its back is {-back:.1f} mm from B1)")
    m = arc_steps(w, tolerance, math.pi)
    top = np.linspace(0.0, math.pi, m + 1)
    end = np.column_stack([w * np.cos(top), w * np.sin(top)])  # right → over the top → left
    return np.vstack(
        [
            end,
            [[-w, back]],
            np.column_stack([x, y]),
            [[w, back]],
        ]
    )


def _placed(g: WalkerGeometry, phi_hub: float, psi):
    """Shoe points of parameter ψ, the leg placed at hub angle φ (hub at the origin)."""
    _, _, x, y = _points(g, psi)
    c, s = math.cos(phi_hub), math.sin(phi_hub)
    pin = crank_pin(g, phi_hub)[0]
    return c * x - s * y + pin[0], s * x + c * y + pin[1]


def stance_check(g: WalkerGeometry, phi=None, *, half_range: float = STANCE) -> dict:
    """Place the leg at every hub angle and find the shoe's lowest point directly.

    For each φ the placed surface's height is minimised over the surface parameter (grid, then
    Brent on the central-difference slope); the minimiser must be the paper's contact (parameter
    φ, point K1) and the hub K above it; and the placed surface's tangent at K1 (central
    difference) must be horizontal, i.e. Y2 is the contact normal.
    Returns the largest deviations (rad, mm) and ``holds``.
    """
    phi = np.linspace(-half_range, half_range, 91) if phi is None else np.asarray(phi, dtype=float)
    grid = np.linspace(-half_range, half_range, 721)
    worst = {"parameter_rad": 0.0, "contact_mm": 0.0, "normal_rad": 0.0, "hub_height_mm": 0.0}
    h = 1e-6

    def slope(s, p):  # d(height)/dψ of the placed surface, by central differences
        return (float(_placed(g, p, s + h)[1]) - float(_placed(g, p, s - h)[1])) / (2 * h)

    for p in phi:
        k = int(np.argmin(_placed(g, p, grid)[1]))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        psi = (
            brentq(lambda s, p=p: slope(s, p), lo, hi, xtol=1e-14)
            if slope(lo, p) * slope(hi, p) < 0
            else float(grid[k])
        )
        x0, y0 = (float(v) for v in _placed(g, p, psi))
        # eqs. 1–2 make Y2 (vertical when placed) the surface normal at K1: the placed surface's
        # tangent at the paper's contact (ψ = φ) must be horizontal
        xp, yp = (float(v) for v in _placed(g, p, p + h))
        xm, ym = (float(v) for v in _placed(g, p, p - h))
        pin = crank_pin(g, p)[0]
        y1, y2 = (float(v) for v in _points(g, p)[:2])
        k1 = pin + y1 * np.array([math.sin(p), -math.cos(p)]) + np.array([0.0, -y2])
        worst["parameter_rad"] = max(worst["parameter_rad"], abs(psi - p))
        worst["contact_mm"] = max(worst["contact_mm"], float(np.hypot(x0 - k1[0], y0 - k1[1])))
        worst["normal_rad"] = max(worst["normal_rad"], abs(math.asin((yp - ym) / math.hypot(xp - xm, yp - ym))))
        worst["hub_height_mm"] = max(worst["hub_height_mm"], abs(-y0 - g.K))
    worst["holds"] = worst["contact_mm"] < 1e-6 and worst["hub_height_mm"] < 1e-9 and worst["normal_rad"] < 1e-7
    worst["hub_height"] = g.K
    return worst


def ring_stance_check(g: WalkerGeometry, ring: np.ndarray, phi=None) -> dict:
    """The written part placed at every hub angle: its lowest vertex must lie K below the hub
    (within the outline tolerance) and horizontally at the paper's contact K1 within the
    longest sole chord (``chord_mm``: the flat bottom leaves the lowest vertex that free)."""
    phi = np.linspace(-STANCE, STANCE, 91) if phi is None else np.asarray(phi, dtype=float)
    back = ring[int(np.argmax(ring[:, 0])), 1]  # the sole's ends are its widest points
    edges = np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T)
    ends = np.vstack([ring[1:], ring[:1]])
    sole = (ring[:, 1] <= back + 1e-9) & (ends[:, 1] <= back + 1e-9) & ~((ring[:, 1] == back) & (ends[:, 1] == back))
    chord = float(edges[sole].max())
    height = across = 0.0
    for p in phi:
        c, s = math.cos(p), math.sin(p)
        pts = np.column_stack([c * ring[:, 0] - s * ring[:, 1], s * ring[:, 0] + c * ring[:, 1]]) + crank_pin(g, p)
        k = int(np.argmin(pts[:, 1]))
        y1, y2 = (float(v) for v in _points(g, p)[:2])
        k1x = crank_pin(g, p)[0, 0] + y1 * math.sin(p)
        height = max(height, abs(-pts[k, 1] - g.K))
        across = max(across, abs(pts[k, 0] - k1x))
    return {"hub_height_mm": height, "contact_across_mm": across, "chord_mm": chord}


def speed_comparison(g: WalkerGeometry, *, i_paper: float, law=None, samples: int = 361) -> dict:
    """Vehicle speed per unit drive-shaft speed, v/ω (mm/rad), over a stance quarter.

    * ``round``: the existing machine's round gears, ω/ω_H = 4;
    * ``paper_as_built``: the paper's pitch curves kept in contact on the line of centres force
      θ = 4φ (that is how eq. 12 was made), so ω/ω_H = 4 — the same speed as round gears;
    * ``paper_as_intended``: ω/ω_H = r_H/r = i_paper·(K + 3b·cos 2φ)/K: v/ω = K/i_paper, but the
      pinion would turn i_paper·(π/2 + 3b/K) per quarter instead of 2π;
    * ``rolling``: the pair that rolls and closes, ratio ``law.k(φ)`` (a
      :class:`~gearcad.pitch.walker.RatioLaw`, blended or not); omitted when ``law`` is None.

    Each entry: ``v`` (list), ``min``, ``max``, ``mean`` (distance / time over the quarter) and
    ``variation`` = (max − min)/mean.
    """
    phi = np.linspace(-STANCE, STANCE, samples)
    dx = shoe_functions(phi, g)["dX01"]
    u = g.K + 3 * g.b * np.cos(2 * phi)
    ratios = {
        "round": np.full_like(phi, 4.0),
        "paper_as_built": np.full_like(phi, 4.0),
        "paper_as_intended": i_paper * u / g.K,
    }
    if law is not None:
        ratios["rolling"] = np.asarray(law.k(phi), dtype=float)

    if samples % 2 == 0:
        raise ValueError(f"Simpson's rule needs an odd number of samples, got {samples}")
    weights = np.ones(samples)
    weights[1:-1:2], weights[2:-1:2] = 4.0, 2.0
    weights *= (phi[1] - phi[0]) / 3

    def integral(values):  # composite Simpson on the uniform grid
        return float(weights @ values)

    out = {"phi_deg": np.degrees(phi).tolist()}
    for name, ratio in ratios.items():
        v = dx / ratio
        mean = integral(dx) / integral(ratio)
        out[name] = {
            "v": v.tolist(),
            "min": float(v.min()),
            "max": float(v.max()),
            "mean": mean,
            "variation": float((v.max() - v.min()) / mean),
            "pinion_turn_per_quarter_deg": math.degrees(integral(ratio)),
        }
    return out
