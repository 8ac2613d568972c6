"""What each chart is drawn from: the typed payloads a mechanism puts under ``Draft.charts``
(chart file name → payload), computed with the design and read by ``gearcad/export/charts/``,
which draws and computes nothing of the model.  A new chart is its payload here and its drawing
there; the tuples are named so that a drawer may still unpack them."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, TypeAlias, TypedDict, Union

import numpy as np

if TYPE_CHECKING:
    from ..teeth.pair import ToothedPairData
    from .pair_pitch import PairDesign


@dataclass(frozen=True)
class RollingWheelDetail:
    """The motion over the travel: driver angle, the wheel's angle by both methods, rates."""

    phi1: np.ndarray
    by_contour: np.ndarray
    by_rates: np.ndarray
    omega2: np.ndarray
    omega3: np.ndarray
    eps2: np.ndarray


__all__ = [
    "Json",
    "Blocks",
    "PitchCurvesChart",
    "MeshChart",
    "WalkerPitchChart",
    "ShoeChart",
    "AmplitudeLimitsChart",
    "FieldFrame",
    "VelocityFieldChart",
    "LimitsVsRChart",
    "ShapeFamilyChart",
    "ChartData",
    "Charts",
]

Json: TypeAlias = None | bool | int | float | str | list["Json"] | tuple["Json", ...] | dict[str, "Json"]
"""A JSON-ready value (numpy scalars count as numbers: the report makes them plain)."""
Blocks: TypeAlias = dict[str, Json]
"""A mechanism's report blocks by key (``Draft.data``, ``Design.data``): JSON-ready."""


class PitchCurvesChart(NamedTuple):
    """``pitch_curves.png``: the pair in mesh and each pitch curve within the tolerance (mm)."""

    pitch: PairDesign
    rings: tuple[np.ndarray, np.ndarray]


class MeshChart(NamedTuple):
    """``mesh.png``: the teeth in mesh."""

    pitch: PairDesign
    teeth: ToothedPairData


class WalkerPitchChart(NamedTuple):
    """``paper_pitch_curves.png``: the paper's wheel and pinion beside gearcad's pair (polar)."""

    paper: dict[str, Any]
    pair: dict[str, Any]


class ShoeChart(NamedTuple):
    """``shoe.png``: the shoe's ring (mm), its poses (hub angle, turn, crank pin B1 from the hub)
    and the hub height K."""

    ring: np.ndarray
    poses: list[tuple[float, float, np.ndarray]]
    hub: float


class AmplitudeLimitsChart(TypedDict):
    """``amplitude_limits.png``: the exact limits against m, beside eq. 4."""

    limits: Blocks
    direction: str
    roller_radius: float
    eq4: tuple[float, float]


class FieldFrame(TypedDict):
    """The contour at one turn angle and 49 of its points with their velocity and acceleration."""

    degrees: float
    outline: np.ndarray
    points: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


class VelocityFieldChart(TypedDict):
    """``velocity_field.png``: the body's field at a few turn angles."""

    direction: str
    m: int
    amplitude: float
    rpm: float
    roller_radius: float
    field: list[FieldFrame]


class LimitsVsRChart(TypedDict):
    """``limits_vs_r.png``: the limits against the roller radius, and the paper's by-eye ones."""

    table: Blocks
    paper_by_eye: Any


class ShapeFamilyChart(TypedDict):
    """``shape_family_m<m>.png``: the paper's Figs. 1–2."""

    family: tuple[dict[str, Any], ...]
    title: str


ChartData: TypeAlias = Union[
    "PairDesign",  # kinematics.png
    PitchCurvesChart,
    MeshChart,
    WalkerPitchChart,
    ShoeChart,
    AmplitudeLimitsChart,
    VelocityFieldChart,
    LimitsVsRChart,
    ShapeFamilyChart,
    "RollingWheelDetail",  # motion.png
    Blocks,  # train.png (the train's report blocks), elliptic_type2.png and vehicle_speed.png (tables)
]
"""What one chart is drawn from."""
Charts: TypeAlias = dict[str, ChartData]
"""Chart file name → what it is drawn from."""
