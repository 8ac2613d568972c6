"""What every writer is handed besides the design and its folder: the drawings and solids of
the parts, each made once however many formats read it, and the files of one format piece by
piece (each part, then each of the format's wholes)."""

from __future__ import annotations

from collections.abc import Callable
from functools import cached_property
from pathlib import Path

from ..formats import Format
from ..mechanisms import Design

__all__ = ["Made", "write_pieces"]


class Made:
    """A design's drawings and solids, made when a writer first asks for them."""

    def __init__(self, design: Design):
        self.design = design
        self._drawings: dict = {}

    def drawing(self, stem: str, whole: str | None = None):
        """A part's drawing (by its name) or a whole's (``whole``: "assembly", "sheet"; the sheet
        places and letters every part's name)."""
        key = (whole,) if whole else stem
        if key not in self._drawings:
            from .drawing import assembly_drawing, part_drawing
            from .sheet import sheet_drawing

            made = {"assembly": assembly_drawing, "sheet": sheet_drawing}
            design = self.design
            self._drawings[key] = made[whole](design) if whole else part_drawing(design, design.part(stem))
        return self._drawings[key]

    @cached_property
    def solids(self) -> dict:
        """Each part's solid: extruded, two stacked bands, or lofted through its twisted sections."""
        from ..geometry.outline import mirrored
        from .loft import loft
        from .mesh import extrude, stacked

        design, out = self.design, self.design.params.output

        def solid(part):
            twisted = design.sections.get(part.name)
            if part.name in design.bands:
                upper = mirrored(part.outline, design.bands[part.name])
                return stacked(part.outline, upper, out.thickness, name=part.name, chamfer=out.chamfer)
            if twisted is None:
                return extrude(part.outline, out.thickness, name=part.name, chamfer=out.chamfer)
            holes = part.outline.rings[1:]
            return loft(twisted.heights, twisted.rings, name=part.name, holes=holes, chamfer=out.chamfer)

        return {p.name: solid(p) for p in design.parts()}

    def pieces(self, fmt: Format) -> list[tuple[str, str | None, object]]:
        """What a format's files are drawn from, file by file: (file stem, whole or None, drawing
        or solids) for every part, then for each of the format's wholes."""
        design = self.design
        if fmt.takes == "drawing":
            pieces = [(p.name, None, self.drawing(p.name)) for p in design.parts()]
            return pieces + [(w, w, self.drawing(w, w)) for w in fmt.wholes]
        from .mesh import SolidItem

        solids = self.solids
        plates = list(zip(design.plate_files(), design.plates))
        scenes = {"assembly": [("assembly", design.placements)], "plate": plates}
        pieces = [(name, None, [SolidItem(solid)]) for name, solid in solids.items()]
        return pieces + [
            (stem, w, [SolidItem(solids[pl.part], pl.angle, (*pl.offset, 0.0)) for pl in layout])
            for w in fmt.wholes
            for stem, layout in scenes[w]
        ]


def write_pieces(fmt: Format, folder: Path, made: Made, one: Callable[[Path, str | None, object], dict]) -> dict:
    """Every file of ``fmt``: ``one(path, whole, drawing or solids)`` writes one and returns its
    counts; returns the report's entries by file name."""
    files = {}
    for stem, whole, what in made.pieces(fmt):
        path = folder / f"{stem}.{fmt.extension}"
        counts = one(path, whole, what)
        files[path.name] = {"bytes": path.stat().st_size, "kind": fmt.name, "part": stem, **counts}
    return files
