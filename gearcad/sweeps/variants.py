"""A sweep's designs' parameters: the profile validated once, each design's overrides alone.

``Variants(data, name).params(overrides)`` is ``parse_profile(overridden(data, overrides),
default_name=name)`` — the same parameters (fields, defaults, ``model_fields_set``), or the same
:class:`~gearcad.errors.ProfileError` — without validating the whole profile for every design
(issue 35: validation was a third of a pitch-stage design's time on the focus pair).

For each set of override keys a plan is made once (``overridden`` run on placeholders: which
tables are copied, which keys set and which removed depend on the keys only): the tables on the
overrides' paths are built again for each design — each value the overrides leave as the profile
gives it validated once, each new one by its field's own schema, the table assembled as pydantic
assembles it and its ``after`` validators run on it — and the tables off the paths are each
validated once (by their field's schema: their own validators, none of their parent's) and
shared.  A model with any other kind of validation (``before`` or ``wrap`` validators, field
validators, a post-init, private attributes, aliases, a default pydantic would copy, a config
beyond the profiles' own), a new ``name`` (the title follows it) or an overridden union tag goes
through ``parse_profile``; so does any design whose values or rules fail here, so that its
refusal is ``parse_profile``'s own message.
"""

from __future__ import annotations

import inspect
from functools import cache
from typing import Annotated, Any

from pydantic import BaseModel, TypeAdapter

from ..profiles.reading import MODEL_OF, parse_profile
from .overrides import overridden
from .space import admits

__all__ = ["Variants"]

_CONFIG = {"frozen", "extra", "json_schema_extra", "defer_build", "title"}
"""Model settings that change nothing of how a field's value is validated (``extra`` is
"forbid": an unknown key sends the design to ``parse_profile``)."""


_ABSENT = object()
"""A key the profile does not give."""


@cache
def _adapter(cls: type[BaseModel], key: str):
    """The validator of the field's own schema (its type, constraints, validators, discriminator)."""
    field = cls.model_fields[key]
    return TypeAdapter(Annotated[field.annotation, field]).validator


class _Model:
    """What building a model here needs, found once: its keys, the required ones, the defaults
    to fill in (each shared, as pydantic shares a hashable default) and its ``after`` validators."""

    def __init__(self, cls: type[BaseModel], after: tuple) -> None:
        self.cls, self.after = cls, after
        self.fields = fields = dict(cls.model_fields)
        self.keys = frozenset(fields)
        self.required = frozenset(k for k, f in fields.items() if f.is_required())
        self.defaults = {k: f.default for k, f in fields.items() if not f.is_required()}

    def full(self, values: dict[str, Any], given) -> dict[str, Any]:
        """Every field's value, in the model's order: ``values`` for the keys given, else the default."""
        return {k: values[k] if k in given else self.defaults[k] for k in self.fields}

    def make(self, full: dict[str, Any], given: set[str]) -> BaseModel:
        """The model of ``full`` (every field, validated), its ``after`` validators run on it: as
        pydantic makes it."""
        made = self.cls.__new__(self.cls)
        object.__setattr__(made, "__dict__", full)
        object.__setattr__(made, "__pydantic_fields_set__", given)
        object.__setattr__(made, "__pydantic_extra__", None)
        object.__setattr__(made, "__pydantic_private__", None)
        for check in self.after:
            made = check(made)
        return made


def _shareable(value: Any) -> bool:
    try:
        hash(value)
    except TypeError:
        return False
    return True


@cache
def _model(cls: type[BaseModel]) -> _Model | None:
    """How to build ``cls`` here; None if it has any validation but ``after`` validators (which
    building would skip), aliases, default factories or defaults that pydantic would copy."""
    decorators = cls.__pydantic_decorators__
    plain = not (decorators.field_validators or decorators.root_validators or decorators.validators)
    plain = plain and cls.__pydantic_post_init__ is None and not cls.__private_attributes__
    plain = plain and set(cls.model_config) <= _CONFIG and cls.model_config.get("extra") == "forbid"
    for field in cls.model_fields.values():
        plain = plain and field.alias is None and field.validation_alias is None and field.default_factory is None
        plain = plain and (field.is_required() or _shareable(field.default))
    if not plain:
        return None
    after = []
    for decorator in decorators.model_validators.values():
        if decorator.info.mode != "after" or len(inspect.signature(decorator.func).parameters) != 1:
            return None
        after.append(decorator.func)
    return _Model(cls, tuple(after))


