"""Field types of the profile models: one TOML value each, checked strictly.

Every type carries the phrase that says what it allows ("a length in mm > 0"); when a value is
bad, its error is that phrase, which :mod:`.messages` puts after the dotted key and the value:
``gear1.b = -3: must be a length in mm > 0``. Numbers are strict: a bool, a string such as
``"3"``, NaN, infinity or an integer too large for a float is refused, never coerced.
"""

from __future__ import annotations

import math
import numbers
import re
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BeforeValidator, Field, ValidationError
from pydantic_core import PydanticCustomError, core_schema

__all__ = [
    "Must",
    "Problems",
    "number",
    "integer",
    "choice",
    "terms",
    "Length",
    "LengthOrZero",
    "Size",
    "Text",
    "Flag",
    "PartName",
    "LayerName",
    "RESERVED_NAMES",
    "LARGEST_LENGTH",
    "SMALLEST_LENGTH",
    "FASTEST",
    "NAME_RULE",
    "Speed",
    "PressureAngleDeg",
    "StandardRackPressureAngleDeg",
    "close_enough",
]

VALUE_ERROR = "gearcad_value"
"""Error type of a value that breaks its own rule; the message is "must be …"."""
RULE_ERROR = "gearcad_rule"
"""Error type of rules between fields; the context lists ``problems``, each with its own key."""


@dataclass(frozen=True)
class Must:
    """``Annotated`` marker: an error about the value becomes the one line "must be <text>".

    Errors inside a list (one bad element) keep their own index, unless ``whole`` is set: then
    any error in the value, however deep, is reported once for the value as a whole. A list's
    length is checked here (``items``), before its elements, so that a list of bad elements
    is not also reported as too short.
    """

    text: str
    whole: bool = False
    items: tuple[int, int | None] | None = None

    def __get_pydantic_core_schema__(self, source: Any, handler: Any) -> core_schema.CoreSchema:
        return core_schema.no_info_wrap_validator_function(self._check, handler(source))

    def __get_pydantic_json_schema__(self, schema: Any, handler: Any) -> Any:
        json_schema = handler(schema)
        if self.items is not None:
            low, high = self.items
            json_schema["minItems"] = low
            if high is not None:
                json_schema["maxItems"] = high
        return json_schema

    def _check(self, value: Any, handler: Any) -> Any:
        if self.items is not None and isinstance(value, list | tuple):
            low, high = self.items
            if len(value) < low or (high is not None and len(value) > high):
                raise PydanticCustomError(VALUE_ERROR, "must be {rule}", {"rule": self.text})
        try:
            return handler(value)
        except ValidationError as exc:
            if self.whole or any(_about_whole(e) for e in exc.errors()):
                raise PydanticCustomError(VALUE_ERROR, "must be {rule}", {"rule": self.text}) from None
            raise


def _about_whole(error: Any) -> bool:
    # a fixed-length tuple given too few items reports the first absent index as "missing"
    loc = error["loc"]
    return loc == () or (error["type"] == "missing" and len(loc) == 1)


class Problems:
    """Rules between fields of one model, collected and raised together.

    Each problem names the key to change (relative to the model, e.g. ``"b"`` or
    ``"harmonics[2]"``), the value it has and what is wrong, so that the message blames the key
    the user must change, not the table that holds it.
    """

    def __init__(self) -> None:
        self._items: list[dict[str, Any]] = []

    def add(self, key: str, value: Any, message: str) -> None:
        self._items.append({"key": key, "value": value, "message": message})

    def missing(self, key: str, message: str) -> None:
        self._items.append({"key": key, "missing": True, "message": message})

    def raise_any(self) -> None:
        if self._items:
            summary = "; ".join(f"{p['key']}: {p['message']}" for p in self._items)
            raise PydanticCustomError(RULE_ERROR, "{summary}", {"summary": summary, "problems": tuple(self._items)})


def bounds_text(*, gt=None, ge=None, lt=None, le=None) -> str:
    """``> 0``, ``from 10 to 35``, ``≥ 0 and < 1``: the range in the words of a message."""
    low = f"> {gt:g}" if gt is not None else f"≥ {ge:g}" if ge is not None else ""
    high = f"< {lt:g}" if lt is not None else f"≤ {le:g}" if le is not None else ""
    if ge is not None and le is not None:
        return f"from {ge:g} to {le:g}"
    return " and ".join(part for part in (low, high) if part)


def number(what: str, *, gt=None, ge=None, lt=None, le=None, why: str = "") -> Any:
    """A finite float (an int is accepted and converted; a bool or string is not)."""
    rule = " ".join(part for part in (what, bounds_text(gt=gt, ge=ge, lt=lt, le=le)) if part)
    return Annotated[
        float,
        Field(strict=True, allow_inf_nan=False, gt=gt, ge=ge, lt=lt, le=le),
        Must(f"{rule}{why}"),
        BeforeValidator(_plain_number),
    ]


def integer(what: str = "an integer", *, ge=None, le=None, multiple_of=None, why: str = "") -> Any:
    """An int (a bool or a float such as 2.0 is refused)."""
    rule = " ".join(part for part in (what, bounds_text(ge=ge, le=le)) if part)
    strict = Field(strict=True, ge=ge, le=le, multiple_of=multiple_of)
    return Annotated[int, strict, Must(f"{rule}{why}"), BeforeValidator(_plain_number)]


