"""The backlash band of a mesh: its play as drawn and over the process's tolerance stack.

The made parts differ from the drawn ones by an edge offset δ (the kerf's variation, a printer's
XY error and elephant foot) and sit at a centre distance off by ±Δa (with the bores' play).  The
play is measured from the geometry: both outlines offset by δ (shapely's buffer), gear 2 placed
at E + Δa, and at each driver position gear 2 turned each way until it touches gear 1 (found
exactly, :mod:`~..geometry.sweep`); the two free turns times the contact radius add up to the
play, mm on the pitch curve.  The smallest play comes with both parts large and the centres
close, the largest with both small and the centres apart.  Where the worst case overlaps already (it jams), the play is
negative: the parts are shrunk until they come free, and the shrink ε counts −4ε/cos α (a
rack-cut flank moved ε along its normal moves 1/cos α along the pitch curve; four flanks).
Only a window of each gear around the contact (three modules) is offset and intersected.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..threads import side_by_side
from .certify import Certificate, certify_play
from .pin import pinned
from .play import PairGeometry, play_between, signed_play
from .prove import prove_lazily, prove_play

__all__ = ["Band", "band_of", "pair_band"]


@dataclass(frozen=True)
class Band:
    """Play of a mesh (mm on the pitch curve): as drawn over one cycle, and over the tolerance
    stack, with where the smallest falls and what change would free it."""

    mesh: str
    nominal: tuple[float, float]
    band: tuple[float, float]
    worst_tooth: int
    worst_phi: float
    edge: tuple[float, float, float]
    center_spread: float
    needed_backlash: float
    """Backlash to add so that the worst case keeps the margin free (0 when it does)."""
    margin: float
    pressure_angle: float
    certificate: Certificate | None = None
    """How the least play was bounded between positions (estimated or proven: its ``kind``; None:
    measured at the positions only)."""
    gear1_phi: float | None = None
    """Gear 1's turn at the least play (rad) where the driver is gear 2 (``worst_phi`` is the driver's)."""
    mate_phi: float | None = None
    """Gear 2's turn at the least play (rad), as the band measured it."""
    pin: Callable[[], Band] | None = field(default=None, compare=False, repr=False)
    """The same band with its least measured play followed down from the lowest minima between
    positions (:func:`~.pin.pinned`): what a search for the backlash skips, and the design it
    chooses reports (:meth:`pinned`)."""

    def pinned(self) -> Band:
        """This band with its least pinned down (:attr:`pin`), else itself."""
        return self if self.pin is None else self.pin()

    @property
    def least(self) -> float:
        """The least play the verdict rests on (mm): the certified one where there is a certificate."""
        return self.band[0] if self.certificate is None else min(self.band[0], self.certificate.lower)

    @property
    def fits(self) -> bool:
        return self.least >= self.margin

    @property
    def unproven(self) -> bool:
        """Whether the work budget ran out before the bound settled the verdict."""
        return self.certificate is not None and not self.certificate.proven

    def as_dict(self) -> dict:
        return {
            "mesh": self.mesh,
            "nominal_min": self.nominal[0],
            "nominal_max": self.nominal[1],
            "min": self.band[0],
            "max": self.band[1],
            "worst_tooth": self.worst_tooth,
            "worst_phi": self.worst_phi,
            "worst_phi1": self.worst_phi if self.gear1_phi is None else self.gear1_phi,
            "edge": {"nominal": self.edge[0], "min": self.edge[1], "max": self.edge[2]},
            "center_distance_spread": self.center_spread,
            "verdict": "fits" if self.fits else "jams",
            "needed_backlash": self.needed_backlash,
            "center_distance_change": self.needed_backlash / (2 * math.tan(self.pressure_angle)),
            **({} if self.certificate is None else self.certificate.as_dict()),
        }


def pair_band(
    g: PairGeometry,
    *,
    edge: tuple[float, float, float],
    spread: float,
    tol: float,
    backlash: float,
    name: str = "pair",
    internal: bool = False,
    certificate: str = "estimate",
    pin: bool = False,
) -> Band:
    """The band of one pair under an edge offset (nominal, smallest, largest; mm) and ±``spread``
    of centre distance (closer centres take play from an external mesh, farther from an internal
    one); ``tol`` the outline tolerance (the worst case must keep twice it free), ``backlash``
    the designed play (bounds the search with the stack), ``certificate`` how the tight case's
    least play is bounded between positions (``output.certificate``: "estimate", the slopes'
    :func:`~.certify.certify_play`, or "theorem", :func:`~.prove.prove_play`), ``pin``: the band
    keeps how to pin its least down (:attr:`Band.pin`; a closure, so the band no longer pickles
    until :meth:`Band.pinned` is called)."""
    closer = spread if internal else -spread
    alpha = g.pressure_angle
    reach = backlash + 4 * max(abs(e) for e in edge) / math.cos(alpha) + 2 * spread * math.tan(alpha) + 0.5 * g.module
    margin = _margin(edge, spread, tol, alpha)
    certify = g.at is not None and g.ratio is not None
    grown = [(e - g.cut, e - g.cut) for e in edge]  # the rings grown so (cut paths: less the cutter)
    lazy = pin and certificate == "theorem" and margin >= 0  # the least pinned down only when asked
    bounded = prove_lazily if lazy else prove_play if certificate == "theorem" else certify_play
    if edge[0] == edge[1] == edge[2] and not spread:  # no stack (no process): one case, not three alike
        if certify:
            found = bounded(g, grown[0], 0.0, tol, reach=reach, margin=margin)
            return _certified(name, found, None, None, grown[0], 0.0, edge, spread, tol, reach, alpha, pin, lazy)
        nominal = tight = wide = signed_play(g, grown[0], 0.0, tol, reach=reach)
    else:
        with side_by_side() as pool:  # GEOS releases the GIL: the cases side by side
            if certify:
                tight_job = pool.submit(bounded, g, grown[2], closer, tol, reach=reach, margin=margin)
            else:
                tight_job = pool.submit(signed_play, g, grown[2], closer, tol, reach=reach)
            jobs = [
                pool.submit(play_between, g, grown[0], 0.0, tol, reach=reach),
                tight_job,
                pool.submit(play_between, g, grown[1], -closer, tol, reach=reach),
            ]
            (nominal, _), tight, (wide, _) = (job.result() for job in jobs)
        if certify:
            return _certified(name, tight, nominal, wide, grown[2], closer, edge, spread, tol, reach, alpha, pin, lazy)
    return band_of(
        name, (nominal, tight, wide), g.teeth, g.phi1, edge=edge, spread=spread, tol=tol, alpha=alpha, phi2=g.phi2
    )


