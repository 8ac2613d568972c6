"""How many teeth, what module, and where they sit so that the pair meshes.

The perimeter is z·π·m exactly, so a requested module is rounded to the nearest valid tooth
count and then adjusted.  Gear 2's tooth spaces are placed where gear 1's teeth arrive: the
contact carries gear 1's arc length σ to gear 2's s2(π) − σ.  When gear 2 is gear 1 turned by
δ (a self-conjugate pair) the count is also chosen so both gears are the same part: the point
of gear 1 that meets its own apex, at polar angle π + δ, must be a space centre.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import DesignError
from .frame import ArcFrame

__all__ = ["ToothPlan", "plan_teeth", "tooth_count", "COUNT_RANGE"]

COUNT_RANGE = (6, 2000)
"""The tooth counts a profile's teeth.count accepts: what a message may suggest."""


@dataclass(frozen=True)
class ToothPlan:
    teeth: tuple[int, int]
    module: float
    """Module that makes the perimeters exactly z·π·m, mm."""
    requested_module: float | None
    pitch: float
    phases: tuple[float, float]
    """Arc length of tooth space 0 on each gear, mm."""
    identical: bool
    """The two toothed gears are the same part (gear 2 = gear 1 turned)."""


def _space_fractions(frame1: ArcFrame, rotation: float, lobes: int) -> np.ndarray:
    """Where gear 1's point at π + δ falls, as fractions of the perimeter, for δ and every
    rotation by a whole lobe (all of them turn gear 1 onto gear 2)."""
    angles = np.pi + rotation + 2 * np.pi * np.arange(lobes) / lobes
    return frame1.arc(angles) / frame1.perimeter


def _identical_ok(z: int, fractions: np.ndarray) -> bool:
    x = z * fractions - 0.5
    return bool(np.any(np.abs(x - np.round(x)) < 1e-6))


def plan_teeth(
    frame1: ArcFrame,
    frame2: ArcFrame,
    lobes: tuple[int, int],
    *,
    module: float | None = None,
    count: int | None = None,
    identical_rotation: float | None = None,
) -> ToothPlan:
    """Tooth counts, module and phases for a pair; exactly one of ``module``/``count``.

    ``identical_rotation`` is δ when gear 2 is gear 1 turned by δ, else None.
    """
    z1 = tooth_count(frame1, lobes, module=module, count=count, identical_rotation=identical_rotation)
    n1, n2 = lobes
    z2 = z1 * n2 // n1
    pitch = frame1.perimeter / z1
    # gear 1: a tooth centred at φ = 0, so space 0 is half a pitch on
    phase1 = pitch / 2
    # gear 2: a space wherever gear 1's tooth arrives; gear 1's tooth at σ = 0 meets s2(π)
    phase2 = float(frame2.arc(np.array([np.pi]))[0]) % pitch
    return ToothPlan(
        teeth=(z1, z2),
        module=pitch / math.pi,
        requested_module=module,
        pitch=pitch,
        phases=(phase1, phase2),
        identical=identical_rotation is not None,
    )


def tooth_count(
    frame1: ArcFrame,
    lobes: tuple[int, int],
    *,
    module: float | None = None,
    count: int | None = None,
    identical_rotation: float | None = None,
) -> int:
    """Gear 1's tooth count (gear 2 is not needed to choose or refuse it: a refusal comes before
    the mate's arc-length map is built)."""
    n1, n2 = lobes
    step = n1 // math.gcd(n1, n2)  # z1 must be a multiple of this for z2 = z1·n2/n1 to be whole
    fraction = _space_fractions(frame1, identical_rotation, n1) if identical_rotation is not None else None

    def valid(z: int) -> bool:
        return z >= 3 and z % step == 0 and (fraction is None or _identical_ok(z, fraction))

    if count is not None:
        z1 = count
        if z1 % step:
            raise DesignError(
                f"teeth.count = {count}: with {n1}:{n2} lobes the mate gets {count}·{n2}/{n1} teeth; "
                f"the count must be a multiple of {step}"
            )
        if fraction is not None and not _identical_ok(z1, fraction):
            # only counts that teeth.count itself accepts, nearest first
            near = sorted(
                range(max(COUNT_RANGE[0], count - 64), min(COUNT_RANGE[1], count + 64) + 1),
                key=lambda z: (abs(z - count), z),
            )
            options = [z for z in near if valid(z)][:4]
            raise DesignError(
                f"teeth.count = {count}: the two gears are identical, so a tooth must meet a space "
                f"at the apexes, which {count} teeth cannot do; "
                + (
                    f"nearest counts that can: {', '.join(map(str, options))}"
                    if options
                    else "give teeth.module instead"
                )
            )
    else:
        ideal = frame1.perimeter / (math.pi * module)
        candidates = [z for z in range(max(3, int(ideal) - 64), int(ideal) + 66) if valid(z)]
        if not candidates:
            raise DesignError(f"teeth.module = {module:g}: no tooth count near {ideal:.1f} fits this pair")
        z1 = min(candidates, key=lambda z: (abs(z - ideal), z))
    return z1
