"""The least measured play pinned down (docs/fit.md, "The least pinned down"): once a proof
(:mod:`.prove`) has settled the verdict, the play it measured is followed down from its lowest
local minima by golden sections, so that the least reported is the least the outlines have there,
not the least at the positions the proof happened to measure."""

from __future__ import annotations

import numpy as np

from ..roots import golden_sections
from .prove import PAIRS, Measures

__all__ = ["pinned"]


PINNED = 4
"""Once the margin is proven, the play measured is followed down from this many of its lowest
local minima within :data:`PIN_NEAR` of the least (golden sections between each one's
neighbours, to :data:`PIN_WIDTH` of a radian):
the least measured then is the least the outlines have there, not the least at the positions
the proof happened to measure (issue 33: the report within 1 µm of the written files)."""
PIN_WIDTH = 1e-6
PIN_STEPS = 24
"""At most this many golden steps (a bracket 0.618²⁴ ≈ 1e-5 of its first width)."""
PIN_NEAR = 0.004


def pinned(g, measured: np.ndarray, offsets, spread: float, tol: float, reach: float, measures: Measures = PAIRS):
    """The play measured by golden sections about the :data:`PINNED` lowest local minima of
    ``measured`` (the play at ``g``'s positions, as :func:`~.prove.prove_play` gives them), each between
    its neighbours: (the geometry at every position so measured, the play there)."""
    order = np.argsort(g.phi1 % g.cycle)
    phi, measured = g.phi1[order] % g.cycle, measured[order]
    how = (offsets, spread, tol, reach)
    low = np.flatnonzero(
        (measured <= np.roll(measured, 1))
        & (measured <= np.roll(measured, -1))
        & (measured <= float(np.min(measured)) + PIN_NEAR)
    )
    low = low[np.argsort(measured[low])][:PINNED]
    lo = phi[low] - (phi[low] - np.roll(phi, 1)[low]) % g.cycle
    hi = phi[low] + (np.roll(phi, -1)[low] - phi[low]) % g.cycle
    xs, fs = [], []

    def measure(x: np.ndarray) -> np.ndarray:
        sub = g.at(x % g.cycle)
        f = measures.signed(sub, *how)
        xs.append(sub)
        fs.append(f)
        return f

    golden_sections(measure, lo, hi, PIN_STEPS, lambda lo, hi, fa, fb: float(np.max(hi - lo)) <= PIN_WIDTH)
    return measures.joined(xs), np.concatenate(fs)
