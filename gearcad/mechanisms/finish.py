"""The one finishing line: any mechanism's :class:`Draft` made into the complete :class:`Design`.

A mechanism draws only what is its own — its parts' rings, where they sit, which of them touch,
its report blocks, findings and chart data — and :func:`finish` does the rest the same way for
every mechanism, in one pass: make the parts and cut their paths, prove the assembly with one
overlap and nudge policy (:class:`~gearcad.tolerances.Budget`), lay out the sheet and the plate,
and build the :class:`Design` whole.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import numpy as np

from ..findings import Finding, finding
from ..formats import TABLE
from ..tolerances import budget
from . import layouts
from .base import Assembly, Design, Motion, Table, assembly_depth, assembly_gap, assembly_overlap
from .chart_data import Blocks, Charts
from .parts import Blank, BoreSpec, CutSpec, Part, Placement, cut_paths, make_part
from .registry import MECHANISMS

if TYPE_CHECKING:
    from ..teeth.helical import GearSections

__all__ = ["Contact", "Draft", "PartSpec", "Proof", "TOUCHES", "finish", "prove"]


@dataclass(frozen=True)
class PartSpec:
    """A part as its mechanism draws it, pivot at the origin: rings sampled at the budget's fine
    tolerance ((n, 2) float, mm) — the outer ring counter-clockwise; ``hole`` a given inner ring
    (clockwise) instead of the bore; ``marks`` closed rings to engrave; ``bore`` the shaft hole,
    leaving ``wall`` mm to the outline."""

    name: str
    outer: np.ndarray
    bore: BoreSpec | None = None
    wall: float = 0.0
    marks: tuple[np.ndarray, ...] = ()
    hole: np.ndarray | None = None
    caps: tuple[np.ndarray, ...] = ()
    """Other outer rings of the solid's end faces the chamfer must fit (a twisted gear's end sections)."""

    def blank(self, output: CutSpec) -> Blank:
        """The part made from this spec (:func:`~.parts.make_part`), before its cut paths."""
        return make_part(
            self.name,
            self.outer,
            output=output,
            bore=self.bore,
            wall=self.wall,
            marks=self.marks,
            hole=self.hole,
            caps=self.caps,
        )


TOUCHES = ("mesh", "rolling", "apart")
"""What touch a :class:`Contact` is, each with its proof that can fail both ways."""


@dataclass(frozen=True)
class Contact:
    """Two placed parts (indices into the placements) and what touch they are (``touch``):

    - ``"mesh"``, toothed (``module`` given): they may overlap by the teeth's allowance and, the
      second turned by the budget's nudge arc over ``radius`` (its pitch radius at the contact,
      mm) either way, must overlap by more — unless ``nudge`` is False because the mechanism
      proved the mesh over a whole cycle itself (a :class:`Proof`);
    - ``"rolling"``, smooth outlines rolling on each other along ``length`` mm: they may overlap
      by the tolerance along that length and leave no gap wider than the budget's depth (2·tol);
    - ``"apart"``: they must not touch at all.

    Left out, ``touch`` is "mesh" with a module, "rolling" with a length, else "apart".
    """

    first: int
    second: int
    module: float | None = None
    radius: float = 0.0
    length: float = 0.0
    nudge: bool = True
    touch: str = ""
    play: float = 0.0
    """A mesh's designed play (arc at the contact, mm): the nudged test turns beyond it."""

    def __post_init__(self):
        touch = self.touch or ("mesh" if self.module is not None else "rolling" if self.length > 0 else "apart")
        if touch not in TOUCHES:
            raise ValueError(f"touch = {touch!r}: must be one of {', '.join(TOUCHES)}")
        if (touch == "mesh") != (self.module is not None) or (touch == "rolling") != (self.length > 0):
            raise ValueError(f"a {touch} contact: a module only for a mesh, a length (> 0) only for rolling")
        object.__setattr__(self, "touch", touch)


class Proof:
    """What a mechanism's own mesh proof over a cycle reports (``teeth.mesh.MeshData`` is one)."""

    positions: int
    max_overlap: float
    allowed_overlap: float
    nudged_min_overlap: float
    max_depth: float


D = TypeVar("D")
"""A mechanism's own computed objects (``Draft.detail``): ``GearPairDetail``, ``RollerBodyDetail``, …"""


