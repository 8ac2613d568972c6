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

__all__ = ["SHARED", "compact", "assemble", "product_head"]

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


_LINE = re.compile(r"^#(\d+)=([A-Z_0-9]*)(.*);$", re.M)
"""A compacted file's entity: its number, its type (empty for a complex entity), the rest."""


def product_head(name: str) -> list[str]:
    """Entities #1–#9 of a file of one product ``name``, as OpenCASCADE writes them: the
    protocol, the product and its definition, whose shape representation is #10."""
    return [
        "#1=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#2);",
        "#2=APPLICATION_CONTEXT('core data for automotive mechanical design processes');",
        "#3=SHAPE_DEFINITION_REPRESENTATION(#4,#10);",
        "#4=PRODUCT_DEFINITION_SHAPE('','',#5);",
        "#5=PRODUCT_DEFINITION('design','',#6,#9);",
        "#6=PRODUCT_DEFINITION_FORMATION('','',#7);",
        f"#7=PRODUCT('{name}','{name}','',(#8));",
        "#8=PRODUCT_CONTEXT('',#2,'mechanical');",
        "#9=PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design');",
    ]


def assemble(parts: dict[str, str], placements: list[tuple[str, float, float, float]]) -> str:
    """The assembly file of the parts' files as written (``parts``: name → compacted STEP text
    of one product, one shape representation), each placed as ``placements`` says — (part, angle
    about z in rad, x, y in mm), in order: the entities OpenCASCADE's assembly writer writes
    (the assembly's product and shape representation, each part's file under it, and per
    placement a CONTEXT_DEPENDENT_SHAPE_REPRESENTATION with an ITEM_DEFINED_TRANSFORMATION and a
    NEXT_ASSEMBLY_USAGE_OCCURRENCE numbered 1, 2, …), made from text: no solid transferred again.
    A part whose file is an earlier one's but for its name refers to that one's geometry
    (:data:`SHARED`): its own vertices, edges, faces and product only."""
    lines: list[str] = [
        *product_head("assembly"),
        "",  # #10, the assembly's shape representation: its items are the placements below
        "#11=AXIS2_PLACEMENT_3D('',#12,#13,#14);",
        "#12=CARTESIAN_POINT('',(0.,0.,0.));",
        "#13=DIRECTION('',(0.,0.,1.));",
        "#14=DIRECTION('',(1.,0.,0.));",
        "#15=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#7));",
    ]
    count = len(lines)
    head = ""
    known: dict[str, tuple[int, int, int, int]] = {}  # part: its definition, representation, origin, context
    alike: dict[str, dict[int, int]] = {}  # a part's file without its name: its entities' numbers here
    for name, text in parts.items():
        head = head or text.partition("DATA;\n")[0]
        data = text.partition("DATA;\n")[2].partition("ENDSEC;\nEND-ISO")[0]
        entities = _LINE.findall(data)
        earlier = alike.get(text.replace(f"'{name}'", "''"))
        new: dict[int, int] = {}
        kept = []
        for number, kind, rest in entities:
            n = int(number)
            if kind in ("APPLICATION_PROTOCOL_DEFINITION", "APPLICATION_CONTEXT"):
                new[n] = 2  # the assembly's (nothing refers to the protocol definition)
            elif earlier is not None and kind in SHARED:
                new[n] = earlier[n]
            else:
                count += 1
                new[n] = count
                kept.append(f"#{number}={kind}{rest};")
        lines.append(_TOKEN.sub(lambda m: f"#{new[int(m[1])]}" if m[1] else m[0], "\n".join(kept)))
        alike.setdefault(text.replace(f"'{name}'", "''"), new)
        bodies = {int(n): (kind, rest) for n, kind, rest in entities}
        sdr = next(rest for _, kind, rest in entities if kind == "SHAPE_DEFINITION_REPRESENTATION")
        definition = next(int(n) for n, kind, _ in entities if kind == "PRODUCT_DEFINITION")
        representation = [int(m[1]) for m in _TOKEN.finditer(sdr) if m[1]][1]
        refs = [int(m[1]) for m in _TOKEN.finditer(bodies[representation][1]) if m[1]]
        known[name] = (new[definition], new[representation], new[refs[0]], new[refs[-1]])
    items = []
    for k, (name, angle, x, y) in enumerate(placements):
        definition, representation, origin, _ = known[name]
        n = count + 1  # the placement's point, direction and axes; the representation in context,
        # its relation, transformation, shape and occurrence
        lines += [
            f"#{n}=CARTESIAN_POINT('',({_real(x)},{_real(y)},0.));",
            f"#{n + 1}=DIRECTION('',({_real(math.cos(angle))},{_real(math.sin(angle))},0.));",
            f"#{n + 2}=AXIS2_PLACEMENT_3D('',#{n},#13,#{n + 1});",
            f"#{n + 3}=CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{n + 4},#{n + 6});",
            f"#{n + 4}=( REPRESENTATION_RELATIONSHIP('','',#{representation},#10) "
            f"REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{n + 5}) SHAPE_REPRESENTATION_RELATIONSHIP() );",
            f"#{n + 5}=ITEM_DEFINED_TRANSFORMATION('','',#{origin},#{n + 2});",
            f"#{n + 6}=PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{n + 7});",
            f"#{n + 7}=NEXT_ASSEMBLY_USAGE_OCCURRENCE('{k + 1}','{name}','',#5,#{definition},$);",
        ]
        items.append(n + 2)
        count += 8
    context = next(iter(known.values()))[3]
    lines[9] = f"#10=SHAPE_REPRESENTATION('',({','.join(f'#{n}' for n in [11, *items])}),#{context});"
    head = re.sub(r"FILE_NAME\('(?:[^']|'')*'", "FILE_NAME('assembly'", head, count=1)
    return head + "DATA;\n" + "\n".join(lines) + "\nENDSEC;\nEND-ISO-10303-21;\n"
