"""The numerical tolerances of gearcad, each with the reason for its value."""

import math
from dataclasses import dataclass

__all__ = ["Tolerances", "DEFAULT", "Budget", "budget", "designed_play", "WORKING_DEPTH"]


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


WORKING_DEPTH = 2.25
"""A tooth's working depth in modules (addendum 1 + dedendum 1.25): the stretch of a flank that
two meshing outlines share."""

NUDGE_PER_TOLERANCE = 200.0
"""The nudged mesh test turns the mate by this many tolerances of arc beyond its play: the
overlap it then makes, about (200·tol)·2.25·m, dwarfs the allowance 2·tol·2.25·m (~0.44·δ/tol
times it), so a pass is no accident of round-off."""

NUDGE_CAP_MODULES = 0.5
"""…capped at half a module, well under a pitch (π·m), so that on a coarse tolerance the turn
never carries a tooth past a space into the next one."""


@dataclass(frozen=True)
class Budget:
    """Every rule derived from one design's ``output.tolerance`` (mm), made once per design
    (:func:`budget`) and passed down: how finely outlines are cut, how far a written path may
    stray from them, and how much the assembled parts may overlap.  The reasons are in the
    :class:`Tolerances` fields and the constants above."""

    tolerance: float
    """output.tolerance, mm: the largest distance of a written outline from the exact curve."""
    fine_fraction: float = DEFAULT.fine_fraction

    @property
    def fine(self) -> float:
        """The tolerance outlines are cut at (mm): ``tolerance × fine_fraction``."""
        return self.tolerance * self.fine_fraction

    @property
    def fit(self) -> float:
        """What a path fitted to the fine outline (arcs, chords, a thinned ring) may stray by,
        mm: the rest of the tolerance, ``tolerance − fine``."""
        return self.tolerance - self.fine

    def allowed_overlap(self, length: float) -> float:
        """The overlap (mm²) two outlines in contact may show as assembled: each may stray by the
        tolerance along ``length`` mm of the contact (for teeth, their working depth
        ``WORKING_DEPTH · m``), so 2·tol·length."""
        return 2 * self.tolerance * length

    def teeth_overlap(self, module: float) -> float:
        """:meth:`allowed_overlap` of meshing teeth of ``module``: 2·tol·2.25·m."""
        return self.allowed_overlap(WORKING_DEPTH * module)

    @property
    def allowed_depth(self) -> float:
        """How deep (mm) two outlines in contact may penetrate each other as written: each may
        stray by the tolerance towards the other, so 2·tol.  An area bound alone lets a long thin
        sliver through (the walker's 16.6 µm bite had 0.0013 mm²); depth is what binds."""
        return 2 * self.tolerance

    def nudge_arc(self, *, module: float, play: float = 0.0) -> float:
        """How far (arc at the contact, mm) the mate is turned for the nudged test: beyond the
        designed ``play`` by ``NUDGE_PER_TOLERANCE`` tolerances, capped at
        ``NUDGE_CAP_MODULES`` modules: play + min(200·tol, 0.5·m)."""
        return play + min(NUDGE_PER_TOLERANCE * self.tolerance, NUDGE_CAP_MODULES * module)


def budget(tolerance: float) -> Budget:
    """The budget of a design cut at ``tolerance`` mm (the profile's output.tolerance)."""
    return Budget(tolerance)


def designed_play(*, backlash: float, clearance: float, pressure_angle: float) -> float:
    """The free turn (arc at the contact, mm) a pair is cut with: its backlash, and the flank
    clearance taken off both flanks of both gears, 4·c / cos α along the pitch curve."""
    return backlash + 4 * clearance / math.cos(pressure_angle)
