"""The carrier-less noncircular planetary: a lobed sun, N identical planets, a lobed ring.

The model (docs/mechanisms.md, "Noncircular planetary"), in the sun's frame (the sun held, its
centre O at the origin):

* Sun and planets share one pitch curve ``r(θ) = R·(1 + e·cos nθ + e₂·cos 2nθ)`` (e₂ = 0 for the
  makers' curve; e₂ is the free parameter of exact closure).
* A planet rolls on the sun **exactly**: the two curves touch, tangent, at the point P1 = S(θ) of
  the sun, and the arc lengths rolled on both are equal.  At θ = 0 the sun's lobe (θ = 0) meets
  the planet's valley (ψ = π/n); as the contact runs forward on the sun it runs back on the
  planet, ``s(ψ) = s(π/n) − s(θ)`` (s the arc length of the curve from polar angle 0).  This
  fixes the planet's pose: its turn β (the tangents opposite at P1) and its centre C = P1 −
  Rot(β)·Q(ψ).  The centre distance |C| is not constant: that is the planets' orbit law.
* Aronhold–Kennedy: the planet–sun instant centre is P1, the ring–sun one is O, so the
  planet–ring instant centre P2 is on the line O P1; for the planet's pitch curve to be its
  centrode against the ring, P2 is where that ray leaves the planet on its far side.  The ring
  turns about O at ω_r = ω_p·|P2 − P1|/|P2|, ω_p = ds·(κ_sun + κ_planet) the planet's rate.
* The ring's pitch curve is the locus of P2 in the ring's frame: radius ρ = |P2| at polar angle
  γ = θ − φ_r.  Per sun lobe (θ from 0 to 2π/n, after which the picture repeats turned by
  2π/n) γ changes by Δγ; the ring has n_r = 2π/|Δγ| lobes, its **natural lobe count**, which
  is an integer only by design (:func:`close_ring`).

Two computations, sharing only the curve and the pose's geometry:

* :func:`by_sun_angle` — the Kennedy rate ω_r integrated over the sun's angle θ, the planet's
  angle ψ(θ) from the rolling ODE dψ/dθ = −|S′(θ)|/|S′(ψ)|, classical Runge–Kutta.
* :func:`by_arc_length` — ψ by inverting the arc length (a Fourier series of |S′|), and the ring
  rolled on the planet: the ring's pitch curve is as long as the planet's arc its contact
  sweeps, so ρ·|dγ| = √(ds_p² − dρ²); periodic samples, derivatives and the integral spectral.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from ..roots import brentq
from .lobed import Lobed, convex_limit

__all__ = [
    "Lobed",
    "RingData",
    "PlanetPoses",
    "by_sun_angle",
    "by_arc_length",
    "poses",
    "convex_limit",
    "close_ring",
    "circular_ring_speed",
    "matched_sun",
]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class RingData:
    """One sun lobe of the carrier-less set, sun held (lengths in the curve's units)."""

    natural_lobes: float
    """n_r = 2π/|Δγ|: the ring's lobes if its pitch curve is to be the planet's conjugate."""
    sweep: float
    """Δγ: how far the ring contact moves round the ring per sun lobe, rad (negative: backward)."""
    ring_turn: float
    """Δφ_r: how far the ring turns per sun lobe, sun held, rad."""
    orbit_min: float
    orbit_max: float
    """Least and largest distance of a planet's centre from the sun's."""

    @property
    def orbit_change(self) -> float:
        """(max − min)/mean of the orbit radius: the change of the planets' orbit radius."""
        return (self.orbit_max - self.orbit_min) / (0.5 * (self.orbit_max + self.orbit_min))


def _far_contact(curve: Lobed, theta, centre, beta, guess):
    """Polar angle χ (planet frame) where the ray from O at angle θ leaves the planet: Newton on
    f(χ) = (u × C) + r(χ)·sin(χ − (θ − β)) = 0, started at χ = θ − β (the side facing away)."""
    lam = theta - beta
    ux, uy = np.cos(theta), np.sin(theta)
    base = ux * centre[..., 1] - uy * centre[..., 0]
    chi = np.array(guess, dtype=float)
    for _ in range(50):
        s, c = np.sin(chi - lam), np.cos(chi - lam)
        f = base + curve.r(chi) * s
        step = f / (curve.dr(chi) * s + curve.r(chi) * c)
        chi = chi - step
        if np.max(np.abs(step)) < 1e-15:
            break
    return chi


def _pose(sun: Lobed, planet: Lobed, theta, psi):
    """The planet's turn β and centre C when its point ψ rolls on the sun's point θ."""
    beta = sun.tangent_angle(theta) + np.pi - planet.tangent_angle(psi)
    cb, sb = np.cos(beta), np.sin(beta)
    q = planet.point(psi)
    p = sun.point(theta)
    centre = np.stack(
        [p[..., 0] - (cb * q[..., 0] - sb * q[..., 1]), p[..., 1] - (sb * q[..., 0] + cb * q[..., 1])], -1
    )
    return beta, centre


def _pose_scalar(sun: Lobed, planet: Lobed, theta: float, psi: float) -> tuple[float, float, float]:
    """:func:`_pose` for one θ and ψ in plain floats (β, C_x, C_y): the same formulas, without
    numpy's per-call cost (the integrator asks for it 2000 times)."""
    r, dr, _ = sun._scalar(theta)
    q, dq, _ = planet._scalar(psi)
    beta = theta + math.atan2(r, dr) + math.pi - (psi + math.atan2(q, dq))
    cb, sb = math.cos(beta), math.sin(beta)
    qx, qy = q * math.cos(psi), q * math.sin(psi)
    return beta, r * math.cos(theta) - (cb * qx - sb * qy), r * math.sin(theta) - (sb * qx + cb * qy)


# ----------------------------------------------------------------------------- method 1


def by_sun_angle(sun: Lobed, planet: Lobed | None = None, steps: int = 2000) -> RingData:
    """n_r by the Kennedy rate integrated over the sun's angle (classical RK4, ``steps`` a lobe).

    y = (ψ, φ_r): ψ′ = −|S′(θ)|/|S′(ψ)|, φ_r′ = |S′(θ)|·(κ(θ) + κ(ψ))·|P2 − P1|/|P2|, where P2 is
    found on the ray by bisection (Brent), independent of :func:`by_arc_length`'s Newton."""
    planet = planet or sun
    n = sun.lobes

    def far(theta: float, psi: float) -> tuple[float, float, float]:
        beta, cx, cy = _pose_scalar(sun, planet, theta, psi)
        ux, uy = math.cos(theta), math.sin(theta)
        lam = theta - beta

        def f(chi: float) -> float:
            r = planet._scalar(chi)[0]
            return ux * cy - uy * cx + r * math.sin(chi - lam)

        chi = brentq(f, lam - 1.0, lam + 1.0, xtol=1e-15, rtol=1e-15)
        r = planet._scalar(chi)[0]
        px, py = cx + r * math.cos(chi + beta), cy + r * math.sin(chi + beta)
        rho = px * ux + py * uy
        return rho, math.hypot(cx, cy), rho - sun._scalar(theta)[0]

    def rhs(theta: float, psi: float) -> tuple[float, float]:
        r, dr, d2r = sun._scalar(theta)
        q, dq, d2q = planet._scalar(psi)
        g_s, g_p = math.hypot(r, dr), math.hypot(q, dq)
        k_s = (r * r + 2 * dr * dr - r * d2r) / g_s**3
        k_p = (q * q + 2 * dq * dq - q * d2q) / g_p**3
        rho, _, arm = far(theta, psi)
        return -g_s / g_p, g_s * (k_s + k_p) * arm / rho

    h = TWO_PI / n / steps
    theta, psi, phi = 0.0, math.pi / n, 0.0
    orbit = [far(theta, psi)[1]]
    for _ in range(steps):
        k1 = rhs(theta, psi)
        k2 = rhs(theta + h / 2, psi + h / 2 * k1[0])
        k3 = rhs(theta + h / 2, psi + h / 2 * k2[0])
        k4 = rhs(theta + h, psi + h * k3[0])
        psi += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        phi += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        theta += h
        orbit.append(far(theta, psi)[1])
    sweep = TWO_PI / n - phi
    return RingData(TWO_PI / abs(sweep), sweep, phi, *_vertex_extremes(np.array(orbit)))


def _vertex_extremes(values: np.ndarray) -> tuple[float, float]:
    """Least and largest of a smooth periodic function sampled evenly (last sample = first):
    the parabola through each sampled extreme and its neighbours, its vertex value."""
    y = values[:-1]
    out = []
    for sign in (1.0, -1.0):
        k = int(np.argmin(sign * y))
        a, b, c = y[k - 1], y[k], y[(k + 1) % len(y)]
        den = a - 2 * b + c
        out.append(float(b - (c - a) ** 2 / (8 * den)) if den != 0 else float(b))
    return out[0], out[1]


# ----------------------------------------------------------------------------- method 2


class _ArcLength:
    """s(θ) = c₀θ + Σ (a_k sin kθ − b_k cos kθ)/k + const, from the FFT of |S′| (spectral)."""

    def __init__(self, curve: Lobed, samples: int = 1024):
        t = np.arange(samples) * TWO_PI / samples
        coef = np.fft.rfft(curve.speed(t)) / samples
        self.c0 = coef[0].real
        keep = np.abs(coef) > 1e-17 * abs(self.c0)  # the rest is round-off (≤ 1e-17 of s)
        keep[0] = False
        self.k = np.nonzero(keep)[0]
        self.a = 2 * coef.real[self.k]
        self.b = -2 * coef.imag[self.k]
        self.curve = curve

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        kt = np.multiply.outer(t, self.k)
        return self.c0 * t + (np.sin(kt) * self.a / self.k - (np.cos(kt) - 1.0) * self.b / self.k).sum(-1)

    def invert(self, s, guess):
        t = np.array(guess, dtype=float)
        for _ in range(60):
            step = (self(t) - s) / self.curve.speed(t)
            t = t - step
            if np.max(np.abs(step)) < 1e-15:
                break
        return t


@dataclass(frozen=True)
class PlanetPoses:
    """A planet's state at sun angles θ (sun held): its rolled angle ψ, turn β, centre C, the far
    contact's polar angle χ on the planet and ρ = |P2| on the ray at θ."""

    theta: np.ndarray
    psi: np.ndarray
    beta: np.ndarray
    centre: np.ndarray
    chi: np.ndarray
    rho: np.ndarray


def poses(sun: Lobed, planet: Lobed, theta, arcs: tuple[_ArcLength, _ArcLength] | None = None) -> PlanetPoses:
    """The first planet's pose for each sun angle θ (vectorised; θ may run past one lobe)."""
    arc_s, arc_p = arcs or (_ArcLength(sun), _ArcLength(planet))
    n = sun.lobes
    theta = np.asarray(theta, dtype=float)
    target = arc_p(np.pi / n) - arc_s(theta)
    psi = arc_p.invert(target, np.pi / n - theta)
    beta, centre = _pose(sun, planet, theta, psi)
    chi = _far_contact(planet, theta, centre, beta, theta - beta)
    cb, sb = np.cos(beta), np.sin(beta)
    q = planet.point(chi)
    p2 = np.stack(
        [centre[..., 0] + cb * q[..., 0] - sb * q[..., 1], centre[..., 1] + sb * q[..., 0] + cb * q[..., 1]], -1
    )
    rho = p2[..., 0] * np.cos(theta) + p2[..., 1] * np.sin(theta)
    return PlanetPoses(theta, psi, beta, centre, chi, rho)


def by_arc_length(sun: Lobed, planet: Lobed | None = None, samples: int = 128, *, extremes: bool = True) -> RingData:
    """n_r by rolling the ring on the planet: ρ·|dγ/dθ| = √((ds_p/dθ)² − (dρ/dθ)²) over one sun
    lobe, the periodic parts differentiated and integrated spectrally on ``samples`` points."""
    planet = planet or sun
    n = sun.lobes
    arcs = (_ArcLength(sun), _ArcLength(planet))
    arc = arcs[1]
    lobe = TWO_PI / n
    theta = np.arange(samples) * lobe / samples
    pose = poses(sun, planet, theta, arcs)
    per_lobe = arc.c0 * lobe  # the planet's arc of one lobe: the far contact runs back by it
    sp = arc(pose.chi) + per_lobe * theta / lobe  # periodic in θ
    wave = np.fft.rfftfreq(samples, d=lobe / samples) * TWO_PI

    def derivative(y):
        return np.fft.irfft(1j * wave * np.fft.rfft(y), n=samples)

    dsp = derivative(sp) - per_lobe / lobe
    drho = derivative(pose.rho)
    # the ring's arc runs with the planet's (no slip); beyond convexity the planet's contact can
    # stop and turn back, and the ring's with it: the sign is the planet's
    rate = np.sign(dsp) * np.sqrt(np.maximum(dsp * dsp - drho * drho, 0.0)) / pose.rho
    sweep = float(rate.mean()) * lobe
    orbit = np.hypot(pose.centre[:, 0], pose.centre[:, 1])
    if extremes:
        lo, hi = _refined_extremes(sun, planet, arcs, orbit, theta, lobe / samples)
    else:
        lo, hi = float(orbit.min()), float(orbit.max())
    return RingData(TWO_PI / abs(sweep), sweep, lobe - sweep, lo, hi)


def _refined_extremes(sun, planet, arcs, orbit, theta, h) -> tuple[float, float]:
    """The orbit radius's least and largest values: each sampled extreme refined by zooming a
    33-point grid on the exact pose round it (each round 16 times finer, to ~1e-7 rad in θ,
    ~1e-14 in the value at a smooth extreme), since sampled values bound nothing by themselves."""

    def radius(t):
        c = poses(sun, planet, t, arcs).centre
        return np.hypot(c[:, 0], c[:, 1])

    out = []
    for sign in (1.0, -1.0):
        best = theta[int(np.argmin(sign * orbit))]
        width = h
        for _ in range(5):
            grid = best + np.linspace(-width, width, 33)
            values = sign * radius(grid)
            best = grid[int(np.argmin(values))]
            width /= 16
        out.append(float(sign * values.min()))
    return out[0], out[1]


# ----------------------------------------------------------------------------- closure


def circular_ring_speed(sun: float, planet: float) -> float:
    """The ring's turn per carrier turn, sun held, circular set (method of stopping): ring
    radius sun + 2·planet, ω_r/ω_c = 1 + sun/ring."""
    return 1.0 + sun / (sun + 2 * planet)


def matched_sun(planet: Lobed, e: float) -> Lobed:
    """The sun of eccentricity ``e`` whose lobe is exactly as long as the planet's (its mean
    radius scaled: arc length is linear in R), so that a lobe still meets a valley each lobe."""
    trial = Lobed(1.0, planet.lobes, e)
    return Lobed(float(_ArcLength(planet).c0 / _ArcLength(trial).c0), planet.lobes, e)


def close_ring(planet: Lobed, ring_lobes: int, *, key: str = "e") -> tuple[Lobed, float]:
    """The sun that makes the ring close with exactly ``ring_lobes`` lobes round the given planets.

    Identical sun and planets never close (n_r > 3n for every e > 0 and every small second
    harmonic shared by both: docs/mechanisms.md); the free parameter is the sun's own
    eccentricity e_s, its mean radius matched so that its lobe is as long as the planet's.  The
    residual ring_lobes·|Δγ(e_s)| − 2π is bracketed by stepping out from e_s = e in both
    directions (within convexity) and its root found by Brent's method.  Returns the sun and the
    closure residual |ring_lobes·|Δγ| − 2π|, rad."""

    seen: dict[float, float] = {}

    def residual(es: float) -> float:
        if es not in seen:
            sweep = by_arc_length(matched_sun(planet, es), planet, extremes=False).sweep
            seen[es] = ring_lobes * abs(sweep) - TWO_PI
        return seen[es]

    limit = convex_limit(planet.lobes)
    e0 = planet.e
    r0 = residual(e0)
    if abs(r0) <= 1e-12:  # closed already (circles: the residual's double root at e = 0)
        return matched_sun(planet, e0), abs(r0)
    step = 0.1 * limit
    bracket = None
    for k in range(1, 11):
        for side in (1.0, -1.0):
            x = e0 + side * k * step
            if not 0.0 <= x < limit:
                continue
            near = e0 + side * (k - 1) * step
            if residual(x) * residual(near) <= 0:
                bracket = (min(near, x), max(near, x))
                break
        if bracket:
            break
    if bracket is None:
        natural = TWO_PI / abs(by_arc_length(planet, extremes=False).sweep)
        raise DesignError(
            f"{key} = {e0:g}: no sun eccentricity in [0, {limit:.4g}) closes the ring at {ring_lobes} lobes round "
            f"these planets (natural lobe count {natural:.4f}); choose another e or ring lobes"
        )
    es = brentq(residual, *bracket, xtol=1e-16, rtol=1e-15)
    sun = matched_sun(planet, es)
    return sun, abs(residual(es))
