"""Bounded work: estimate the outline points a design needs before cutting it, and refuse one
that would exceed the budget, naming the keys to change.

A tooth's flanks, fillets and tip are sampled so that chords sag at most the fine tolerance
(a quarter of ``output.tolerance``); their curvature scales with the module, so a tooth takes
about ``POINTS_PER_TOOTH · √(m / fine tolerance)`` points (measured on the example profiles at
0.01–0.0001 mm: 1.3–1.7).  A design takes about 40 µs per point, so the budget keeps one
design under ~25 s and well under 1 GB on the 2-core reference machine.
"""

from __future__ import annotations

import math

from ..errors import DesignError
from ..tolerances import budget

__all__ = [
    "check_backlash",
    "POINT_BUDGET",
    "FINEST_TOLERANCE",
    "COARSEST_TOLERANCE",
    "teeth_points",
    "check_teeth_work",
    "check_outline_work",
    "SECTION_POINT_BUDGET",
    "check_section_work",
    "MAX_SAMPLE_ORDER",
    "MAX_SAMPLE_WORK",
    "SAMPLE_NOISE",
]

POINT_BUDGET = 600_000
"""Outline points (fine cut, every gear of a design) one build may need."""
POINTS_PER_TOOTH = 2.0
"""Points per tooth per √(module / fine tolerance): above the largest seen on the profiles."""
MAX_TEETH = 5000
"""Most teeth on one gear: beyond the points, each tooth space costs time of its own (its pieces
joined and its loops cut), so 5000 teeth took ~25 s on the reference machine when the loops were
removed one space at a time (measured on roller bodies: 5032 teeth 24 s, 8050 teeth 36 s,
40 252 teeth over 120 s); all spaces' loops are now found with one R-tree."""
FINEST_TOLERANCE = 1e-4
"""The smallest output.tolerance a profile accepts, mm: never suggest a finer one."""
COARSEST_TOLERANCE = 0.5
"""The largest output.tolerance a profile accepts, mm: never suggest a coarser one."""
MODULE_PER_TOLERANCE = 4.0
"""Smallest module per output.tolerance: a flank 2.25·m deep drawn within a tolerance of more
than a quarter module is no flank (on the spur pair the mesh proof fails below ~3)."""


def teeth_points(teeth: int, module: float, tolerance: float) -> float:
    """About how many points the fine cut of ``teeth`` teeth of ``module`` takes (mm)."""
    return POINTS_PER_TOOTH * teeth * math.sqrt(module / budget(tolerance).fine)


def check_teeth_work(
    gears: list[tuple[int, float]], tolerance: float, *, keys: str = "teeth.module / teeth.count"
) -> None:
    """Refuse gears ((teeth, module) each) whose teeth the tolerance cannot draw, or whose cut
    would take more than the point budget; ``keys`` name what sizes the teeth in the profile."""
    most = max(z for z, _ in gears)
    if most > MAX_TEETH:
        raise DesignError(
            f"a gear would carry {most:.0f} teeth (at most {MAX_TEETH}); use fewer or larger teeth ({keys})"
        )
    smallest = min(m for _, m in gears)
    if smallest < MODULE_PER_TOLERANCE * tolerance:
        finer = smallest / MODULE_PER_TOLERANCE
        raise DesignError(
            f"output.tolerance = {tolerance:g}: teeth of module {smallest:.4g} mm cannot be drawn within it; use "
            + (f"output.tolerance ≤ {finer:.2g} mm, or " if finer >= FINEST_TOLERANCE else "")
            + f"larger teeth ({keys})"
        )
    need = sum(teeth_points(z, m, tolerance) for z, m in gears)
    if need <= POINT_BUDGET:
        return
    # points grow as tolerance^−½: the coarsest tolerance that fits
    fits = 1.05 * tolerance * (need / POINT_BUDGET) ** 2
    teeth = round(sum(z for z, _ in gears))
    raise DesignError(
        f"output.tolerance = {tolerance:g}: {teeth} teeth of module {max(m for _, m in gears):.4g} mm would need "
        f"about {need / 1e6:.1f} million outline points (the budget is {POINT_BUDGET / 1e6:.1f} million); use "
        f"output.tolerance ≥ {fits:.2g} mm, or fewer or smaller teeth ({keys})"
    )


def check_outline_work(length: float, min_radius: float, tolerance: float, *, what: str) -> None:
    """Refuse a plain outline of ``length`` mm whose tightest bend (radius mm) would take more
    than the point budget to sample within the fine tolerance (chord sag ≈ ds²/8ρ)."""
    step = math.sqrt(8 * budget(tolerance).fine * max(min_radius, 1e-9))
    need = length / step
    if need > POINT_BUDGET:
        raise DesignError(
            f"output.tolerance = {tolerance:g}: {what} would need about {need / 1e6:.1f} million outline points "
            f"(the budget is {POINT_BUDGET / 1e6:.1f} million); use a coarser output.tolerance"
        )


SECTION_POINT_BUDGET = 2 * POINT_BUDGET
"""Points of a helical pair's transverse sections (both gears, every level): each costs about
what a planar outline point does to cut and to loft (a herringbone of thickness 100 mm, β 25°,
0.01 mm: 0.41 million in ~4 s), and two triangles in each gear's STL (1.2 million: ~60 MB)."""


def check_section_work(levels: int, points: int, *, thickness: float, helix_angle: float) -> None:
    """Refuse helical sections — ``levels`` of up to ``points`` points, both gears — beyond
    :data:`SECTION_POINT_BUDGET`: their count grows with the twist, thickness·tan β."""
    need = 2.0 * levels * points
    if need <= SECTION_POINT_BUDGET:
        return
    fits = thickness * SECTION_POINT_BUDGET / need
    raise DesignError(
        f"output.thickness = {thickness:g}: the teeth twist {thickness * math.tan(helix_angle):.4g} mm along "
        f"the face (thickness·tan β), {levels} sections of {points} points: about {need / 1e6:.1f} million "
        f"points (the budget is {SECTION_POINT_BUDGET / 1e6:.1f} million); use output.thickness ≤ {fits:.3g} mm, "
        "a smaller teeth.helix_angle_deg or a coarser output.tolerance"
    )


MAX_SAMPLE_ORDER = 360
"""Highest harmonic order a pitch curve given by radii may hold above its noise: the cut's time
grows with it (about 10 s at 360 on the reference machine), and a wave finer than a degree of
turn is finer than any tooth."""

MAX_SAMPLE_WORK = 120 * 120
"""Most (top order + 1) × (orders held) of a pitch curve given by radii: a curve's evaluations
cost one step per order held and the pieces its fits need grow with the top order, so its pitch
stage grows as their product (0.3 mm of noise in 720 radii: order 360, every order held, 40 s of
pitch stage alone; cut at order 120: about 4 s)."""

SAMPLE_NOISE = 0.1
"""The smallest orders of sampled radii are dropped as noise while together they move the curve
by at most this fraction of the output tolerance."""


def check_backlash(backlash: float, module: float, key: str) -> None:
    """Refuse a backlash that would thin every tooth (``module`` mm, the smallest) to under half
    its thickness, as a pair's ``teeth.backlash`` is refused."""
    if backlash >= math.pi * module / 2:
        raise DesignError(
            f"{key} = {backlash:g}: it would thin every tooth to under half its thickness; "
            f"the largest backlash module {module:.4g} takes is {math.pi * module / 2:.3f} mm"
        )