def _certified(name, found, nominal, wide, offsets, spread_at, edge, spread, tol, reach, alpha, pin, lazy) -> Band:
    """The band of a certified tight case ``found`` (``lazy``: (found, finish), :func:`~.prove.prove_lazily`:
    its least pinned down, and pinned, only by :meth:`Band.pinned`); ``offsets``, ``spread_at``: how the
    tight case was measured."""
    finish = found[1] if lazy else None
    found = found[0] if lazy else found

    def band_of_(tight) -> Band:
        return _band_certified(name, tight, nominal, wide, edge=edge, spread=spread, tol=tol, alpha=alpha)

    band = band_of_(found)
    if not pin:
        return band
    if finish is None:
        return _pinnable(band, found, offsets, spread_at, tol, reach)

    def pin_() -> Band:
        done = finish()
        return _pinnable(band_of_(done), done, offsets, spread_at, tol, reach).pinned()

    return replace(band, pin=pin_)


def _pinnable(band: Band, found, offsets, spread: float, tol: float, reach: float) -> Band:
    """``band`` with its :attr:`~Band.pin`: where its tight case is proven to keep the margin,
    the golden sections of :func:`~.pin.pinned` about its lowest minima, the least, where it
    falls, and the positions and slack of the certificate taken from them where lower."""
    g, tight, cert = found
    if cert is None or cert.kind != "theorem" or not cert.proven or band.margin < 0 or band.band[0] < band.margin:
        return band  # (exact parts that may bite: their jams cost a bisection each, the slack pins them)

    def pin() -> Band:
        sub, play = pinned(g, tight, offsets, spread, tol, reach)
        cert2 = replace(cert, positions=cert.positions + len(play))
        k = int(np.argmin(play)) if len(play) else -1
        if k < 0 or play[k] >= band.band[0]:
            return replace(band, certificate=cert2, pin=None)
        low = float(play[k])
        return replace(
            band,
            band=(low, band.band[1]),
            worst_tooth=int(sub.teeth[k]),
            worst_phi=float(sub.phi1[k] % g.cycle),
            mate_phi=float(sub.phi2[k]),
            certificate=replace(cert2, slack=low - cert.lower),
            pin=None,
        )

    return replace(band, pin=pin)


def _margin(edge, spread: float, tol: float, alpha: float) -> float:
    """The play the worst case must keep (mm): made parts twice the writing tolerance; exact parts
    (no process) may bite by what the writing tolerance takes from four flanks, which the mesh
    proof allows."""
    return 2 * tol if any(edge) or spread else -4 * tol / math.cos(alpha)


def _band_certified(name, found, nominal, wide, *, edge, spread, tol, alpha) -> Band:
    """The band from the certified tight case ``found`` (:func:`~.certify.certify_play` or
    :func:`~.prove.prove_play`) and the nominal and wide
    plays at the first positions (None: no stack, the tight case is all three)."""
    g, tight, cert = found
    if nominal is None:
        cases = (tight, tight, tight)
    else:
        # the tight case was measured at the first positions and those refined; the others at the first
        more = np.full(len(tight) - len(nominal), np.nan)
        cases = (np.concatenate([nominal, more]), tight, np.concatenate([wide, more]))
    return band_of(
        name, cases, g.teeth, g.phi1, edge=edge, spread=spread, tol=tol, alpha=alpha, certificate=cert, phi2=g.phi2
    )


def band_of(
    name: str, plays, teeth, phi1, *, edge, spread: float, tol: float, alpha: float, certificate=None, phi2=None
) -> Band:
    """The :class:`Band` of one mesh from its plays over the cycle (nominal, tight, wide: mm per
    position, the tight one signed), the tooth and driver angle of each position, its edge
    offsets and centre spread (mm), the outline tolerance and the pressure angle (rad)."""
    nominal, tight, wide = plays
    worst = int(np.nanargmin(tight))
    margin = _margin(edge, spread, tol, alpha)
    low = float(tight[worst])
    least = low if certificate is None else min(low, certificate.lower)
    return Band(
        mesh=name,
        nominal=_span(nominal, tight),
        band=(low, _span(wide, tight)[1]),
        worst_tooth=int(teeth[worst]),
        worst_phi=float(phi1[worst]),
        edge=edge,
        center_spread=spread,
        needed_backlash=max(0.0, margin - least),
        margin=margin,
        pressure_angle=alpha,
        certificate=certificate,
        mate_phi=None if phi2 is None else float(phi2[worst]),
    )


def _span(play: np.ndarray, signed: np.ndarray) -> tuple[float, float]:
    """(smallest, largest) of a play over the cycle; where it jams everywhere (all NaN), the
    signed play's (negative: the shrink that frees it)."""
    values = signed if np.isnan(play).all() else play
    return float(np.nanmin(values)), float(np.nanmax(values))
