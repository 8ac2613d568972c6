"""Polar samples of the wheel-walker's pitch curves for a chart: the paper's (eqs. 10 and 12,
θ = 4φ) and a pair's, both as ``{wheel_phi, wheel_r, pinion_theta, pinion_r, L}`` with θ
measured on the pinion from the direction pointing at the wheel (its paper convention)."""

from __future__ import annotations

import numpy as np

from .curve import TWO_PI
from .pair import PairData
from .walker import WalkerGeometry, paper_pinion_radius, paper_wheel_radius

__all__ = ["paper_polar", "pair_polar"]


def paper_polar(g: WalkerGeometry, i: float, *, samples: int = 721) -> dict:
    """The paper's wheel (four copies of eq. 10's quarter) and pinion (eq. 12), mm and rad."""
    phi = np.linspace(0.0, TWO_PI, samples)
    quarter = (phi + np.pi / 4) % (np.pi / 2) - np.pi / 4
    theta = np.linspace(-np.pi, np.pi, samples)
    return {
        "wheel_phi": phi.tolist(),
        "wheel_r": paper_wheel_radius(quarter, i, g).tolist(),
        "pinion_theta": theta.tolist(),
        "pinion_r": paper_pinion_radius(theta, i, g).tolist(),
        "L": g.L,
    }


def pair_polar(pair: PairData, *, samples: int = 721) -> dict:
    """A gearcad pair (gear 1 the wheel, gear 2 the pinion in gearcad's mate convention, whose
    body angle ψ = π faces the wheel at the start): the same keys, θ = π − ψ."""
    phi = np.linspace(0.0, TWO_PI, samples)
    return {
        "wheel_phi": phi.tolist(),
        "wheel_r": pair.gear1.r(phi).tolist(),
        "pinion_theta": (np.pi - phi).tolist(),
        "pinion_r": pair.gear2.r(phi).tolist(),
        "L": pair.center_distance,
    }
