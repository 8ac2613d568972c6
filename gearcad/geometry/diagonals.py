"""How a loft splits the quads between two corresponding rings (moved whole from
teeth/correspond.py, which re-exports it: the loft, an exporter, reads only geometry)."""

from __future__ import annotations

import numpy as np

__all__ = ["rising_diagonals"]


def rising_diagonals(lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """(m,) bool: for each quad lower[j], lower[j+1], upper[j+1], upper[j] of two corresponding
    rings, whether lower[j]–upper[j+1] is its shorter diagonal (ties: yes).  The loft splits
    each quad along it, so that a triangle spans the larger of the chord and the twist's step."""
    nxt = np.roll(np.arange(len(lower)), -1)
    rising = np.sum((upper[nxt] - lower) ** 2, axis=1)
    falling = np.sum((upper - lower[nxt]) ** 2, axis=1)
    return rising <= falling
