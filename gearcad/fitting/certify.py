"""The certificate of a pair's least play between the driver positions measured (docs/fit.md, "How
the least play is certified"), as ``output.certificate`` picks it: by default an *estimate* — the
tight case's play bounded between positions by a Lipschitz constant taken from the slopes it
shows, refined where that cannot settle the verdict (:func:`certify_play`); a dip narrower than
the slopes around it could hide.  The *theorem* (:func:`.prove.prove_play`) bounds it from the
geometry, at 6–45 times the CPU."""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace

import numpy as np

from .play import PairGeometry, measure

__all__ = ["KINDS", "PER_TOOTH", "Certificate", "certify", "certify_play"]

KINDS = ("estimate", "theorem")
"""The certificates ``output.certificate`` picks from: the slope estimate (:func:`certify_play`,
the default) and the theorem (:func:`.prove.prove_play`)."""


@dataclass(frozen=True)
class Certificate:
    """How the smallest play of the tight case was bounded between the positions measured."""

    lower: float
    """The least play the verdict rests on (mm): under ``kind`` "theorem" no driver angle of the
    cycle has less (proven); under "estimate" the slope bound's least (:func:`certify_play`)."""
    positions: int
    """Driver positions measured for it (the first even ones and those refined)."""
    slack: float
    """The least measured play less ``lower`` (mm): what the bound gives away."""
    proven: bool
    """Whether the bound settled the verdict (``lower`` keeps the margin, or a measured position
    falls below it); False: the work budget ran out first (``open`` is the interval)."""
    open: tuple[float, float] = (0.0, 0.0)
    """The driver interval (rad) whose play the budget could not bound, when not ``proven``."""
    kind: str = "estimate"
    """Which bound: "estimate" (slopes, :func:`certify_play`) or "theorem" (:func:`.prove.prove_play`)."""

    def as_dict(self) -> dict:
        out = {"certificate": self.kind, "certified_min": self.lower, "positions": self.positions}
        out |= {"slack": self.slack, "proven": self.proven}
        if not self.proven:
            out["open_phi"] = list(self.open)
        return out


PER_TOOTH = 2
"""Positions a driver tooth the certificate starts from: the play turns once a tooth (one
contact hands over to the next): two a tooth see each hand-over's slope, and the bound refines
    from there."""
SAFETY = 2.0
"""The certificate's Lipschitz bound over an interval is this many times the steepest slope the
play shows over it and the :data:`REACH` intervals either side."""
REACH = 2
JAM_HALVINGS = 1
"""Once a measured position jams, the intervals about the least play are halved this many times
more to say how far short it falls (the verdict is settled)."""


def certify_play(g: PairGeometry, offsets, spread: float, tol: float, *, reach: float, margin: float, budget: int = 0):
    """The tight case's signed play, measured at ``g``'s positions and refined where the estimated
    bound between them cannot settle the verdict: (geometry at every position measured, play
    there, :class:`Certificate` of kind "estimate").

    Between two measured driver angles a and b = a + h the play is at least
    min(p(a), p(b)) − L·h/2, L the Lipschitz bound: :data:`SAFETY` times the steepest slope
    |p(b) − p(a)|/h of the interval and :data:`REACH` intervals either side (it grows as the
    refining finds steeper flanks; a tight spot between two positions shows in the slopes of its
    neighbours), and never under the resolution over the cycle.  An interval whose bound stays
    under the margin is halved — once the pair is shown to jam, only those near the least play
    found whose bound lies under it less the resolution, max(tol, 1e-4·m), at most
    :data:`JAM_HALVINGS` times — until all are
    settled, none is narrower than a millionth of the cycle, or the budget (4 times the first
    positions) runs out: then the certificate is not ``proven`` and names the interval."""
    if g.first is not None:  # the certificate's own even start along the pitch curve
        g = g.at(g.first)
    measured: list[PairGeometry] = []

    def play_at(phi: np.ndarray) -> np.ndarray:
        sub = g.at(phi) if measured else g
        measured.append(sub)
        return measure(sub, offsets, spread, tol, reach=reach)

    _, play, cert = certify(play_at, g.phi1, g.cycle, module=g.module, tol=tol, margin=margin, budget=budget)
    return functools.reduce(_joined, measured), play, cert


def certify(measure, first: np.ndarray, cycle: float, *, module: float, tol: float, margin: float, budget: int = 0):
    """The tight case's signed play measured at the driver angles ``first`` and refined where the
    bound between them cannot settle the verdict: (angles measured, play there, certificate).
    ``measure(phi) -> play``.  The bound, constants and refining are
    :func:`~.certify.certify_play`'s: between a and b = a + h the play is at least
    min(p(a), p(b)) − L·h/2, L :data:`~.certify.SAFETY` times the steepest slope over the interval
    and :data:`~.certify.REACH` either side, never under the resolution over the cycle."""
    budget = budget or 4 * len(first)
    resolution = max(tol, 1e-4 * module)
    narrowest = 1e-6 * cycle
    phi, play = np.asarray(first, dtype=float), measure(np.asarray(first, dtype=float))
    jammed = 0
    while True:
        order = np.argsort(phi, kind="stable")
        a, b = order, np.roll(order, -1)
        lo = phi[a]
        h = (phi[b] - lo) % cycle
        slope = np.abs(play[b] - play[a]) / np.maximum(h, narrowest)
        near = np.max([np.roll(slope, j) for j in range(-REACH, REACH + 1)], axis=0)
        lipschitz = np.maximum(SAFETY * near, resolution / cycle)
        ends = np.minimum(play[a], play[b])
        low = ends - lipschitz * h / 2
        least = float(np.min(play))
        if least < margin:
            jammed += 1
            split = (low < least - resolution) & (ends < least + 8 * resolution) & (jammed <= JAM_HALVINGS)
        else:
            split = low < margin
        split &= h > narrowest
        bound = float(np.min(low))
        proven = least < margin or bound >= margin
        if not split.any() or len(phi) + int(split.sum()) > budget:
            worst = int(np.argmin(low))
            lower = least if least < margin else min(bound, least)
            cert = Certificate(
                lower=lower,
                positions=len(phi),
                slack=least - lower,
                proven=proven,
                open=(0.0, 0.0) if proven else (float(lo[worst]), float(lo[worst] + h[worst])),
            )
            return phi, play, cert
        mids = (lo[split] + h[split] / 2) % cycle
        phi, play = np.concatenate([phi, mids]), np.concatenate([play, measure(mids)])


def _joined(g: PairGeometry, more: PairGeometry) -> PairGeometry:
    cat = np.concatenate
    return replace(
        g,
        phi1=cat([g.phi1, more.phi1]),
        phi2=cat([g.phi2, more.phi2]),
        r1=cat([g.r1, more.r1]),
        teeth=cat([g.teeth, more.teeth]),
    )
