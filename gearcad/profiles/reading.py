"""Profiles read: TOML text, overrides, validation into parameters; and the profiles' JSON Schema.

Every error a user can cause here is a :class:`~gearcad.errors.ProfileError` whose message has
one line per bad value (``gear1.b = -3: must be a length in mm > 0``); :func:`load_profile`
prefixes each line with the file's path.
"""

from __future__ import annotations

import codecs
import copy
import functools
import tomllib
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Annotated, Any, TypeVar, Union

from pydantic import BaseModel, Discriminator, Tag, TypeAdapter, ValidationError
from pydantic.json_schema import GenerateJsonSchema

from ..errors import ProfileError
from .carrier_train import CarrierTrainParams
from .common import ParamsModel
from .docs import document_fields
from .gear_pair import GearPairParams
from .messages import error_lines, show
from .nc_internal import NcInternalParams
from .nc_planetary import NcPlanetaryParams
from .roller_body import RollerBodyParams
from .rolling_wheel import RollingWheelParams

__all__ = [
    "MOST_BYTES",
    "MECHANISMS",
    "MODELS",
    "MODEL_OF",
    "EXCLUSIVE_KEYS",
    "ProfileParams",
    "parse_profile",
    "load_profile",
    "read_profile_text",
    "apply_overrides",
    "validated",
    "profile_error",
    "profile_schema",
]

MODELS: tuple[type[ParamsModel], ...] = (
    GearPairParams,
    RollerBodyParams,
    RollingWheelParams,
    CarrierTrainParams,
    NcInternalParams,
    NcPlanetaryParams,
)
"""Every mechanism's profile model, the default first: a new mechanism's model is one more entry
(its ``mechanism`` field's default is its name)."""
MECHANISMS = tuple(model.model_fields["mechanism"].default for model in MODELS)
MODEL_OF: dict[str, type[ParamsModel]] = dict(zip(MECHANISMS, MODELS, strict=True))
"""The profile model of each ``mechanism`` value: a new mechanism registers its model here
(``MODEL_OF[name] = Model``, its ``mechanism`` field a ``Literal[name]`` defaulting to it); reading,
errors and the schema look models up here, not in :data:`MODELS`."""
ProfileParams = Union[MODELS]  # noqa: UP007 - made from the table, not written out again

EXCLUSIVE_KEYS = (("teeth.module", "teeth.count"), ("gear1.b", "gear1.eccentricity"))
"""Keys of which a profile gives one: an override that sets one removes the other."""
_PARTNER = {a: b for pair in EXCLUSIVE_KEYS for a, b in (pair, pair[::-1])}

M = TypeVar("M", bound=BaseModel)


def _mechanism_of(value: Any) -> Any:
    return value.get("mechanism", "gear-pair") if isinstance(value, Mapping) else getattr(value, "mechanism", None)


def _tagged() -> Any:
    """Any profile model, told apart by its ``mechanism`` (every model of :data:`MODEL_OF` now,
    a registered one too)."""
    return Annotated[
        Union[tuple(Annotated[cls, Tag(tag)] for tag, cls in MODEL_OF.items())],  # noqa: UP007
        Discriminator(_mechanism_of),
    ]


def profile_error(exc: ValidationError, root: Any = None) -> ProfileError:
    """A pydantic ``ValidationError`` as gearcad's error, one line per bad value.

    ``root`` is the class that was validated (found from the error's title when not given):
    for an API layer that builds parameters itself, ``except ValidationError as e: raise
    profile_error(e) from None``.
    """
    if root is None:
        root = {cls.__name__: cls for cls in ParamsModel.__subclasses__()}.get(exc.title, None) or _tagged()
    return ProfileError("\n".join(error_lines(exc, root)))


def validated(cls: type[M], /, **fields: Any) -> M:
    """``cls(**fields)``, raising :class:`ProfileError` (not pydantic's error) for bad fields.

    ``validated(CircleParams, radius=-1)`` raises ``ProfileError("radius = -1: must be a
    length in mm > 0")``; keys are relative to ``cls``.
    """
    try:
        return cls(**fields)
    except ValidationError as exc:
        raise profile_error(exc, cls) from None


def parse_profile(data: Mapping[str, Any], *, default_name: str = "profile") -> ProfileParams:
    """Validate a profile's data (as TOML reads it); ``name`` defaults to ``default_name``.

    Raises :class:`ProfileError` with one line per bad value, all of them at once where one
    does not hide another (rules between keys are checked once each key is valid).
    """
    if not isinstance(data, Mapping):
        raise ProfileError(f"the profile = {show(data)}: must be a table of keys")
    mechanism = data.get("mechanism", "gear-pair")
    cls = MODEL_OF.get(mechanism) if isinstance(mechanism, str) else None
    if cls is None:
        raise ProfileError(f"mechanism = {show(mechanism)}: must be one of " + ", ".join(map(repr, MODEL_OF)))
    named = "name" in data
    try:
        return cls.model_validate(data if named else {**data, "name": default_name})
    except ValidationError as exc:
        lines = error_lines(exc, cls)
    if not named:  # the name came from the file's name: say so, and how to choose another
        lines = [
            f'{ln} (the name comes from the file\'s name; set name = "…")' if ln.startswith("name = ") else ln
            for ln in lines
        ]
    raise ProfileError("\n".join(lines))