def _plain_number(value: Any) -> Any:
    """A numpy integer or float as the Python number it stands for (an API caller's ``np.int64(39)``);
    a bool stays a bool, to be refused."""
    if isinstance(value, bool | int | float) or not isinstance(value, numbers.Real):
        return value
    return int(value) if isinstance(value, numbers.Integral) else float(value)


def choice(*options: str) -> Any:
    """One of a few strings."""
    return Annotated[Literal[options], Must("one of " + ", ".join(repr(o) for o in options))]


def terms(*, max_order: int, multiple_of: int = 1, why: str = "") -> Any:
    """Fourier terms ``[[order, cos, sin], …]``: at most 16, orders 1 … ``max_order``."""
    order = integer(ge=multiple_of, le=max_order, multiple_of=multiple_of)
    coefficient = number("a number")
    step = f", a multiple of {multiple_of}" if multiple_of > 1 else ""
    term = Annotated[
        tuple[order, coefficient, coefficient],
        Must(
            f"[order, cos, sin]: an integer order from {multiple_of} to {max_order}{step}{why}, then two numbers", True
        ),
    ]
    return Annotated[tuple[term, ...], Must("a list of at most 16 [order, cos, sin] terms", items=(0, 16))]


LARGEST_LENGTH = 100_000.0
"""mm: 100 m, far beyond any part and still a number the geometry handles exactly (at 1e12 mm the
rolling residual of a pair is 1e-4 mm, at 1e300 the curves overflow)."""
SMALLEST_LENGTH = 0.001
"""mm: 1 µm, finer than any tolerance (at 1e-6 mm GEOS loses the topology, at 1e-300 the
polylines are NaN)."""
FASTEST = 1e6
"""rev/min: far beyond any mechanism, and the accelerations (∝ speed²) stay finite."""

Length = number("a length in mm", ge=SMALLEST_LENGTH, le=LARGEST_LENGTH)
LengthOrZero = number("a length in mm", ge=0, le=LARGEST_LENGTH)
"""A length that may be 0: a gap, a chamfer, a keyway (0 means none)."""
Size = Annotated[tuple[Length, Length], Must("[width, height]: two lengths in mm > 0")]
"""A rectangle, mm: a sheet or a printer bed."""
Speed = number("a speed in rev/min", gt=0, le=FASTEST)
PressureAngleDeg = number("an angle in degrees", ge=10, le=35)
StandardRackPressureAngleDeg = number(
    "an angle in degrees",
    ge=10,
    le=23,
    why=" (the standard rack, tip rounding 0.38·m and dedendum 1.25·m, comes to a point beyond 23.1°)",
)
"""The pressure angle of a mechanism whose rack has no other keys (carrier trains, roller bodies)."""
MOST_TEXT = 500
"""Characters a text value (a title, a source) may hold: a chart's title is one line, and
matplotlib lays a 300 kB one out in ~40 s."""


def _utf8(text: Any) -> Any:
    try:
        if isinstance(text, str):
            text.encode("utf-8")
    except UnicodeEncodeError as exc:  # a lone surrogate: a byte of a command line that was not UTF-8
        raise PydanticCustomError(
            VALUE_ERROR, "must be UTF-8 text: character {at} is an undecodable byte", {"at": exc.start + 1}
        ) from None
    return text


Text = Annotated[
    str,
    Field(strict=True, max_length=MOST_TEXT),
    Must(f"a string of at most {MOST_TEXT} characters"),
    BeforeValidator(_utf8),
]
Flag = Annotated[bool, Field(strict=True), Must("true or false")]

RESERVED_NAMES = ("assembly", "sheet", "plate", "index", "index.html", "report", "kinematics", "animation")
"""Names the build gives its own files; a part or profile may not take them (any case)."""
NAME_RULE = (
    "a name of 1 to 64 characters: letters A–Z a–z, digits, '-', '_' or '.', "
    "not starting with '.' (it names a file or folder)"
)


def _not_reserved(name: str) -> str:
    if name.casefold() in RESERVED_NAMES or re.fullmatch(r"plate-[0-9]+", name.casefold()):
        raise PydanticCustomError(
            VALUE_ERROR,
            "must not be '{name}': the build writes its own files under that name (reserved: {reserved}, plate-2, …)",
            {"name": name.casefold(), "reserved": ", ".join(RESERVED_NAMES)},
        )
    return name


PartName = Annotated[
    str,
    Field(strict=True, min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_-][A-Za-z0-9._-]*$"),
    Must(NAME_RULE),
    AfterValidator(_not_reserved),
]
"""A profile's or part's name: it becomes a file or folder name, so it cannot leave the output folder."""

LayerName = Annotated[
    str,
    Field(strict=True, min_length=1, max_length=255, pattern=r"^[A-Za-z0-9_$-]+$"),
    Must("a DXF layer name: letters, digits, '-', '_' or '$'"),
]


def close_enough(a: float, b: float) -> bool:
    """Two values given for one quantity (e.g. b and a·√(1 − e²)) agree."""
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
