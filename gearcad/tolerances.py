"""The numerical tolerances of gearcad, each with the reason for its value."""

from dataclasses import dataclass

__all__ = ["Tolerances", "DEFAULT"]


@dataclass(frozen=True)
class Tolerances:
    """Tolerances used across the pipeline (keyword arguments, never positional)."""

    outline_mm: float = 0.001
    """Largest distance of a written outline from the exact curve, mm.  A laser kerf is
    ~0.1 mm and a printer's nozzle ~0.4 mm, so 1 µm is invisible to both."""

    fit_rel: float = 1e-14
    """Chebyshev fits stop when the tail coefficients fall below this fraction of the
    largest one: a few units of double-precision round-off."""

    closure_rad: float = 1e-11
    """A pair counts as closed when the mate's turn misses its target by less than this.
    The root finder reaches ~1e-14; 1e-11 leaves room for long chains of evaluation."""

    rolling_mm: float = 1e-9
    """Largest contact / slip residual of a pair that rolls, mm (or mm per rad)."""

    corner_rad: float = 1e-6
    """A jump of the tangent direction larger than this at a seam is a corner."""

    fine_fraction: float = 0.25
    """Outlines are cut at this fraction of ``outline_mm``; DXF arcs fitted to them, and the
    chords of the thinned outline used for meshes, may stray by the rest of the tolerance."""

    convex_rel: float = 1e-12
    """Convexity is judged on r² + 2r'² − r·r'' relative to r²: round-off allowance."""


DEFAULT = Tolerances()
