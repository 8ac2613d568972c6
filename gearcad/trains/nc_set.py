"""The carrier-less noncircular planetary as a whole (:mod:`.nc_planetary`'s kinematics kept as
periodic interpolants): the ring's turn and pitch curve, every planet with the ring held, the
phasing rule, and a certified bound of the planets' gap over the cycle."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..pitch.curve import PitchCurve, harmonic_series
from .nc_planetary import TWO_PI, Lobed, RingData, _ArcLength, by_arc_length, poses

__all__ = ["PlanetarySet", "planetary_set", "phasing", "planet_gap", "as_pitch_curve", "ring_pitch_curve"]


class _Periodic:
    """A smooth function sampled evenly over one period, evaluated anywhere by its Fourier series
    (trigonometric interpolation: spectral for the analytic functions of this model)."""

    def __init__(self, values: np.ndarray, period: float):
        self.period = period
        self.m = len(values)
        self.coef = np.fft.rfft(values) / self.m

    def __call__(self, t, power: int = 0):
        t = np.asarray(t, dtype=float)
        k = np.arange(len(self.coef))
        w = TWO_PI * k / self.period
        c = self.coef.copy()
        if self.m % 2 == 0:
            c[-1] *= 0.5
        c[1:] *= 2
        phase = np.exp(1j * np.multiply.outer(t, w))
        return ((c * (1j * w) ** power) * phase).sum(-1).real


@dataclass(frozen=True)
class PlanetarySet:
    """The carrier-less set, sun held as the reference frame: the first planet's pose and the
    ring's turn φ_r for any sun angle θ (contact direction), the ring's pitch curve in its frame.

    With the ring held instead (:meth:`ring_held`) the sun turns by −φ_r(θ) and every planet's
    centre orbits at the angle γ(θ) = θ − φ_r(θ) about O (the planets' "carrier" angle)."""

    sun: Lobed
    planet: Lobed
    planets: int
    ring_lobes: int
    data: RingData
    _rho: _Periodic
    _rate: _Periodic
    """dφ_r/dθ over one sun lobe."""

    @property
    def lobe(self) -> float:
        return TWO_PI / self.sun.lobes

    def ring_turn(self, theta):
        """φ_r(θ): the ring's turn (sun held) when the first planet touches the sun at θ."""
        theta = np.asarray(theta, dtype=float)
        mean = self._rate.coef[0].real
        k = np.arange(1, len(self._rate.coef))
        w = TWO_PI * k / self.lobe
        c = 2 * self._rate.coef[1:].copy()
        if self._rate.m % 2 == 0:
            c[-1] *= 0.5
        wave = (c / (1j * w) * (np.exp(1j * np.multiply.outer(theta, w)) - 1.0)).sum(-1).real
        return mean * theta + wave

    def rho(self, theta):
        """|P2|: the ring's pitch radius where the first planet touches it."""
        return self._rho(np.mod(np.asarray(theta, dtype=float), self.lobe))

    def ring_angle(self, theta):
        """γ(θ) = θ − φ_r(θ): where that contact is round the ring, in the ring's frame."""
        return np.asarray(theta, dtype=float) - self.ring_turn(theta)

    def ring_radius_at(self, gamma, *, iterations: int = 20) -> np.ndarray:
        """The ring's pitch radius at polar angle γ of its own frame (Newton on γ(θ) = γ, to
        round-off: quadratic from the linear guess, a handful of steps)."""
        gamma = np.asarray(gamma, dtype=float)
        slope = self.data.sweep / self.lobe
        theta = gamma / slope
        for _ in range(iterations):
            rate = 1.0 - self._rate(np.mod(theta, self.lobe))
            step = (self.ring_angle(theta) - gamma) / rate
            theta = theta - step
            if np.max(np.abs(step)) < 1e-14 * (1.0 + np.max(np.abs(theta))):
                break
        return self.rho(theta)

    def ring_held(self, theta) -> dict:
        """The set with the ring held: the sun's turn, each planet's centre (N, 2) and turn, at the
        first planet's sun contact θ (scalar)."""
        sun, centres, turns = self.ring_held_frames(np.array([float(theta)]))
        return {"sun": float(sun[0]), "centres": centres[0], "turns": turns[0]}

    def ring_held_frames(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`ring_held` at many θ at once: the sun's turns (f,), the planets' centres
        (f, N, 2) and turns (f, N)."""
        theta = np.asarray(theta, dtype=float)
        phi = self.ring_turn(theta)
        pose = poses(self.sun, self.planet, theta)
        a = TWO_PI * np.arange(self.planets)[None, :] / self.planets - phi[:, None]
        ca, sa = np.cos(a), np.sin(a)
        cx, cy = pose.centre[:, :1], pose.centre[:, 1:]
        centres = np.stack([ca * cx - sa * cy, sa * cx + ca * cy], axis=-1)
        return -phi, centres, pose.beta[:, None] + a


def planetary_set(sun: Lobed, planet: Lobed, planets: int, ring_lobes: int, samples: int = 128) -> PlanetarySet:
    """The set of ``planets`` planets in a ring of ``ring_lobes`` lobes: the kinematics of
    :func:`by_arc_length` kept as periodic interpolants (ρ and dφ_r/dθ over one sun lobe)."""
    n = sun.lobes
    lobe = TWO_PI / n
    arcs = (_ArcLength(sun), _ArcLength(planet))
    theta = np.arange(samples) * lobe / samples
    pose = poses(sun, planet, theta, arcs)
    per_lobe = arcs[1].c0 * lobe
    sp = arcs[1](pose.chi) + per_lobe * theta / lobe
    wave = np.fft.rfftfreq(samples, d=lobe / samples) * TWO_PI
    dsp = np.fft.irfft(1j * wave * np.fft.rfft(sp), n=samples) - per_lobe / lobe
    drho = np.fft.irfft(1j * wave * np.fft.rfft(pose.rho), n=samples)
    dgamma = np.sign(dsp) * np.sqrt(np.maximum(dsp * dsp - drho * drho, 0.0)) / pose.rho
    data = by_arc_length(sun, planet, samples)
    return PlanetarySet(
        sun, planet, planets, ring_lobes, data, _Periodic(pose.rho, lobe), _Periodic(1.0 - dgamma, lobe)
    )


def phasing(sun_lobes: int, ring_lobes: int, planets: int) -> str | None:
    """Why N planets cannot be assembled evenly spaced (None if they can): the set must be its own
    copy turned by 2π/N, so N divides both lobe counts, and a carrier-less set needs N ≥ 3."""
    if planets < 3:
        return "at least 3 planets hold a carrier-less set"
    g = math.gcd(sun_lobes, ring_lobes)
    if g % planets:
        ok = [d for d in range(3, g + 1) if g % d == 0]
        return f"the planets must divide gcd(sun lobes, ring lobes) = {g}: " + (
            "use " + " or ".join(map(str, ok)) + " planets" if ok else "no count of 3 or more does"
        )
    return None


def planet_gap(ps: PlanetarySet, *, points: int = 720, tol: float = 5e-3) -> tuple[float, float, float]:
    """The least distance between neighbouring planets' pitch curves over the whole cycle: a
    certified lower bound, the least value measured, and the sun angle θ where that occurs.

    The pair (planet 0, planet 1) repeats every sun lobe, so θ runs over one lobe.  At a θ the
    distance of the two ``points``-gons (exact, GEOS) is within the chords' sagitta (κ_max·h²/8
    each) of the curves'.  Seen from a frame turning with θ about O, a planet's centre moves at
    |C′ − k×C| and it turns at β′ − 1 about it, β′ = |S′|·(κ_sun + κ_planet) (it rolls on the
    sun), so no point of either planet moves faster than v = max|C′ − k×C| + max|β′ − 1|·r_max
    and the distance is Lipschitz in θ with L = 2v (the maxima on a dense grid, 1 % over).  An
    interval [a, b] holds no distance below (g(a) + g(b))/2 − L·(b − a)/2; intervals whose bound
    lies more than ``tol``·R under the least value found are halved until none does."""
    import shapely

    sun, planet = ps.sun, ps.planet
    dense = np.linspace(0.0, TWO_PI, 4097)
    r_max = float(planet.r(dense).max())
    arcs = (_ArcLength(sun), _ArcLength(planet))
    grid = np.linspace(0.0, ps.lobe, 2049)
    pose = poses(sun, planet, grid, arcs)
    dc = np.gradient(pose.centre, grid, axis=0)
    drift = np.hypot(dc[:, 0] + pose.centre[:, 1], dc[:, 1] - pose.centre[:, 0])
    spin = sun.speed(grid) * (sun.curvature(grid) + planet.curvature(pose.psi)) - 1.0
    lipschitz = 2.0 * 1.01 * (float(drift.max()) + float(np.abs(spin).max()) * r_max)
    h = TWO_PI / points
    sagitta = 2 * float(np.abs(planet.curvature(dense)).max()) * (float(planet.speed(dense).max()) * h) ** 2 / 8
    chi = np.arange(points) * h
    q = planet.point(chi)
    turn = TWO_PI / ps.planets
    cr, sr = math.cos(turn), math.sin(turn)
    cache: dict[float, float] = {}

    def measure(thetas) -> None:
        new = np.array(sorted({float(t) for t in thetas} - cache.keys()))
        if not len(new):
            return
        pose = poses(sun, planet, new, arcs)
        c0, b0 = pose.centre, pose.beta
        c1 = np.column_stack([cr * c0[:, 0] - sr * c0[:, 1], sr * c0[:, 0] + cr * c0[:, 1]])
        placed = []
        for c, b in ((c0, b0), (c1, b0 + turn)):  # each planet's polygon at every θ at once
            cb, sb = np.cos(b)[:, None], np.sin(b)[:, None]
            x = c[:, :1] + cb * q[:, 0] - sb * q[:, 1]
            y = c[:, 1:] + sb * q[:, 0] + cb * q[:, 1]
            placed.append(shapely.polygons(np.stack([x, y], -1)))
        for theta, gap in zip(new, shapely.distance(*placed)):
            cache[float(theta)] = float(gap)

    def gap(theta: float) -> float:
        return cache[float(theta)]

    intervals = [(a, a + ps.lobe / 32) for a in np.arange(32) * ps.lobe / 32]
    best = bound = math.inf
    for _ in range(40):
        measure([t for ab in intervals for t in ab])
        low = [(0.5 * (gap(a) + gap(b)) - lipschitz * (b - a) / 2, a, b) for a, b in intervals]
        best = min(cache.values())
        bound = min(x for x, _, _ in low)
        if bound >= best - tol * sun.radius:
            break
        split = []
        for x, a, b in low:
            split += [(a, (a + b) / 2), ((a + b) / 2, b)] if x < best - tol * sun.radius else [(a, b)]
        intervals = split
    where = min(cache, key=cache.get)
    return max(min(bound, best) - sagitta, 0.0), best, float(where)


def as_pitch_curve(curve: Lobed, name: str) -> PitchCurve:
    """The shared curve as a :class:`~gearcad.pitch.curve.PitchCurve` (for cutting teeth)."""
    return PitchCurve(name=name, r=curve.r, dr=curve.dr, d2r=curve.d2r, lobes=curve.lobes)


def ring_pitch_curve(ps: PlanetarySet, name: str = "ring", *, per_lobe: int = 64) -> PitchCurve:
    """The ring's pitch curve ρ(γ) in its own frame as a Fourier series in u = L·γ (L the ring's
    lobes: ρ repeats every 2π/L; spectral, ρ being analytic for a convex planet), from
    ``per_lobe`` samples of one lobe found by Newton on γ(θ) = γ; derivatives by the chain rule."""
    lobes = ps.ring_lobes
    gamma = np.arange(per_lobe) * TWO_PI / lobes / per_lobe
    coef = np.fft.rfft(ps.ring_radius_at(gamma)) / per_lobe
    spectrum = 2 * coef
    spectrum[0] = coef[0]
    if per_lobe % 2 == 0:
        spectrum[-1] = coef[-1]
    keep = np.nonzero(np.abs(spectrum) > 1e-15 * abs(spectrum[0]))[0]
    series = harmonic_series(spectrum[: keep.max() + 1])
    return PitchCurve(
        name=name,
        r=lambda p: series(lobes * np.asarray(p, dtype=float)),
        dr=lambda p: lobes * series(lobes * np.asarray(p, dtype=float), 1),
        d2r=lambda p: lobes * lobes * series(lobes * np.asarray(p, dtype=float), 2),
        lobes=lobes,
    )
