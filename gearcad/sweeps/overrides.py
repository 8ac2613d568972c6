"""A sweep's point applied to its profile's data (:func:`overridden`), as the profile reader's
``apply_overrides`` would, copying only the tables an override's path crosses."""

from __future__ import annotations

from typing import Any

from ..errors import ProfileError
from ..profiles.reading import EXCLUSIVE_KEYS

__all__ = ["overridden"]

_PARTNER = {a: b for pair in EXCLUSIVE_KEYS for a, b in (pair, pair[::-1])}


def overridden(data: dict, overrides: dict[str, Any]) -> dict:
    """What ``apply_overrides(data, overrides)`` gives for a sweep's point, without copying the
    whole profile for every design: only the tables on an override's path are copied (a profile
    of 100,000 sampled radii is not), and ``data`` is not walked again (it was, once, as the
    sweep began).  The values are plain numbers, true/false or text, checked as the sweep began.
    """
    result = dict(data)
    fresh = {id(result)}  # the tables copied for this design: set into freely

    def table(node: dict, part: str, make: bool) -> Any:
        child = node.get(part)
        if child is None and make:
            child = node[part] = {}
            fresh.add(id(child))
        elif isinstance(child, dict) and id(child) not in fresh:
            child = node[part] = dict(child)
            fresh.add(id(child))
        return child

    for key, value in overrides.items():
        parts = key.split(".")
        node: Any = result
        for depth, part in enumerate(parts[:-1], 1):
            node = table(node, part, make=True)
            if not isinstance(node, dict):
                raise ProfileError(f"override {key!r}: {'.'.join(parts[:depth])} is not a table")
        node[parts[-1]] = value
        partner = _PARTNER.get(key)
        if partner is not None:
            *path, last = partner.split(".")
            node = result
            for part in path:
                node = table(node, part, make=False) if isinstance(node, dict) else None
            if isinstance(node, dict):
                node.pop(last, None)
    name, title = result.get("name"), result.get("title")
    if "name" in overrides and "title" not in overrides and isinstance(name, str) and isinstance(title, str) and title:
        result["title"] = f"{title} ({name})"  # as apply_overrides: a variant must not look like the original
    return result
