"""pydantic's ``ValidationError`` turned into gearcad's lines: one per bad value.

Each line names the dotted key as the profile writes it, the value as TOML shows it and what is
allowed::

    gear1.b = -3: must be a length in mm > 0
    gear1.bb: unknown key (allowed here: a, b, curve, eccentricity, name, pivot)
    [gear1] is missing: the table is required

The location pydantic reports (``('gear1', 'ellipse', 'b')``) is walked along the model
classes, which drops the union tags (``'ellipse'``) and finds the table an unknown key was
written in.
"""

from __future__ import annotations

import json
import math
import re
import types
from typing import Annotated, Any, Literal, Union, get_args, get_origin

from pydantic import BaseModel, ValidationError

from .values import RULE_ERROR, VALUE_ERROR, Must

__all__ = ["show", "error_lines"]

_SHOWN_ITEMS = 6
_SHOWN_CHARS = 100
_LINES_PER_LIST = 5
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")  # TOML's bare keys; any other key is shown quoted


def show(value: Any) -> str:
    """A value as the profile would write it (strings quoted), kept short: a list or table is cut
    between its elements (``[1, 2, 3, … 999,997 more]``), never inside a number."""
    text = _toml(value, depth=0, budget=_SHOWN_CHARS)
    return text if len(text) <= _SHOWN_CHARS else text[: _SHOWN_CHARS - 1] + "…"


def _elements(texts, count: int, budget: int, brackets: str) -> str:
    """``[a, b, … N more]`` with as many whole elements as fit in ``budget`` characters (one at
    least), from the element texts ``texts`` (lazily made) of ``count`` elements."""
    shown: list[str] = []
    used = 2
    for text in texts:
        more = count - len(shown) - 1
        tail = len(f", … {more:,} more") if more else 0
        if shown and used + len(text) + 2 + tail > budget:
            break
        shown.append(text)
        used += len(text) + 2
    if len(shown) < count:
        shown.append(f"… {count - len(shown):,} more")
    return brackets[0] + ", ".join(shown) + brackets[1]