def apply_overrides(
    data: Mapping[str, Any],
    overrides: Sequence[str] | Mapping[str, Any] = (),
    *,
    unset: Iterable[str] = (),
) -> dict[str, Any]:
    """A deep copy of ``data`` with keys removed (``unset``) and then set (``overrides``).

    ``overrides`` is either ``KEY=VALUE`` strings, as ``--set`` gives them (VALUE is read as
    TOML, else taken as a plain string), or a mapping ``{dotted key: value}`` where None
    removes the key. Setting one of :data:`EXCLUSIVE_KEYS` removes its partner, so that
    ``teeth.count=39`` works on a profile that gives ``teeth.module``. Setting ``name`` but not
    ``title`` appends `` (name)`` to the title, so that a variant is told apart from its original.
    """
    _check_nesting(data, "the profile")
    result = copy.deepcopy(dict(data))
    for key in [unset] if isinstance(unset, str) else unset:
        _remove(result, _parts(key, f"--unset {key!r}"))
    items = list(_items(overrides))
    keys = {key.strip() for _, key, _ in items if isinstance(key, str)}
    for label, key, value in items:
        parts = _parts(key, label)
        if value is None:
            _remove(result, parts)
            continue
        node = result
        for depth, part in enumerate(parts[:-1], 1):
            node = node.setdefault(part, {})
            if not isinstance(node, dict):
                raise ProfileError(f"{label}: {'.'.join(parts[:depth])} is not a table")
        node[parts[-1]] = value
        partner = _PARTNER.get(".".join(parts))
        if partner is not None:
            _remove(result, partner.split("."))
    name, title = result.get("name"), result.get("title")
    if "name" in keys and "title" not in keys and isinstance(name, str) and isinstance(title, str) and title:
        result["title"] = f"{title} ({name})"  # a variant must not look like the original in the index
    return result


def _items(overrides: Sequence[str] | Mapping[str, Any]) -> Iterable[tuple[str, str, Any]]:
    if isinstance(overrides, Mapping):
        for key, value in overrides.items():
            _check_nesting(value, f"override {key!r}")
            yield f"override {key!r}", key, copy.deepcopy(value)
        return
    if isinstance(overrides, str):
        overrides = [overrides]
    for item in overrides:
        label = f"--set {show(item)}"  # kept short: an item may be megabytes
        if not isinstance(item, str) or "=" not in item:
            raise ProfileError(f"{label}: must be KEY=VALUE, e.g. gear1.a=30")
        key, raw = item.split("=", 1)
        yield label, key, toml_value(raw, label)


def toml_value(raw: str, label: str = "value") -> Any:
    """A command-line value read as TOML (else as the text itself); nesting bounded (``label`` names it)."""
    try:
        parsed = tomllib.loads(f"v = {raw}")
    except ValueError:  # TOMLDecodeError, or an integer past Python's 4300-digit limit
        return raw
    except RecursionError:
        raise ProfileError(f"{label}: nested more than {_MOST_NESTING} lists or tables deep") from None
    _check_nesting(parsed, label)
    return parsed["v"] if parsed.keys() == {"v"} else raw


MOST_BYTES = 16 << 20
"""The largest profile file read, bytes (100 000 sampled radii take about 2 MB)."""
_MOST_NESTING = 32
"""Tables and lists inside one another a profile may hold (a profile needs 4; Python's own
recursion gives out near 500)."""


def _check_nesting(value: Any, label: str) -> None:
    """Refuse ``value`` nested deeper than :data:`_MOST_NESTING` (walked without recursion)."""
    stack = [(value, 0)]
    while stack:
        node, depth = stack.pop()
        if depth > _MOST_NESTING:
            raise ProfileError(f"{label}: nested more than {_MOST_NESTING} lists or tables deep")
        children = node.values() if isinstance(node, Mapping) else node if isinstance(node, list | tuple) else ()
        stack.extend((child, depth + 1) for child in children if isinstance(child, Mapping | list | tuple))


def _parts(key: Any, label: str) -> list[str]:
    parts = [part.strip() for part in key.split(".")] if isinstance(key, str) else [""]
    if not all(parts):
        raise ProfileError(f"{label}: the key must be dotted names, e.g. pair.driver_rpm")
    return parts