@dataclass(frozen=True)
class Draft(Generic[D]):
    """What a mechanism's ``design(params)`` returns: only what is its own (``Draft[D]``: ``D``
    the type of its ``detail``, read by its own hooks and charts)."""

    params: Any
    mechanism: str
    summary: str
    findings: tuple[Finding, ...]
    parts: tuple[PartSpec, ...]
    placements: tuple[Placement, ...]
    contacts: tuple[Contact, ...]
    data: Blocks
    """The mechanism's report blocks (JSON-ready)."""
    units: dict[str, str]
    detail: D | None = None
    details: tuple[str, ...] = ()
    motion: Motion | None = None
    tables: tuple[Table, ...] = ()
    sections: dict[str, GearSections] = field(default_factory=dict)
    """Part name → its twisted sections: such a part's solid is lofted through them."""
    bands: dict[str, float] = field(default_factory=dict)
    """Part name → the line (its angle, rad, in the part's frame, through its pivot) about which its
    upper half is its lower half mirrored: two stacked straight tooth bands (:attr:`.Design.bands`).
    A set so made cannot be put together from loose parts: its plate holds it assembled."""
    charts: Charts = field(default_factory=dict)
    """Chart name → the data it is drawn from (``chart_data``: the exporters compute nothing of the model)."""
    proofs: tuple = ()
    """The mechanism's own mesh proofs over a cycle (:class:`Proof` each), joined to the assembly's."""
    where: str = "assembly"
    """What a finding about the assembly names as its place."""
    placed: str = "meshing parts touch"
    """What the assembly drawing shows, in the page's words (how the parts are placed)."""


def prove(parts: dict[str, Part], draft: Draft) -> Assembly:
    """The proof of the draft's contacts, each by its touch, with one overlap and nudge policy:
    no overlap beyond the budget; a mesh, turned a little, bites; a rolling contact leaves no gap."""
    b = budget(draft.params.output.tolerance)
    placements = list(draft.placements)
    pairs = [(c.first, c.second) for c in draft.contacts]
    overlap = assembly_overlap(parts, placements, pairs)
    allowed = max(
        (b.teeth_overlap(c.module) if c.touch == "mesh" else b.allowed_overlap(c.length) for c in draft.contacts),
        default=0.0,
    )
    nudged = [p.nudged_min_overlap for p in draft.proofs]
    for c in draft.contacts:
        if c.touch != "mesh" or not c.nudge:
            continue
        turn = b.nudge_arc(module=c.module, play=c.play) / c.radius
        first, mate = placements[c.first], placements[c.second]
        # turned a little either way, the second part must bite into the first: they do touch
        turned = [Placement(mate.part, mate.angle + d, mate.offset) for d in (-turn, turn)]
        nudged.append(max(assembly_overlap(parts, [first, t], [(0, 1)]) for t in turned))
    proofs = draft.proofs
    # depth, not only area: a long thin sliver passes an area bound but binds the made parts
    toothed = [(c.first, c.second) for c in draft.contacts if c.touch == "mesh"]
    depths = [p.max_depth for p in proofs]
    if toothed:
        step = 0.1 * min(c.module for c in draft.contacts if c.touch == "mesh")
        depths.append(assembly_depth(parts, placements, toothed, step=step))
    rolling = [(c.first, c.second) for c in draft.contacts if c.touch == "rolling"]
    return Assembly(
        max([overlap] + [p.max_overlap for p in proofs]),
        proofs[0].allowed_overlap if proofs else allowed,
        min(nudged) if nudged else None,
        proofs[0].positions if proofs else 1,
        max(depths) if depths else None,
        b.allowed_depth if depths else None,
        gap=assembly_gap(parts, placements, rolling) if rolling else None,
        allowed_gap=b.allowed_depth if rolling else None,
        proven=bool(toothed) and _bands_proven(draft),
    )


def _bands_proven(draft: Draft) -> bool:
    """Whether every band of the draft's meshes is proven to fit (:attr:`Assembly.proven`)."""
    bands = draft.data.get("bands") or []
    return bool(bands) and all(
        b.get("certificate") == "theorem" and b.get("proven") and b.get("verdict") == "fits" for b in bands
    )


def _hook(draft: Draft, name: str):
    """The draft's mechanism's hook ``name`` (None for a draft no registry entry names)."""
    entry = MECHANISMS.get(draft.mechanism)
    return None if entry is None else entry.hook(name)


def _with_papers(draft: Draft) -> Blocks:
    """The draft's report blocks and, for a profile that reproduces a seed, the papers' numbers
    beside gearcad's (``papers``)."""
    papers = _hook(draft, "papers")
    block = None if papers is None else papers(draft.params, draft.data)
    return draft.data if block is None else {**draft.data, "papers": block}


