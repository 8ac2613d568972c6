"""A STEP file's text made smaller without changing what it describes: geometric entities that
are the same (a direction (0, 0, 1) written for every placement, a circle's centre written again
for its cylinder, the unit vector of every vertical line) written once and referred to from
every place, entities numbered #1, #2, … in the order OpenCASCADE wrote them, no blanks around
``=`` and no line breaks inside an entity.  Topology (vertices, edges, loops, faces) is never
merged: only points, directions, vectors, placements, curves and surfaces, which STEP lets any
number of entities share.  Pure text: no OpenCASCADE here."""

from __future__ import annotations

import re

__all__ = ["SHARED", "compact"]

SHARED = frozenset(
    {
        "CARTESIAN_POINT",
        "DIRECTION",
        "VECTOR",
        "AXIS2_PLACEMENT_3D",
        "LINE",
        "CIRCLE",
        "PLANE",
        "CYLINDRICAL_SURFACE",
        "CONICAL_SURFACE",
        "B_SPLINE_CURVE_WITH_KNOTS",
        "B_SPLINE_SURFACE_WITH_KNOTS",
    }
)
"""The entity types written once where several are the same (their references made the same
first): geometry only."""

_LEVELS = (
    ("CARTESIAN_POINT", "DIRECTION"),
    ("VECTOR", "AXIS2_PLACEMENT_3D", "B_SPLINE_CURVE_WITH_KNOTS", "B_SPLINE_SURFACE_WITH_KNOTS"),
    ("LINE", "CIRCLE", "PLANE", "CYLINDRICAL_SURFACE", "CONICAL_SURFACE"),
)
""":data:`SHARED` by what they refer to: each level only to the levels before it (a point or
direction to nothing, a placement to points and directions, a circle to a placement), so that
one pass a level finds every equal pair."""

_TOKEN = re.compile(r"'(?:[^']|'')*'|#(\d+)")
"""A quoted string (left as it is: 'Context #1' is no reference) or a reference #n."""
_NEGATIVE_ZERO = re.compile(r"(?<=[(,])-0\.(?=[,)])")
_WRAP = re.compile(r"\n(?!#)[ ]*")
"""OpenCASCADE's line breaks inside an entity (the next line does not start a new one)."""


def compact(text: str) -> str:
    """``text`` (a STEP file as OpenCASCADE writes it) with equal geometric entities shared and
    the entities renumbered densely; the same input gives the same output."""
    head, sep, rest = text.partition("DATA;\n")
    data, sep2, tail = rest.partition("ENDSEC;\nEND-ISO")
    if not sep or not sep2:
        return text  # not the layout expected: left as written
    numbers, texts, kinds = [], {}, {}
    for line in _WRAP.sub("", data).splitlines():
        number, _, body = line.partition(" = ")
        if not number.startswith("#") or not body.endswith(";"):
            return text
        n = int(number[1:])
        numbers.append(n)
        texts[n] = body[:-1]
        kinds[n] = body.partition("(")[0]
    alias: dict[int, int] = {}

    def follow(m: re.Match) -> str:
        return f"#{alias.get(int(m[1]), int(m[1]))}" if m[1] else m[0]

    for level in _LEVELS:
        seen: dict[str, int] = {}
        for n in numbers:
            if kinds[n] in level:
                body = _TOKEN.sub(follow, texts[n]) if "#" in texts[n] else texts[n]
                if "-0." in body:
                    body = _NEGATIVE_ZERO.sub("0.", body)
                texts[n] = body
                first = seen.setdefault(body, n)
                if first != n:
                    alias[n] = first
    kept = [n for n in numbers if n not in alias]
    renumber = {str(n): f"#{k + 1}" for k, n in enumerate(kept)}
    renumber.update({str(n): renumber[str(first)] for n, first in alias.items()})
    body = "".join([f"#{n}={texts[n]};\n" for n in kept])  # renumbered in one pass over the text
    body = _TOKEN.sub(lambda m: renumber[m[1]] if m[1] else m[0], body)
    return head + sep + body + sep2 + tail
