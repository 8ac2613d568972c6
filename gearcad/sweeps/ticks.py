"""Axis ticks for the sweep's pages: 1, 2 or 5 × 10ᵏ apart, and their labels."""

from __future__ import annotations

import math

__all__ = ["nice_ticks", "tick_label"]


def nice_ticks(lo: float, hi: float, most: int = 7) -> tuple[float, float, list[float], int]:
    """(axis from, axis to, ticks, decimals): ticks 1, 2 or 5 × 10ᵏ apart, at most ``most`` of
    them, the axis widened to whole ticks; decimals enough to tell neighbouring ticks apart."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        lo, hi = 0.0, 1.0
    if hi <= lo:
        pad = max(abs(lo) * 0.01, 0.5) if lo else 0.5
        lo, hi = lo - pad, hi + pad
    raw = (hi - lo) / max(most - 1, 1)
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1, 2, 5, 10) if m * power >= raw * (1 - 1e-9))
    first, last = math.floor(lo / step + 1e-9), math.ceil(hi / step - 1e-9)
    ticks = [k * step for k in range(first, last + 1)]
    decimals = max(0, -math.floor(math.log10(step) + 1e-9))
    return ticks[0], ticks[-1], [0.0 if t == 0 else t for t in ticks], decimals


def tick_label(value: float, decimals: int) -> str:
    """A tick's number with ``decimals`` places (three significant digits where that is too many)."""
    if abs(value) >= 1e6 or decimals > 6:
        return f"{value:.3g}"
    return f"{value:.{decimals}f}"