def finish(draft: Draft[D], *, start: float | None = None) -> Design[D]:
    """The complete design of a draft: parts with their cut paths, the assembly proven, the
    sheet and plate laid out (``start``: when the design began, for its ``seconds``)."""
    start = time.perf_counter() if start is None else start
    out = draft.params.output
    made = tuple(s.blank(out) for s in draft.parts)
    router = getattr(getattr(draft.params, "process", None), "kind", None) == "cnc"
    parts = cut_paths(made, out, router=router)
    marks = _hook(draft, "marks")  # a gear pair's dots where its teeth meet
    parts = marks(draft, parts) if marks is not None else parts
    assembly = prove({p.name: p for p in parts}, draft)
    findings = draft.findings
    if not assembly.fits and not any(f.code == "interference" for f in findings):
        findings += (finding("interference", _unfit(assembly), draft.where),)
    line = f"assembly: max overlap {assembly.overlap:.3g} mm² (allowed {assembly.allowed:.3g})"
    if assembly.nudged is not None:
        line += f", nudged {assembly.nudged:.3g} mm²"
    if assembly.gap is not None:
        line += f", rolling gap {assembly.gap:.3g} mm (allowed {assembly.allowed_gap:.3g})"
    if assembly.proven:
        line += "; no deeper between positions (every mesh's band proven)"
    chosen = [f for f in TABLE if f.name in set(out.formats)]
    wholes = {w for f in chosen for w in f.wholes}
    lay = layouts.in_place_layout if draft.bands else layouts.plate_layout
    plates = lay(parts, draft.placements, out, draft.sections) if "plate" in wholes else None
    findings += _too_large(plates)
    return Design(
        params=draft.params,
        mechanism=draft.mechanism,
        summary=counted(draft.summary, len(findings)),
        findings=findings,
        part_list=parts,
        placements=draft.placements,
        assembly=assembly,
        data=_with_papers(draft),
        units=draft.units,
        detail=draft.detail,
        details=(*draft.details, line),
        motion=draft.motion,
        tables=draft.tables,
        sheet=layouts.sheet_layout(parts, draft.placements, out) if "sheet" in wholes else (),
        plates=plates.plates if plates is not None else (),
        sections=draft.sections,
        bands=draft.bands,
        made=_made_rings(made, out) if any(f.exact for f in chosen) and out.kerf > 0 else {},
        charts=draft.charts,
        placed=draft.placed,
        seconds=time.perf_counter() - start,
    )


def _unfit(a: Assembly) -> str:
    """Why the assembly does not fit, in one sentence: a gap where parts roll, teeth that do not
    engage when turned, or parts that overlap (by area, and by depth)."""
    if a.gap is not None and a.gap > a.allowed_gap:
        return f"rolling parts stand {a.gap:.4g} mm apart as assembled (allowed {a.allowed_gap:.3g} mm): no contact"
    if a.nudged is not None and a.overlap <= a.allowed and a.nudged <= a.allowed:
        return (
            f"meshing parts turned a little overlap by only {a.nudged:.4g} mm² (more than {a.allowed:.3g} "
            "needed): their teeth do not engage"
        )
    message = f"parts overlap by {a.overlap:.4g} mm² as assembled (allowed {a.allowed:.3g} mm²)"
    if a.depth is not None and a.depth > a.allowed_depth:
        message += f", {a.depth * 1e3:.3g} µm deep (allowed {a.allowed_depth * 1e3:.3g} µm)"
    return message


def _too_large(plates) -> tuple:
    """A ``bed`` finding per part no printer bed of ``output.bed`` takes (left off the plates)."""
    if plates is None or not plates.too_large:
        return ()
    w, h = plates.bed
    found = []
    for name in dict.fromkeys(b.part for b in plates.too_large):
        box = next(b for b in plates.too_large if b.part == name)
        need_w, need_h = plates.needs(box)
        found.append(
            finding(
                "bed",
                f"{name} ({box.width:.1f} × {box.height:.1f} mm) fits on no plate of the {w:g} × {h:g} mm bed "
                f"(output.bed): print it alone on a bed of at least {need_w} × {need_h} mm "
                f"(--set output.bed=[{need_w},{need_h}]), or cut it from the sheet",
                name,
            )
        )
    return tuple(found)


def counted(summary: str, findings: int) -> str:
    """The summary with its "N warning(s)" saying how many findings the design ends with: a
    mechanism counts its own when it draws, and the fit's bands and the assembly's proof may
    add more (the headline, report.json, the page and ``Design.findings`` agree)."""
    return re.sub(r"\b\d+ warning\(s\)", f"{findings} warning(s)", summary)


def _made_rings(blanks, out) -> dict:
    """Every part's cut rings fitted as without a kerf: the part itself, for its solid."""
    return {p.name: p.cut for p in cut_paths(blanks, out.model_copy(update={"kerf": 0.0}))}