@cache
def _table_class(cls: type[BaseModel], key: str, tag: Any) -> type[BaseModel] | None:
    """The model a table given for ``cls.key`` is (its tag ``tag`` where the field is a tagged
    union), if it can be built here: the field admits tables only, with no constraint of its own."""
    field = cls.model_fields[key]
    tables, plain = admits(field.annotation)
    if plain or not tables or field.metadata:
        return None
    if len(tables) > 1:
        name = field.discriminator
        if not isinstance(name, str) or tag is None:
            return None
        tables = [t for t in tables if name in t.model_fields and tag in _literals(t.model_fields[name].annotation)]
    return tables[0] if len(tables) == 1 and _model(tables[0]) is not None else None


def _literals(annotation: Any) -> tuple:
    return getattr(annotation, "__args__", ()) if getattr(annotation, "__origin__", None) is not None else ()


class _Key:
    """Where an override's value goes, in a plan (``overridden`` run once with these in place of
    the values: which tables are copied, which keys set and which removed depends on the keys only)."""

    __slots__ = ("key",)

    def __init__(self, key: str) -> None:
        self.key = key


class _Plan:
    """One table on the overrides' paths: its model, its keys, every field's value but those the
    overrides change (the profile's validated once, or the default) and, in order, the changes:
    ``(key, validator, the override's key)`` for a value, ``(key, None, plan)`` for a table further
    down the path."""

    __slots__ = ("model", "given", "template", "changes")

    def __init__(self, model: _Model, given: frozenset, fixed: dict, changes: list) -> None:
        self.model, self.given, self.changes = model, given, changes
        self.template = model.full({**fixed, **{key: None for key, _, _ in changes}}, given)

    def make(self, overrides: dict[str, Any]) -> BaseModel:
        full = self.template.copy()
        for key, validator, change in self.changes:
            full[key] = (
                validator.validate_python(overrides[change]) if validator is not None else change.make(overrides)
            )
        return self.model.make(full, set(self.given))


class Variants:
    """The parameters of a profile's variants, one design's overrides at a time."""

    def __init__(self, data: dict, name: str) -> None:
        self.data, self.name = data, name
        self._base = data if "name" in data else {**data, "name": name}
        self._plans: dict[tuple, _Plan | None] = {}  # the overrides' keys → how to make their parameters
        self.fast = 0
        """Designs whose parameters were made here (the others went through parse_profile)."""

    def params(self, overrides: dict[str, Any]):
        """``parse_profile(overridden(data, overrides), default_name=name)``."""
        keys = tuple(overrides)
        if keys not in self._plans:
            self._plans[keys] = self._plan(keys)
        plan, made = self._plans[keys], None
        if plan is not None:
            try:
                made = plan.make(overrides)
            except Exception:  # noqa: BLE001 - whatever it is, parse_profile says it in its own words
                made = None
        if made is None:
            return parse_profile(overridden(self.data, overrides), default_name=self.name)
        self.fast += 1
        return made

    def _plan(self, keys: tuple) -> _Plan | None:
        """How to make the parameters of overrides of these keys; None: through parse_profile."""
        if "name" in keys:  # the title follows a new name when it is text: it depends on the value
            return None
        try:
            new = overridden(self._base, {key: _Key(key) for key in keys})
            mechanism = new.get("mechanism", "gear-pair")
            cls = MODEL_OF.get(mechanism) if isinstance(mechanism, str) else None
            return self._table(cls, new, self._base) if cls is not None else None
        except Exception:  # noqa: BLE001 - a bad key, an invalid profile: parse_profile says so
            return None

    def _table(self, cls: type[BaseModel], data: dict, base: dict) -> _Plan | None:
        model = _model(cls)
        given = frozenset(data)
        if model is None or not given <= model.keys or not model.required <= given:  # pydantic says which
            return None
        fixed, changes = {}, []
        for key, raw in data.items():
            if raw is base.get(key, _ABSENT):  # as the profile gives it: validated once
                fixed[key] = _adapter(cls, key).validate_python(raw)
            elif isinstance(raw, _Key):
                changes.append((key, _adapter(cls, key), raw.key))
            elif isinstance(raw, dict):  # a table on an override's path
                tag = model.fields[key].discriminator
                tag = raw.get(tag) if isinstance(tag, str) else None
                table = _table_class(cls, key, tag) if not isinstance(tag, _Key) else None
                was = base.get(key)
                plan = self._table(table, raw, was if isinstance(was, dict) else {}) if table is not None else None
                if plan is None:
                    return None
                changes.append((key, None, plan))
            else:
                return None
        return _Plan(model, given, fixed, changes)
