"""Design profiles: TOML files read and validated into frozen pydantic models.

Each TOML table is a model whose fields are the table's keys; constructing one validates it.
Every bad value gives one line naming the dotted key, the value and what is allowed::

    gear1.b = -3: must be a length in mm > 0
    gear1.bb: unknown key (allowed here: a, b, curve, eccentricity, name, pivot)

Lengths are mm; angles are degrees at this boundary (keys ending in ``_deg``) and radians in
the properties the later stages read (``pressure_angle``, ``blend_width``). This package
imports only the standard library, pydantic, :mod:`gearcad.errors` and :mod:`gearcad.formats`.
"""

from .carrier_train import CarrierTrainParams, TrainParams
from .common import DXF_FLAVOURS, FORMATS, BoreParams, OutputParams, ParamsModel
from .curves import (
    CURVES,
    CircleParams,
    CurveParams,
    EllipseParams,
    MotionParams,
    OvalParams,
    RatioParams,
    SamplesParams,
    WalkerParams,
)
from .gear_pair import ClaimParams, Gear2Params, GearPairParams, PairParams, TeethParams
from .nc_internal import InternalTeethParams, NcInternalParams, RingParams
from .nc_planetary import NcPlanetaryParams, PlanetarySetParams, SetTeethParams
from .reading import (
    EXCLUSIVE_KEYS,
    MECHANISMS,
    MODEL_OF,
    MODELS,
    ProfileParams,
    apply_overrides,
    load_profile,
    parse_profile,
    profile_error,
    profile_schema,
    read_profile_text,
    validated,
)
from .roller_body import BodyParams, KinematicsParams, RollerBodyParams, RollerTeethParams
from .rolling_wheel import DriveParams, RollingWheelParams
from .values import RESERVED_NAMES

__all__ = [
    # reading
    "parse_profile",
    "load_profile",
    "read_profile_text",
    "apply_overrides",
    "validated",
    "profile_error",
    "profile_schema",
    "ProfileParams",
    "ParamsModel",
    # gear pair
    "GearPairParams",
    "CurveParams",
    "EllipseParams",
    "MotionParams",
    "OvalParams",
    "CircleParams",
    "RatioParams",
    "WalkerParams",
    "SamplesParams",
    "Gear2Params",
    "PairParams",
    "ClaimParams",
    "TeethParams",
    # other mechanisms
    "RollerBodyParams",
    "BodyParams",
    "KinematicsParams",
    "RollerTeethParams",
    "RollingWheelParams",
    "DriveParams",
    "CarrierTrainParams",
    "TrainParams",
    "NcInternalParams",
    "RingParams",
    "InternalTeethParams",
    "NcPlanetaryParams",
    "PlanetarySetParams",
    "SetTeethParams",
    # shared
    "OutputParams",
    "BoreParams",
    # constants
    "MECHANISMS",
    "MODELS",
    "MODEL_OF",
    "CURVES",
    "DXF_FLAVOURS",
    "FORMATS",
    "EXCLUSIVE_KEYS",
    "RESERVED_NAMES",
]
