"""A STEP file's text made smaller without changing what it describes: geometric entities that
are the same (a direction (0, 0, 1) written for every placement, a circle's centre written again
for its cylinder, the unit vector of every vertical line) written once and referred to from
every place, entities numbered #1, #2, … in the order OpenCASCADE wrote them, no blanks around
``=`` and no line breaks inside an entity.  Topology (vertices, edges, loops, faces) is never
merged: only points, directions, vectors, placements, curves and surfaces, which STEP lets any
number of entities share.  Pure text: no OpenCASCADE here."""

from __future__ import annotations

import math
import re

__all__ = ["SHARED", "compact", "assemble"]

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
        number, _, body = line.partition("=")  # "#1 = …" as OpenCASCADE writes it, "#1=…" as here
        number, body = number.strip(), body.strip()
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


def _real(x: float) -> str:
    """A STEP real: a decimal point always, an upper-case exponent, no negative zero."""
    text = repr(float(x) + 0.0)
    mantissa, _, exponent = text.partition("e")
    if "." not in mantissa:
        mantissa += "."
    mantissa = mantissa.rstrip("0") if mantissa.endswith("0") and "." in mantissa else mantissa
    out = mantissa + (f"E{exponent}" if exponent else "")
    return "0." if out in ("-0.", "0.") else out


def _entities(text: str) -> tuple[str, list[tuple[int, str]]]:
    """A compacted STEP file's header (its text up to ``DATA;``) and its entities (number, body
    without the ``;``), in the file's order."""
    head, _, rest = text.partition("DATA;\n")
    data = rest.partition("ENDSEC;\nEND-ISO")[0]
    out = []
    for line in data.splitlines():
        number, _, body = line.partition("=")
        out.append((int(number.strip()[1:]), body.strip()[:-1]))
    return head, out


def _refs(body: str) -> list[int]:
    return [int(m[1]) for m in _TOKEN.finditer(body) if m[1]]


def assemble(parts: dict[str, str], placements: list[tuple[str, float, float, float]]) -> str:
    """The assembly file of the parts' files as written (``parts``: name → compacted STEP text
    of one product, one shape representation), each placed as ``placements`` says — (part, angle
    about z in rad, x, y in mm), in order: the entities OpenCASCADE's assembly writer writes
    (the assembly's product and shape representation, each part's file under it, and per
    placement a CONTEXT_DEPENDENT_SHAPE_REPRESENTATION with an ITEM_DEFINED_TRANSFORMATION and a
    NEXT_ASSEMBLY_USAGE_OCCURRENCE numbered 1, 2, …), made from text: no solid transferred again."""
    lines: list[str] = []
    count = 0

    def add(body: str) -> int:
        nonlocal count
        count += 1
        lines.append(f"#{count}={body};")
        return count

    first_head = None
    # the assembly's own product; its shape representation (#10) is written once the placements
    # are known, its context is the first part's
    add("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#2)")
    add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')")
    add("SHAPE_DEFINITION_REPRESENTATION(#4,#10)")
    add("PRODUCT_DEFINITION_SHAPE('','',#5)")
    add("PRODUCT_DEFINITION('design','',#6,#9)")
    add("PRODUCT_DEFINITION_FORMATION('','',#7)")
    add("PRODUCT('assembly','assembly','',(#8))")
    add("PRODUCT_CONTEXT('',#2,'mechanical')")
    add("PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design')")
    add("SHAPE_REPRESENTATION")  # #10: filled in below
    origin = add("AXIS2_PLACEMENT_3D('',#12,#13,#14)")
    add("CARTESIAN_POINT('',(0.,0.,0.))")
    add("DIRECTION('',(0.,0.,1.))")
    add("DIRECTION('',(1.,0.,0.))")
    add("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#7))")
    known: dict[str, tuple[int, int, int, int]] = {}  # part: its definition, representation, origin, context
    for name, text in parts.items():
        head, entities = _entities(text)
        first_head = first_head or head
        kinds = {n: body.partition("(")[0] for n, body in entities}
        dropped = {n for n, k in kinds.items() if k in ("APPLICATION_PROTOCOL_DEFINITION", "APPLICATION_CONTEXT")}
        new = {n: (2 if kinds[n] == "APPLICATION_CONTEXT" else 0) for n in dropped}
        for n, _ in entities:
            if n not in dropped:
                count += 1
                new[n] = count
        for n, body in entities:
            if n not in dropped:
                lines.append(f"#{new[n]}={_TOKEN.sub(lambda m: f'#{new[int(m[1])]}' if m[1] else m[0], body)};")
        sdr = next(body for n, body in entities if kinds[n] == "SHAPE_DEFINITION_REPRESENTATION")
        pds = next(n for n, _ in entities if kinds[n] == "PRODUCT_DEFINITION")
        rep = _refs(sdr)[1]
        rep_refs = _refs(dict(entities)[rep])
        known[name] = (new[pds], new[rep], new[rep_refs[0]], new[rep_refs[-1]])
    items = []
    for k, (name, angle, x, y) in enumerate(placements):
        pd, rep, part_origin, _ = known[name]
        c, s = math.cos(angle), math.sin(angle)
        point = add(f"CARTESIAN_POINT('',({_real(x)},{_real(y)},0.))")
        ref = add(f"DIRECTION('',({_real(c)},{_real(s)},0.))")
        placed = add(f"AXIS2_PLACEMENT_3D('',#{point},#13,#{ref})")
        items.append(placed)
        n = count + 1  # the representation in context, its relation, transformation, shape, occurrence
        add(f"CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{n + 1},#{n + 3})")
        add(
            f"( REPRESENTATION_RELATIONSHIP('','',#{rep},#10) "
            f"REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{n + 2}) SHAPE_REPRESENTATION_RELATIONSHIP() )"
        )
        add(f"ITEM_DEFINED_TRANSFORMATION('','',#{part_origin},#{placed})")
        add(f"PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{n + 4})")
        add(f"NEXT_ASSEMBLY_USAGE_OCCURRENCE('{k + 1}','{name}','',#5,#{pd},$)")
    context = next(iter(known.values()))[3]
    lines[9] = f"#10=SHAPE_REPRESENTATION('',({','.join(f'#{n}' for n in [origin, *items])}),#{context});"
    head = re.sub(r"FILE_NAME\('(?:[^']|'')*'", "FILE_NAME('assembly'", first_head or "", count=1)
    return compact(head + "DATA;\n" + "\n".join(lines) + "\nENDSEC;\nEND-ISO-10303-21;\n")
