"""Helical and herringbone teeth: the transverse sections of a twisted noncircular gear (SPEC §5a).

A helical rack (helix angle β, normal module m_n) rolled without slip along the pitch curve cuts,
in the transverse section at height z, what the straight *transverse* rack cuts when it is
displaced along the pitch curve by the arc length Δs(z) = z·tan β.  A displacement of the rack is
a change of the phase of :func:`~.gear.cut_teeth`, so the section at z is ``cut_teeth(frame, rack,
teeth, phase + hand·Δs(z))``.  The mate's section takes the same shift with the opposite sign in
its own (counter-clockwise) arc length, because the contact carries gear 1's arc length σ to
gear 2's s2(π) − σ: every pair of sections is a planar pair that meshes.  Herringbone:
Δs(z) = min(z, b − z)·tan β, the helix reverses at mid-height.

The transverse rack of a helical rack with normal module m_n and normal pressure angle α_n has
m_t = m_n/cos β and tan α_t = tan α_n/cos β; heights (addendum, dedendum, profile shift) are the
same lengths, so their coefficients × m_t shrink by cos β.  The rack's tip rounding of radius ρ
(normal section) is an ellipse in the transverse section; it is cut as the circle of radius ρ —
the root fillet only, below the working flank, and the root depth is kept.

Sections are spaced from the tolerance (see :func:`section_spacing`) and resampled with the same
number of points between the same tooth-anchored points in every section, so that a loft through
them (``export/loft.py``) is a faithful triangulation of the twisted flank.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from ..errors import DesignError
from ..geometry.outline import Outline
from ..geometry.verify import is_simple
from ..pitch.curve import corners
from ..pitch.pair import PairData
from ..tolerances import Budget
from .correspond import ANCHORS, AnchoredRing, anchor_ring, correspond, mid_section, ring_distance
from .frame import ArcFrame
from .gear import ToothedGear, cut_teeth
from .mesh import MeshData, mesh_check
from .pair import ToothedPairData, with_clearance
from .plan import ToothPlan
from .rack import Rack

__all__ = [
    "SectionSpacing",
    "section_spacing",
    "section_heights",
    "GearSections",
    "HelicalSections",
    "helical_sections",
    "pair_sections",
    "section_mesh",
    "refuse_corners",
]


def refuse_corners(frames: Sequence, names: Sequence[str], helix_angle: float) -> None:
    """One line refusing a helix on a pitch curve with corners: the sections slide along the
    curve, and a rack cannot roll round a corner."""
    for frame, name in zip(frames, names):
        curve = getattr(frame, "curve", None)  # a ParametricFrame is a smooth Fourier series
        found = corners(curve) if curve is not None else []
        if found:
            where = ", ".join(f"{math.degrees(c.phi):.2f}°" for c in found)
            raise DesignError(
                f"teeth.helix_angle_deg = {math.degrees(helix_angle):g}: {name} has corners (at φ = {where}) and "
                "a helical rack cannot roll round a corner; blend the corners (e.g. gear1.blend_width_deg)"
            )


# ----------------------------------------------------------------------------- spacing


@dataclass(frozen=True)
class SectionSpacing:
    """The section spacing h of a twisted gear's loft, and what it comes from.

    A rack point at (a, v) from its pitch point C(σ) generates the gear point
    P(σ) = C + a·T + v·N whatever the phase (the rack is rigidly attached to the rolling frame at
    the contact), so the flank point it generates climbs the twisted flank along
    z ↦ (P(σ0 + z·tan β), z): a material line of the flank.  By Frenet (T' = κN, N' = −κT)
    P' = T + κ(a·N − v·T) and P'' = κ·N + κ'·(a·N − v·T) − κ²·(a·T + v·N), so with
    D = max √(a² + v²) over the rack (its flank's |v|/sin α_t, largest at the tip or at the
    fillet joint) a section point moves sideways by at most λ = h·tan β·V, V = 1 + D·κ_max,
    along a path whose curvature (in the section plane) is at most tan²β·A,
    A = κ_max + D·(κ_max² + κ'_max).

    * ``bound`` — vertex j of every section is the same tooth point (tooth-anchored resampling:
      the pitch points, the root centre and the fillet joints are rack-fixed material points),
      so the loft's vertical edges are chords of material lines and stray by at most
      h²·tan²β·A/8; holding that to the ``budget`` gives h = √(8·budget/(tan²β·A)).
    * ``floor`` — what any correspondence within λ of the material one is held to: a triangle
      then spans at most λ (with the shorter diagonal) of a section of curvature ≤ κ_s and
      strays by at most κ_s·λ²/8 + h²·tan²β·A/8, so h = √(8·budget/(tan²β·(κ_s·V² + A))).

    The bound leaves out the twist of a quad and how far the resampling slips off the material
    lines, so the loft's longest interval is measured against the exactly cut mid-section, and
    h halved (never below the floor) until it is within the tolerance less the fine cut's.
    """

    spacing: float
    """The h used, mm (∞ for β = 0: a straight prism needs only its end sections)."""
    bound: float
    """√(8·budget/(tan²β·A)), mm."""
    floor: float
    """√(8·budget/(tan²β·(κ_s·V² + A))), mm."""
    measured: float
    """Largest distance of the loft's mid-interval section from the exact one, measured on the
    longest interval at ``spacing`` (both gears), mm; NaN where not measured (β = 0, floor)."""
    lateral_speed: float
    """V: sideways motion of a section point per mm of arc-length shift."""
    section_curvature: float
    """κ_s: largest curvature of the toothed section away from its corners, 1/mm."""
    path_curvature: float
    """A: bound on |d²P/dσ²| of a generated point, 1/mm."""
    budget: float
    """Share of the tolerance given to the twist between sections, mm."""


def _pitch_curvature(frame) -> tuple[float, float]:
    """(max |κ|, max |dκ/ds|) of a smooth closed pitch curve, from a dense periodic sample."""
    m = 4096
    s = np.linspace(0.0, frame.perimeter, m, endpoint=False)
    kappa = frame.curvature(s)
    step = frame.perimeter / m
    slope = (np.roll(kappa, -1) - np.roll(kappa, 1)) / (2 * step)
    return float(np.max(np.abs(kappa))), float(np.max(np.abs(slope)))


def _reach(rack: Rack) -> float:
    """D: the farthest a generating point of the rack lies from its pitch point, mm (a flank
    point at height v: |v|/sin α; the fillet's farthest is its joint with the flank; the root
    and the tip land lie straight above or below theirs)."""
    return max(max(rack.v_tip, -rack.v_low) / math.sin(rack.params.pressure_angle), -rack.v_root)


def section_spacing(
    frames: Sequence, racks: Sequence[Rack], *, helix_angle: float, section_curvature: float, budget: float
) -> SectionSpacing:
    """The bound and floor of :class:`SectionSpacing` for a pair (the tighter of its gears);
    ``spacing`` is the bound, ``measured`` NaN."""
    speed, path = 1.0, 0.0
    for frame, rack in zip(frames, racks):
        kappa, slope = _pitch_curvature(frame)
        d = _reach(rack)
        speed = max(speed, 1 + d * kappa)
        path = max(path, kappa + d * (kappa**2 + slope))
    t2 = math.tan(helix_angle) ** 2
    bound = math.sqrt(8 * budget / (t2 * path)) if t2 * path > 0 else math.inf
    spread = t2 * (section_curvature * speed**2 + path)
    floor = math.sqrt(8 * budget / spread) if spread > 0 else math.inf
    return SectionSpacing(bound, bound, floor, math.nan, speed, section_curvature, path, budget)


def section_heights(
    face_width: float, spacing: float, *, herringbone: bool = False, chamfer: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Heights of the sections and the height each one's helix has climbed, (n,) each, mm.

    Every interval between the breaks (0, the chamfer's ends, mid-height for a herringbone, b)
    is split evenly into steps ≤ ``spacing``.  Herringbone levels are mirrored about mid-height,
    so a level and its mirror take bit-identical shifts.
    """
    b = face_width
    if herringbone:
        breaks = sorted({0.0, b / 2, *((chamfer,) if 0 < chamfer < b / 2 else ())})
    else:
        breaks = sorted({0.0, b, *((chamfer, b - chamfer) if 0 < chamfer < b / 2 else ())})
    levels = [0.0]
    for lo, hi in zip(breaks[:-1], breaks[1:]):
        steps = max(1, math.ceil((hi - lo) / spacing - 1e-9)) if math.isfinite(spacing) else 1
        levels += list(lo + (hi - lo) * np.arange(1, steps + 1) / steps)
    lower = np.array(levels)
    if not herringbone:
        return lower, lower.copy()
    upper = b - lower[-2::-1]
    return np.concatenate([lower, upper]), np.concatenate([lower, lower[-2::-1]])


# ----------------------------------------------------------------------------- sections


@dataclass(frozen=True)
class GearSections:
    """One gear's transverse sections, all with the same number of tooth-anchored vertices."""

    heights: np.ndarray
    """(n,) z of each section, mm, from 0 to the face width."""
    shifts: np.ndarray
    """(n,) arc length the rack was displaced by (in this gear's own direction), mm."""
    rings: np.ndarray
    """(n, m, 2) the sections' outer rings, counter-clockwise, vertex j of every section the same
    point of the same tooth; read-only, mm."""
    gears: tuple[ToothedGear, ...]
    """Each section as a toothed gear (its outline the resampled ring) for the planar mesh proof."""
    hand: str
    """"right" (teeth advance counter-clockwise as z rises), "left", "herringbone-right" (right
    in the lower half) or "herringbone-left"."""
    deviation: float
    """Largest distance of a resampled ring from its finely cut section, mm."""
    mid_height: float
    """z halfway up the widest interval between sections (where the twist between them is
    largest), mm: where a loft through them is checked."""
    mid_ring: np.ndarray
    """(p, 2) the section finely cut at ``mid_height`` (counter-clockwise, mm): what a loft
    through the sections should pass within the tolerance of there."""

    def sections(self) -> list[tuple[float, np.ndarray]]:
        """The (z, ring) pairs."""
        return list(zip(self.heights.tolist(), self.rings))


@dataclass(frozen=True)
class HelicalSections:
    gears: tuple[GearSections, GearSections]
    spacing: SectionSpacing
    fine_tolerance: float
    """Tolerance the sections were cut to before resampling, mm."""


def _cutter(frames, plan: ToothPlan, racks, twist, *, clearance: float, fine: float, resample: float):
    """``section(i, climbed)``: gear i's section once its helix has climbed ``climbed`` mm, cut
    and anchored once per shift."""
    hands, tan = twist
    longest = plan.pitch / 8
    cache: list[dict[float, tuple[ToothedGear, AnchoredRing]]] = [{}, {}]

    def section(i: int, climbed: float) -> tuple[ToothedGear, AnchoredRing]:
        key = float(climbed)
        if key not in cache[i]:
            phase = plan.phases[i] + hands[i] * key * tan
            g = with_clearance(cut_teeth(frames[i], racks[i], plan.teeth[i], phase, tolerance=fine), clearance, fine)
            cache[i][key] = (g, anchor_ring(g, frames[i], tolerance=resample, longest=longest))
        return cache[i][key]

    return section


def helical_sections(
    frames: Sequence[ArcFrame],
    plan: ToothPlan,
    racks: Sequence[Rack],
    *,
    helix_angle: float,
    herringbone: bool,
    face_width: float,
    tolerance: float,
    clearance: float = 0.0,
    chamfer: float = 0.0,
    names: Sequence[str] = ("gear1", "gear2"),
    spacing: float | None = None,
    check_work: Callable[[int, int], None] | None = None,
) -> HelicalSections:
    """The transverse sections of both gears of a pair, for a loft within ``tolerance``.

    ``frames``, ``plan`` and ``racks`` are the planar pair's (``ToothedPairData.frames``,
    ``.plan`` and each gear's ``.rack``, cut with :func:`~.helix.transverse_teeth`); ``helix_angle`` is β
    in rad (gear 1 right-handed, its mate left-handed; β < 0 swaps the hands); ``clearance``
    offsets every section inwards as ``cut_pair`` does.  Sections are cut at
    a quarter of the tolerance, resampled to within another quarter, and spaced so that the twist
    between them costs at most the other half (:class:`SectionSpacing`); ``spacing`` (mm)
    overrides that choice, for studies of it; ``check_work(levels, points)`` may refuse them uncut.
    """
    refuse_corners(frames, names, helix_angle)
    if face_width <= 0:
        raise DesignError(f"output.thickness = {face_width:g}: the face width must be > 0")
    fine = resample = Budget(tolerance).fine
    budget = tolerance - fine - resample
    hands = (1.0, -1.0)
    tan = math.tan(helix_angle)
    section = _cutter(frames, plan, racks, (hands, tan), clearance=clearance, fine=fine, resample=resample)
    kappa = max(section(i, 0.0)[1].smooth_curvature for i in range(2))
    bound = section_spacing(frames, racks, helix_angle=helix_angle, section_curvature=kappa, budget=budget)
    h = bound.bound if spacing is None else spacing
    measured = math.nan
    while True:
        heights, climbed = section_heights(face_width, h, herringbone=herringbone, chamfer=chamfer)
        if check_work is not None:
            check_work(len(heights), max(len(section(i, 0.0)[1].ring) for i in range(2)))
        if spacing is not None or not math.isfinite(h) or h <= bound.floor:
            break
        k = int(np.argmax(np.diff(heights)))
        measured = max(_interval_deviation(section, i, climbed[k], climbed[k + 1], resample) for i in range(2))
        if measured <= tolerance - fine:
            break
        h, measured = max(h / 2, bound.floor), math.nan
    chosen = replace(bound, spacing=h, measured=measured)
    twist = hands, tan, herringbone, names, resample
    out = [_gear_sections(section, i, heights, climbed, plan, twist) for i in range(2)]
    return HelicalSections((out[0], out[1]), chosen, fine)


def _gear_sections(section, i: int, heights, climbed, plan: ToothPlan, twist) -> GearSections:
    """Gear i's sections at every height: its distinct levels cut (a herringbone's repeat),
    their rings made to correspond vertex by vertex, each checked simple."""
    hands, tan, herringbone, names, resample = twist
    distinct, back = np.unique(climbed, return_inverse=True)  # herringbone levels repeat
    cut_list = [section(i, c) for c in distinct]
    counts, rings, deviation = correspond([a for _, a in cut_list], resample)
    roots = (np.cumsum(counts) - counts)[2::ANCHORS]
    gears = []
    for (g, _), ring, c in zip(cut_list, rings, distinct):
        if not is_simple(ring):
            raise DesignError(f"{names[i]}: a helical section crosses itself at this tolerance; use a smaller one")
        phase = plan.phases[i] + hands[i] * float(c) * tan
        gears.append(replace(g, outline=Outline((ring,)), space_root=roots, phase=phase))
    stack = np.stack([rings[k] for k in back])
    k = int(np.argmax(np.diff(heights)))
    mid = section(i, 0.5 * (climbed[k] + climbed[k + 1]))[0].outline.rings[0]
    stack.flags.writeable = False
    hand = ("right", "left")[i]
    return GearSections(
        heights=heights,
        shifts=hands[i] * climbed * tan,
        rings=stack,
        gears=tuple(gears[k] for k in back),
        hand=f"herringbone-{hand}" if herringbone else hand,
        deviation=deviation,
        mid_height=0.5 * float(heights[k] + heights[k + 1]),
        mid_ring=mid,
    )


def _interval_deviation(section, i: int, low: float, high: float, resample: float) -> float:
    """How far the loft between gear i's sections at climbs ``low`` and ``high`` strays, at
    mid-interval, from the section cut there: mm."""
    _, (lower, upper), _ = correspond([section(i, low)[1], section(i, high)[1]], resample)
    exact = section(i, 0.5 * (low + high))[1].ring
    return ring_distance(mid_section(lower, upper), exact)


def pair_sections(teeth: ToothedPairData, **options) -> HelicalSections:
    """:func:`helical_sections` for a pair cut by ``cut_pair`` (with :func:`~.helix.transverse_teeth`);
    ``options`` are its keyword arguments (``helix_angle``, ``herringbone``, ``face_width``, …)."""
    return helical_sections(teeth.frames, teeth.plan, tuple(g.rack for g in teeth.gears), **options)


def section_mesh(
    pair: PairData,
    sections: HelicalSections,
    frames: Sequence[ArcFrame],
    *,
    tolerance: float,
    play: float = 0.0,
    levels: Sequence[int] | None = None,
) -> tuple[tuple[float, MeshData], ...]:
    """The planar mesh proof (:func:`~.mesh.mesh_check`) on the pair's sections at ``levels``
    (default: bottom, middle, top): ((z, MeshData), …)."""
    g1, g2 = sections.gears
    n = len(g1.heights)
    chosen = sorted(set(levels if levels is not None else (0, n // 2, n - 1)))
    return tuple(
        (
            float(g1.heights[k]),
            mesh_check(pair, (g1.gears[k], g2.gears[k]), tuple(frames), tolerance=tolerance, play=play),
        )
        for k in chosen
    )
