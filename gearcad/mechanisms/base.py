"""What every mechanism's ``design(params)`` returns: one :class:`Design` with the same blocks.

The exporters write a design and nothing else; ``gearcad check`` prints it; report.json is
``design.report(files)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import numpy as np

from ..errors import ChecksFailed
from ..findings import Finding, check_codes, failing
from .chart_data import Blocks, Charts
from .parts import Part, Placement

if TYPE_CHECKING:
    from ..teeth.helical import GearSections

__all__ = [
    "SCHEMA_VERSION",
    "Assembly",
    "Design",
    "Motion",
    "Table",
    "assembly_depth",
    "assembly_gap",
    "assembly_overlap",
    "finite",
]

SCHEMA_VERSION = 2
"""report.json's schema: 2 gave every mechanism the same parts[], assembly, warnings and files blocks."""


@dataclass(frozen=True)
class Motion:
    """The assembly in motion over one cycle: each row of ``angles`` (frames, parts) turns the
    parts named in ``parts`` about their placed pivots (rad, added to the placement's angle).  A
    name placed several times (a set's planets) is listed once per placement, in the placements'
    order."""

    parts: tuple[str, ...]
    angles: np.ndarray
    pivots: np.ndarray | None = None
    """(frames, parts, 2): where each part's pivot is at each frame (mm), for parts whose pivots
    move (a carrier-less set's planets); None: the placements' pivots throughout."""


@dataclass(frozen=True)
class Table:
    """A CSV table: column names and rows (n, columns) of floats."""

    file: str
    columns: tuple[str, ...]
    rows: np.ndarray


@dataclass(frozen=True)
class Assembly:
    """The interference proof of the parts as assembled (mm²): neighbours overlap by at most
    ``allowed``, and turned a little (``nudged``, None where not measured) they do touch."""

    overlap: float
    allowed: float
    nudged: float | None = None
    positions: int = 1
    depth: float | None = None
    """Largest penetration depth of neighbours as assembled, mm (None where not measured)."""
    allowed_depth: float | None = None
    gap: float | None = None
    """Widest gap of the rolling contacts as assembled, mm (None where none rolls)."""
    allowed_gap: float | None = None
    proven: bool = False
    """Whether the depth holds between the positions measured too: every mesh's band proven to fit
    (the theorem keeps the made worst case free at every driver angle, docs/fit.md; the drawn
    outlines lie inside it, so they bite no deeper than the allowance anywhere)."""

    @property
    def fits(self) -> bool:
        deep = self.depth is not None and self.allowed_depth is not None and self.depth > self.allowed_depth
        apart = self.gap is not None and self.allowed_gap is not None and self.gap > self.allowed_gap
        bites = self.nudged is None or self.nudged > self.allowed
        return self.overlap <= self.allowed and bites and not deep and not apart

    def as_dict(self) -> dict:
        return {
            "overlap": self.overlap,
            "allowed_overlap": self.allowed,
            "nudged_min_overlap": self.nudged,
            "positions": self.positions,
            "max_depth": self.depth,
            "allowed_depth": self.allowed_depth,
            "depth_proven": self.proven,
            **({"gap": self.gap, "allowed_gap": self.allowed_gap} if self.gap is not None else {}),
            "fits": self.fits,
        }


def assembly_overlap(parts: dict[str, Part], placements: list[Placement], pairs) -> float:
    """The largest overlap area (mm²) of the placed parts named in ``pairs`` ((i, j) indices)."""
    polygons = [parts[p.part].outline.polygon(p.angle, p.offset) for p in placements]
    return max((float(polygons[i].intersection(polygons[j]).area) for i, j in pairs), default=0.0)


