"""The helical rack seen in the transverse plane, and what the report says of a helical toothing.

A helical rack with normal module m_n and normal pressure angle α_n cuts, in the transverse
section, what the straight rack with m_t = m_n/cos β and tan α_t = tan α_n/cos β cuts; heights
(addendum, dedendum, profile shift) are the same lengths, so their coefficients × m_t shrink by
cos β.  The sections themselves are in :mod:`.helical`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import DesignError
from .pair import ToothSpec

__all__ = ["TransverseTeeth", "transverse_teeth", "HelixData", "helix_data"]


@dataclass(frozen=True)
class TransverseTeeth:
    """A :class:`~.pair.ToothSpec` seen in the transverse section: what ``cut_pair`` cuts at z = 0
    for a helical rack (module, pressure angle and coefficients all transverse)."""

    module: float | None
    count: int | None
    pressure_angle: float
    addendum: float
    dedendum: float
    tip_radius: float
    profile_shift: float
    backlash: float
    clearance: float


def transverse_teeth(teeth: ToothSpec, helix_angle: float) -> TransverseTeeth:
    """The transverse rack of a helical rack whose normal section is ``teeth`` (β in rad).

    >>> t = transverse_teeth(TransverseTeeth(1.0, None, math.radians(20), 1.0, 1.25, 0.38, 0.0, 0.0, 0.0),
    ...                      math.radians(30))
    >>> round(t.module, 6), round(math.degrees(t.pressure_angle), 4), round(t.addendum * t.module, 12)
    (1.154701, 22.7959, 1.0)
    """
    if not 0.0 <= helix_angle < math.pi / 2:
        raise DesignError(f"teeth.helix_angle_deg = {math.degrees(helix_angle):g}: must be ≥ 0 and under 90")
    c = math.cos(helix_angle)
    return TransverseTeeth(
        module=None if teeth.module is None else teeth.module / c,
        count=teeth.count,
        pressure_angle=math.atan(math.tan(teeth.pressure_angle) / c),
        addendum=teeth.addendum * c,
        dedendum=teeth.dedendum * c,
        tip_radius=teeth.tip_radius * c,
        profile_shift=teeth.profile_shift * c,
        backlash=teeth.backlash,
        clearance=teeth.clearance,
    )


@dataclass(frozen=True)
class HelixData:
    """What the report says of a helical toothing (mm, rad)."""

    helix_angle: float
    herringbone: bool
    normal_module: float
    transverse_module: float
    normal_pressure_angle: float
    transverse_pressure_angle: float
    axial_pitch: float
    """π·m_n / sin β: the face width over which a tooth advances one pitch (∞ for β = 0)."""
    overlap_ratio: float
    """Face width of one helix (b, or b/2 for a herringbone) over the axial pitch."""
    total_shift: float
    """Largest arc-length displacement of a section from the bottom one, mm."""


def helix_data(
    transverse_module: float, helix_angle: float, *, face_width: float, herringbone: bool, normal_pressure_angle: float
) -> HelixData:
    """Report numbers from the planned (transverse) module; ``face_width`` is the gear's thickness."""
    normal = transverse_module * math.cos(helix_angle)
    width = face_width / 2 if herringbone else face_width
    sin = math.sin(helix_angle)
    return HelixData(
        helix_angle=helix_angle,
        herringbone=herringbone,
        normal_module=normal,
        transverse_module=transverse_module,
        normal_pressure_angle=normal_pressure_angle,
        transverse_pressure_angle=math.atan(math.tan(normal_pressure_angle) / math.cos(helix_angle)),
        axial_pitch=math.pi * normal / sin if sin > 0 else math.inf,
        overlap_ratio=width * sin / (math.pi * normal),
        total_shift=width * math.tan(helix_angle),
    )
