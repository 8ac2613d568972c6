"""The profile reference (docs/reference.md), written from the profiles' JSON Schema.

Every key a profile may hold comes from :func:`~gearcad.profiles.profile_schema`, so the page
cannot drift from what gearcad accepts: a key added to a model appears here once the page is
regenerated, and a test fails until it is::

    python3 -m gearcad.profiles.reference docs/reference.md
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from pathlib import Path

__all__ = ["schema_keys", "reference_markdown", "main"]

_MECHANISM_TITLES = {
    "gear-pair": "Gear pairs (the default: `mechanism` left out)",
    "roller-body": 'Roller bodies (`mechanism = "roller-body"`)',
    "rolling-wheel": 'Rolling wheel (`mechanism = "rolling-wheel"`)',
    "carrier-train": 'Carrier trains (`mechanism = "carrier-train"`)',
}


def _resolve(schema: dict, node: dict) -> dict:
    while "$ref" in node:
        target = schema["$defs"][node["$ref"].rsplit("/", 1)[1]]
        node = {**target, **{k: v for k, v in node.items() if k != "$ref"}}
    return node


def _variants(schema: dict, node: dict) -> list[tuple[str, dict]]:
    """A field that is one of several tables told apart by a key (``gear1.curve``)."""
    mapping = node.get("discriminator", {}).get("mapping", {})
    by_ref = {ref: tag for tag, ref in mapping.items()}
    return [(by_ref.get(v.get("$ref"), ""), _resolve(schema, v)) for v in node.get("oneOf", ())]


def _rows(schema: dict, table: dict, prefix: str) -> Iterator[tuple[str, dict]]:
    """``(dotted key, field schema)`` for every key of ``table``, tables opened in place."""
    for key, raw in table.get("properties", {}).items():
        field = _resolve(schema, raw)
        dotted = f"{prefix}{key}"
        if field.get("type") == "object" and "properties" in field:
            yield dotted, {**field, "_table": True}
            yield from _rows(schema, field, dotted + ".")
        elif "oneOf" in field and all("properties" in v for _, v in _variants(schema, field)):
            yield dotted, {**field, "_table": True}
            yield from _variant_rows(schema, field, dotted + ".")
        else:
            yield dotted, field


def _variant_rows(schema: dict, field: dict, prefix: str) -> Iterator[tuple[str, dict]]:
    """The keys of a table that takes one of several forms: the key that tells them apart
    (with every form it names), the keys all forms share, then each form's own keys."""
    tag_key = field.get("discriminator", {}).get("propertyName")
    variants = [(tag, dict(_rows(schema, v, prefix))) for tag, v in _variants(schema, field)]
    shared = set.intersection(*(set(rows) for _, rows in variants)) if variants else set()
    shared = {k for k in shared if len({json.dumps(rows[k], sort_keys=True) for _, rows in variants}) == 1}
    if tag_key:
        tags = [tag for tag, _ in variants]
        yield prefix + tag_key, {"enum": tags, "description": f"Which form the table takes: {', '.join(tags)}."}
    for key, sub in variants[0][1].items() if variants else ():
        if key in shared:
            yield key, sub
    for tag, rows in variants:
        for key, sub in rows.items():
            if key not in shared and key != prefix + tag_key:
                yield key, {**sub, "_when": tag}


def schema_keys(schema: dict) -> dict[str, list[str]]:
    """``{mechanism: [dotted key, …]}`` of every key the schema allows (tables included)."""
    keys = {}
    for ref in schema["oneOf"]:
        root = _resolve(schema, ref)
        mechanism = root["properties"]["mechanism"]["const"]
        keys[mechanism] = list(dict.fromkeys(key for key, _ in _rows(schema, root, "")))
    return keys


def _allowed(field: dict) -> str:
    """What a value may be, read from the schema's constraints."""
    if "const" in field:
        return f"`{json.dumps(field['const'])}`"
    if "enum" in field:
        return " / ".join(f"`{json.dumps(v)}`" for v in field["enum"])
    if "anyOf" in field or "oneOf" in field:
        return " or ".join(_allowed(v) for v in field.get("anyOf", field.get("oneOf", ())))
    kind = field.get("type", "")
    bounds = [
        f"{sign} {field[name]:g}"
        for name, sign in (("minimum", "≥"), ("exclusiveMinimum", ">"), ("maximum", "≤"), ("exclusiveMaximum", "<"))
        if name in field
    ]
    if kind == "array":
        items = field.get("items") or field.get("prefixItems") or {}
        kinds = [_allowed(i) for i in ([items] if isinstance(items, dict) else items)]
        inner = kinds[0] if len(set(kinds)) == 1 else "; ".join(kinds)
        low, high = field.get("minItems", 0), field.get("maxItems")
        size = f"{low}" if low == high else f"{low}–{high}" if high else f"{low} or more" if low else "any number"
        return f"list ({size}) of {inner}"
    if kind == "string" and "maxLength" in field:
        bounds.append(f"{field.get('minLength', 0)}–{field['maxLength']} characters")
    return " ".join(filter(None, [kind, ", ".join(bounds)])) or "any"


def _cell(text: str) -> str:
    return " ".join(text.replace("|", "\\|").split())


def _default(field: dict) -> str:
    if "default" not in field or field.get("_table"):
        return ""
    value = field["default"]
    return "" if value in (None, "") else f"`{json.dumps(value, ensure_ascii=False)}`"


def reference_markdown(schema: dict | None = None) -> str:
    """The reference page: one table per mechanism, one row per key."""
    if schema is None:
        from .reading import profile_schema

        schema = profile_schema()
    lines = [
        "# Profile reference",
        "",
        "<!-- Generated from the profiles' JSON Schema by "
        "`python3 -m gearcad.profiles.reference docs/reference.md`; do not edit by hand. -->",
        "",
        schema.get("description", ""),
        "",
        "Every key of every mechanism, with the values it takes and its default (an empty default: the",
        "key may be left out, or the table is required). `gearcad schema` prints the same as JSON",
        "Schema for TOML editors. Keys under a curve (`gear1.a`, …) apply when `gear1.curve` names it.",
    ]
    for ref in schema["oneOf"]:
        root = _resolve(schema, ref)
        mechanism = root["properties"]["mechanism"]["const"]
        lines += ["", f"## {_MECHANISM_TITLES.get(mechanism, mechanism)}", "", _cell(root.get("description", ""))]
        lines += ["", "| key | allowed | default | meaning |", "|---|---|---|---|"]
        for key, field in _rows(schema, root, ""):
            allowed = "table" if field.get("_table") else _cell(_allowed(field))
            when = f'(`curve = "{field["_when"]}"`) ' if field.get("_when") else ""
            meaning = _cell(when + field.get("description", ""))
            lines.append(f"| `{key}` | {allowed} | {_default(field)} | {meaning} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Write the page to the file given (or print it); ``--help`` is help, never a file name."""
    import argparse

    parser = argparse.ArgumentParser(
        prog="python3 -m gearcad.profiles.reference", description="Write the profile reference page (Markdown)."
    )
    parser.add_argument("page", nargs="?", type=Path, help="the file to write (default: print the page)")
    page = parser.parse_args(argv).page
    text = reference_markdown()
    if page is None:
        sys.stdout.write(text)
    else:
        try:
            page.write_text(text, encoding="utf-8")
        except OSError as exc:  # a folder, a missing folder, no permission: one line, exit 2
            sys.stderr.write(f"{parser.prog}: error: cannot write {page}: {exc.strerror or exc}\n")
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