def assembly_depth(parts: dict[str, Part], placements: list[Placement], pairs, *, step: float) -> float:
    """The largest penetration depth (mm) of the placed parts named in ``pairs``."""
    from ..geometry.depth import overlap_depths

    polygons = [parts[p.part].outline.polygon(p.angle, p.offset) for p in placements]
    first, second = zip(*((polygons[i], polygons[j]) for i, j in pairs)) if pairs else ((), ())
    return float(max(overlap_depths(first, second, step=step).depth, default=0.0))


def assembly_gap(parts: dict[str, Part], placements: list[Placement], pairs) -> float:
    """The widest gap (mm) between the placed parts named in ``pairs`` (0 where they touch)."""
    polygons = [parts[p.part].outline.polygon(p.angle, p.offset) for p in placements]
    return max((float(polygons[i].distance(polygons[j])) for i, j in pairs), default=0.0)


def finite(value):
    """JSON has no NaN or infinity: such a value becomes null (and numpy scalars plain floats)."""
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v) for v in value]
    return value


D = TypeVar("D")


@dataclass(frozen=True)
class Design(Generic[D]):
    """A checked mechanism: its parts and assembly, findings, report data and what to draw.

    ``data`` holds the mechanism's own report blocks (JSON-ready); ``detail`` the mechanism's
    own computed objects (for charts, and for users who want more than the report; ``Design[D]``:
    ``D`` its type, ``GearPairDetail``, ``RollerBodyDetail``, …).
    """

    params: Any
    mechanism: str
    summary: str
    findings: tuple[Finding, ...]
    part_list: tuple[Part, ...]
    placements: tuple[Placement, ...]
    assembly: Assembly
    data: Blocks
    units: dict[str, str]
    detail: D | None = None
    details: tuple[str, ...] = ()
    """More lines for ``gearcad check``, after the summary."""
    motion: Motion | None = None
    tables: tuple[Table, ...] = ()
    sheet: tuple[Placement, ...] = ()
    """Every placed part laid out flat on ``output.sheet`` (when DXF or SVG is written)."""
    plates: tuple[tuple[Placement, ...], ...] = ()
    """The placed parts laid out on as many printer beds (``output.bed``) as they need, when a
    chosen format writes plates (3MF): ``plate.3mf``, ``plate-2.3mf``, …  A part too large for
    the bed is on none (a ``bed`` finding names it)."""
    sections: dict[str, GearSections] = field(default_factory=dict)
    """Part name → its twisted sections (``teeth.helical.GearSections``): such a part's solid
    is lofted through them instead of extruded."""
    bands: dict[str, float] = field(default_factory=dict)
    """Part name → the angle u (rad, in the part's frame) of the line through its pivot about which
    its upper half is its lower half mirrored: such a part's solid is two stacked straight bands,
    the outline from z = 0 to half the thickness and its mirror image (the outline turned over) above
    (:func:`mirrored_outline`).  Its plate holds the assembly as placed (printed in place)."""
    made: dict = field(default_factory=dict, compare=False)
    """Part name → its cut rings fitted without the kerf (the part itself, for its exact solid),
    made when STEP is written with ``output.kerf`` > 0; see :meth:`made_rings`."""
    charts: Charts = field(default_factory=dict)
    """Chart name → the data it is drawn from, computed with the design (exporters only draw)."""
    placed: str = "meshing parts touch"
    """What the assembly drawing shows, in the page's words (how the parts are placed)."""
    seconds: float = field(default=0.0, compare=False)
    stage: str = "full"
    """How far the design went: ``pitch`` and ``teeth`` (gear pairs only) have no parts, no
    assembly and no files — their reports hold only what those stages compute."""

    @property
    def name(self) -> str:
        return self.params.name

    @property
    def plate(self) -> tuple[Placement, ...]:
        """The first printer bed's placements (``plate.3mf``); () when nothing is laid out."""
        return self.plates[0] if self.plates else ()

    def plate_files(self) -> tuple[str, ...]:
        """The plates' file stems, one per bed: ``plate``, ``plate-2``, …"""
        return tuple("plate" if k == 0 else f"plate-{k + 1}" for k in range(len(self.plates)))

    def parts(self) -> tuple[Part, ...]:
        """Every part once (the assembly may place a part several times)."""
        return self.part_list

    def part(self, name: str) -> Part:
        return next(p for p in self.part_list if p.name == name)

    def made_rings(self, name: str) -> tuple:
        """The part's cut rings as the part itself is (no kerf: what a solid of it is), lines and
        arcs within the tolerance of the exact outline, outer first."""
        if name in self.made:
            return self.made[name]
        if self.params.output.kerf > 0:
            raise ValueError(f"{name}: the rings without kerf are made only with 'step' in output.formats")
        return self.part(name).cut

    def failures(self, allow=()) -> tuple[Finding, ...]:
        """The findings that fail a check (``findings.ERRORS``), but those whose code is in
        ``allow``; an assembly that does not fit fails as "interference" even unreported."""
        found = list(failing(self.findings, allow))
        unfit = self.assembly is not None and not self.assembly.fits  # a stage before "full" proves none
        if unfit and "interference" not in allow and not any(f.code == "interference" for f in found):
            found.append(Finding("interference", f"the parts overlap by {self.assembly.overlap:.4g} mm² as assembled"))
        return tuple(found)

    @property
    def ok(self) -> bool:
        """No failing finding: the design (and, with a process, the made parts) moves."""
        return not self.failures()

    def raise_failures(self, allow=()) -> Design:
        """This design, or :class:`~gearcad.errors.ChecksFailed` listing each failing finding."""
        found = self.failures(check_codes(allow))
        if found:
            lines = "\n".join(f"{self.name}: [{f.code}] {f.message}" for f in found)
            raise ChecksFailed(lines, found)
        return self

    def report(self, files: dict | None = None) -> dict:
        """The report as a JSON-ready dict (README, "report.json"): no NaN, no infinity."""
        p, out = self.params, self.params.output
        placed = {pl.part: pl for pl in reversed(self.placements)}
        parts = [
            {
                "name": part.name,
                "area": part.outline.area,
                "vertices": part.outline.vertex_count,
                "holes": len(part.outline.rings) - 1,
                "cut_vertices": part.cut_vertices,
                "pivot": {"marked_by": part.pivot, "diameter": part.pivot_diameter, "cross": part.pivot_mark},
                "placement": {"angle": placed[part.name].angle, "offset": list(placed[part.name].offset)},
            }
            for part in self.part_list
        ]
        # each gear's entry names its part: area, vertices and holes as in parts[]
        own = {e["name"]: {k: e[k] for k in ("area", "vertices", "holes")} for e in parts}
        data = dict(self.data)
        if "gears" in data:
            data["gears"] = [{**g, "part": own[g["name"]]} if g.get("name") in own else g for g in data["gears"]]
        report = {
            "schema": SCHEMA_VERSION,
            "name": p.name,
            "title": p.title,
            "mechanism": self.mechanism,
            "summary": self.summary,
            "units": self.units,
            "stage": self.stage,
            "tolerance": out.tolerance,
            **data,
            "parts": parts,
            "assembly": self.assembly.as_dict() if self.assembly is not None else None,
            "output": {
                "thickness": out.thickness,
                "chamfer": out.chamfer,
                "kerf": out.kerf,
                "dxf": out.dxf,
                "formats": list(out.formats),
                "layers": {"cut": out.cut_layer, "mark": out.mark_layer},
            },
            "warnings": [f.as_dict() for f in self.findings],
            "ok": self.ok,
            "files": dict(files or {}),
        }
        if self.stage != "full":  # nothing was cut, placed or written
            for key in ("parts", "assembly", "output", "files"):
                del report[key]
            return finite(report)
        if hasattr(p, "bore"):
            report["output"]["bore"] = {
                k: getattr(p.bore, k) for k in ("diameter", "keyway_width", "keyway_depth", "flat", "pilot")
            }
        return finite(report)