def _remove(data: dict, parts: list[str]) -> None:
    node: Any = data
    for part in parts[:-1]:
        node = node.get(part) if isinstance(node, dict) else None
    if isinstance(node, dict):
        node.pop(parts[-1], None)


def _where(path: Path) -> str:
    return str(path) if str(path).isprintable() else str(path).encode("unicode_escape", "backslashreplace").decode()


def read_profile_text(path: str | Path) -> str:
    """A profile file's text: at most 16 MiB of UTF-8 (a byte-order mark is dropped); else
    :class:`ProfileError`, one line starting with ``path: ``."""
    where = _where(Path(path))
    try:
        with open(path, "rb") as fh:  # at most the limit and a byte: /dev/zero has no end
            raw = fh.read(MOST_BYTES + 1)
    except OSError as exc:
        raise ProfileError(f"{where}: cannot read the profile ({exc.strerror or exc})") from None
    if len(raw) > MOST_BYTES:
        raise ProfileError(f"{where}: more than {MOST_BYTES >> 20} MiB, too large for a profile")
    skip = len(codecs.BOM_UTF8) if raw.startswith(codecs.BOM_UTF8) else 0
    try:
        return raw[skip:].decode("utf-8")
    except UnicodeDecodeError as exc:
        at = skip + exc.start
        raise ProfileError(f"{where}: not UTF-8 text (byte 0x{raw[at]:02x} at offset {at})") from None


def load_profile(
    path: str | Path,
    overrides: Sequence[str] | Mapping[str, Any] = (),
    *,
    unset: Iterable[str] = (),
) -> ProfileParams:
    """Read, override and validate one profile file; every error line starts with ``path: ``.

    The file must be UTF-8 (a byte-order mark is accepted); ``name`` defaults to its stem.
    """
    path = Path(path)
    where = _where(path)
    text = read_profile_text(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"{where}: not valid TOML ({exc})") from None
    except ValueError:
        raise ProfileError(f"{where}: not valid TOML (an integer of more than 4300 digits)") from None
    except RecursionError:
        raise ProfileError(f"{where}: not valid TOML here: lists or tables nested hundreds deep") from None
    try:
        return parse_profile(apply_overrides(data, overrides, unset=unset), default_name=path.stem)
    except ProfileError as exc:
        raise ProfileError("\n".join(f"{where}: {line}" for line in str(exc).splitlines())) from None


class _TomlSchema(GenerateJsonSchema):
    """TOML has no null: a key that may be absent is simply left out, never ``null``."""

    def nullable_schema(self, schema: Any) -> Any:
        return self.generate_inner(schema["schema"])

    def default_schema(self, schema: Any) -> Any:
        if schema.get("default", ...) is None:
            return self.generate_inner(schema["schema"])
        return super().default_schema(schema)

    def field_title_should_be_set(self, schema: Any) -> bool:
        return False  # "Center Distance" says less than the key itself, which editors show

    def generate(self, schema: Any, mode: Any = "validation") -> Any:
        return _plain(super().generate(schema, mode=mode))


def _plain(node: Any) -> Any:
    """Docstrings' ``literal`` marks dropped: editors show descriptions as plain text."""
    if isinstance(node, dict):
        return {k: v.replace("``", "") if k == "description" else _plain(v) for k, v in node.items()}
    if isinstance(node, list):
        return [_plain(v) for v in node]
    return node


def _models(cls: type[BaseModel]) -> list[type[BaseModel]]:
    return [sub for child in cls.__subclasses__() for sub in (child, *_models(child))]


def profile_schema() -> dict[str, Any]:
    """The JSON Schema of a profile, for editors (taplo, Even Better TOML).

    ``profiles/profile.schema.json`` holds it; a profile whose first line is
    ``#:schema ./profile.schema.json`` is checked and completed as it is typed. Regenerate
    the file with ``json.dumps(profile_schema(), indent=2, ensure_ascii=False)``.
    """
    return copy.deepcopy(_schema(tuple(MODEL_OF.items()), tuple(_models(ParamsModel))))


@functools.lru_cache(maxsize=2)
def _schema(tagged: tuple, models: tuple) -> dict[str, Any]:
    """:func:`profile_schema` for the profile models registered (``tagged``, and ``models`` every
    model class): made once for them (the models rebuilt and the schema generated: half a
    CPU-second), again only when a mechanism is registered."""
    document_fields(list(models))
    schema = TypeAdapter(_tagged()).json_schema(schema_generator=_TomlSchema)
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "gearcad profile",
        "description": "A gearcad design profile: a gear pair (the default), roller body, rolling wheel "
        "or carrier train. Lengths in mm, angles in degrees where the key ends in _deg.",
        **schema,
    }