def _toml(value: Any, depth: int, budget: int = _SHOWN_CHARS) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if value.bit_length() <= 64:
            return str(value)
        try:
            return f"<an integer of {len(str(abs(value)))} digits>"
        except ValueError:  # str() refuses integers past 4300 digits
            return f"<an integer of about {round(value.bit_length() * math.log10(2))} digits>"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, list | tuple):
        if depth > 2:
            return "[…]"
        texts = (_toml(v, depth + 1, budget // 2) for v in value[:_SHOWN_ITEMS])
        return _elements(texts, len(value), budget, "[]")
    if isinstance(value, dict):
        if depth > 2:
            return "{…}"
        pairs = list(value.items())[:_SHOWN_ITEMS]
        texts = (f"{_key(k)} = {_toml(v, depth + 1, budget // 2)}" for k, v in pairs)
        return _elements(texts, len(value), budget, "{}")
    return str(value)


def _key(name: Any) -> str:
    """A key as TOML writes it: bare if it can be, else quoted (never a raw newline)."""
    name = str(name)
    return name if _BARE_KEY.fullmatch(name) else json.dumps(name, ensure_ascii=not name.isprintable())


_MOST_LINES = 40
"""Lines one profile's errors print at most; the rest are counted."""


def error_lines(exc: ValidationError, root: Any = None) -> list[str]:
    """One line per bad value, in the order pydantic found them.

    ``root`` is the model class (or union of them) that was validated; with it the union tags
    are dropped from the keys and unknown keys list what is allowed in their table.
    """
    lines: dict[str, None] = {}  # ordered and unique in linear time: 100 000 unknown keys are 100 000 errors
    per_list: dict[str, int] = {}
    for error in exc.errors():
        key, where, annotation = _locate(root, error["loc"])
        for line in _lines(error, key, where, annotation):
            base = key.split("[", 1)[0] if "[" in key else None
            if base is not None:
                per_list[base] = per_list.get(base, 0) + 1
                if per_list[base] > _LINES_PER_LIST:
                    continue
            lines[line] = None
    for base, count in per_list.items():
        if count > _LINES_PER_LIST:
            lines[f"{base}: {count - _LINES_PER_LIST} more bad values like these"] = None
    found = list(lines)
    if len(found) > _MOST_LINES:
        found[_MOST_LINES:] = [f"… and {len(found) - _MOST_LINES} more problems"]
    return found


def _lines(error: dict, key: str, where: type[BaseModel] | None, annotation: Any) -> list[str]:
    kind, value, ctx = error["type"], error.get("input"), error.get("ctx") or {}
    shown = key or "the profile"
    if kind == VALUE_ERROR:
        return [f"{shown} = {show(value)}: {error['msg']}"]
    if kind == RULE_ERROR:
        return [_problem(key, p) for p in ctx["problems"]]
    if kind == "extra_forbidden":
        allowed = ", ".join(sorted(where.model_fields)) if where is not None else "see the schema"
        return [f"{key}: unknown key (allowed here: {allowed})"]
    if kind == "missing":
        if _models(annotation):
            return [f"[{key}] is missing: the table is required"]
        rule = next((m.text for m in _metadata(annotation) if isinstance(m, Must)), "a value")
        return [f"{key} is missing: {rule} is required"]
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return [f"{shown} = {show(value)}: must be a table ([{key}])" if key else "the profile must be a table"]
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        field = ctx.get("discriminator", "").strip("'")
        field = "mechanism" if field.endswith("()") else field
        tags = ", ".join(repr(t) for t in _tags(annotation, field))
        full = f"{key}.{field}" if key else field
        if kind == "union_tag_not_found":
            return [f"{full} is missing: one of {tags} is required"]
        given = value.get(field) if isinstance(value, dict) else ctx.get("tag")
        return [f"{full} = {show(given)}: must be one of {tags}"]
    if kind == "literal_error":
        return [f"{shown} = {show(value)}: must be {ctx.get('expected', 'one of the allowed values')}"]
    message = error["msg"][:1].lower() + error["msg"][1:]
    return [f"{shown} = {show(value)}: {message}"]


def _problem(key: str, problem: dict) -> str:
    sub = problem["key"]
    full = f"{key}{sub}" if not key or sub.startswith("[") else f"{key}.{sub}" if sub else key
    if problem.get("missing"):
        return f"{full} is missing: {problem['message']}"
    return f"{full} = {show(problem['value'])}: {problem['message']}"


def _locate(root: Any, loc: tuple) -> tuple[str, type[BaseModel] | None, Any]:
    """The dotted key of ``loc``, the model whose table holds it, and its annotation."""
    key, where, annotation = "", None, root
    for item in loc:
        models = _models(annotation)
        if len(models) > 1 and isinstance(item, str):
            tagged = [m for m in models if any(item in _literals(f.annotation) for f in m.model_fields.values())]
            if tagged:  # a union's tag: not a key the profile writes
                annotation = tagged[0]
                continue
        if isinstance(item, int):
            key += f"[{item}]"
            annotation = _element(annotation, item)
            continue
        key = f"{key}.{_key(item)}" if key else _key(item)
        where = models[0] if len(models) == 1 else None
        field = where.model_fields.get(item) if where is not None else None
        annotation = field.annotation if field is not None else None
        if field is not None:
            annotation = Annotated[(annotation, *field.metadata)] if field.metadata else annotation
    return key, where, annotation


def _unwrap(annotation: Any) -> Any:
    while get_origin(annotation) is Annotated:
        annotation = get_args(annotation)[0]
    return annotation


def _metadata(annotation: Any) -> list:
    found = []
    while get_origin(annotation) is Annotated:
        found.extend(annotation.__metadata__)
        annotation = get_args(annotation)[0]
    for member in _members(annotation) if _is_union(annotation) else ():
        found.extend(_metadata(member))
    return found


def _is_union(annotation: Any) -> bool:
    return get_origin(annotation) in (Union, types.UnionType)


def _members(annotation: Any) -> list:
    annotation = _unwrap(annotation)
    if _is_union(annotation):
        return [m for m in get_args(annotation) if _unwrap(m) is not type(None)]
    return [annotation]


def _models(annotation: Any) -> list[type[BaseModel]]:
    found = [_unwrap(m) for m in _members(annotation)] if annotation is not None else []
    return [m for m in found if isinstance(m, type) and issubclass(m, BaseModel)]


def _literals(annotation: Any) -> tuple:
    annotation = _unwrap(annotation)
    return get_args(annotation) if get_origin(annotation) is Literal else ()


def _tags(annotation: Any, field: str) -> list[str]:
    return [
        tag
        for m in _models(annotation)
        if field in m.model_fields
        for tag in _literals(m.model_fields[field].annotation)
    ]


def _element(annotation: Any, index: int) -> Any:
    members = _members(annotation)
    sequence = _unwrap(members[0]) if len(members) == 1 else None
    if get_origin(sequence) is not tuple:
        return None
    args = get_args(sequence)
    if len(args) == 2 and args[1] is Ellipsis:
        return args[0]
    return args[index] if index < len(args) else None
