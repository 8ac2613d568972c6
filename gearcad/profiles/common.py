"""What every profile shares: the model base, names, ``[output]`` and ``[bore]``."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, model_validator

from ..formats import DEFAULT_FORMATS, DXF_FLAVOURS, FORMATS
from .values import LARGEST_LENGTH, Flag, LayerName, LengthOrZero, Must, Problems, Size, choice, number

__all__ = ["ParamsModel", "OutputParams", "BoreParams", "DXF_FLAVOURS", "FORMATS", "distinct_names"]


Tolerance = number(
    "a length in mm",
    ge=1e-4,
    le=0.5,
    why=" (finer than 0.1 µm is refused: the work would grow without bound)",
)
Formats = Annotated[tuple[choice(*FORMATS), ...], Must("a list drawn from " + ", ".join(map(repr, FORMATS)))]
DxfFlavour = choice(*DXF_FLAVOURS)
CertificateKind = choice("estimate", "theorem")
Thickness = number("a thickness in mm", gt=0, le=1000)
Kerf = number("a kerf width in mm", ge=0, le=2)
Diameter = number("a diameter in mm", ge=0, le=LARGEST_LENGTH)


def _require_tag(schema: dict[str, Any], cls: type[BaseModel]) -> None:
    # a union's tag has a default for Python callers, but a profile must write it (except
    # "gear-pair", the mechanism of a profile that names none)
    for tag in ("curve", "mechanism"):
        field = cls.model_fields.get(tag)
        if field is not None and field.default != "gear-pair":
            schema.setdefault("required", []).append(tag)


class ParamsModel(BaseModel):
    """Frozen, closed models: fields are the TOML keys; constructing one validates it."""

    model_config = ConfigDict(
        frozen=True,
        extra="forbid",
        json_schema_extra=_require_tag,
        defer_build=True,  # a model is built when first used: one mechanism, not all four, per run
    )


def distinct_names(problems: Problems, named: list[tuple[str, str]], prefix: str = "") -> None:
    """Part names become file names, and file systems may ignore case: they must differ as such.

    ``named`` holds (key relative to the model, name); ``prefix`` makes the other key absolute.
    """
    seen: dict[str, tuple[str, str]] = {}
    for key, name in named:
        other, first = seen.setdefault(name.casefold(), (key, name))
        if other != key:
            problems.add(
                key,
                name,
                f"must differ from {prefix}{other} = {first!r} (each part's name names its files; case is ignored)",
            )


class OutputParams(ParamsModel):
    """``[output]``: how finely outlines are drawn and which files are written."""

    tolerance: Tolerance = 0.001
    """Largest distance between a drawn outline and the exact curve, mm (1e-4 … 0.5)."""
    charts: Flag = True
    """Draw charts (pitch curves, kinematics, mesh)."""
    animation: Flag = True
    """Write an animated GIF of the mechanism."""
    formats: Formats = DEFAULT_FORMATS
    """Files to write for each part (the formats allowed are listed with the key; the default leaves out
    those slow to load)."""
    dxf: DxfFlavour = "polyline"
    """How outlines are written to DXF: one polyline with bulges, lines and arcs, or flat polyline."""
    thickness: Thickness = 5.0
    """Plate thickness of the solid parts, mm."""
    chamfer: LengthOrZero = 0.0
    """Chamfer on the solid parts' edges, mm (0: none)."""
    kerf: Kerf = 0.0
    """Width the cutter removes, mm: outlines are offset by half of it. Under process.kind "laser"
    process.kerf wins when both are set (they differ: warning kerf-ignored), under "cnc" the tool's diameter."""
    cut_layer: LayerName = "CUT"
    """DXF layer of the outlines to cut."""
    mark_layer: LayerName = "MARK"
    """DXF layer of the pitch curves and marks (must differ from cut_layer)."""
    sheet: Size = (600.0, 400.0)
    """[width, height] of the sheet the parts are laid out on, mm."""
    gap: LengthOrZero = 3.0
    """Space between parts laid out on a sheet or bed, mm."""
    bed: Size = (250.0, 210.0)
    """[width, height] of the printer bed, mm."""
    certificate: CertificateKind = "theorem"
    """How a gear pair's least play is bounded between the driver positions measured (its band's verdict rests
    on it): "theorem" (default) proves it from the geometry (the follower's motion about the instant centre) and
    says jams, naming the interval, where the work budget cannot close it (every cut of a fit search is proven).
    "estimate" bounds it by twice the steepest slope the measured play shows nearby, at 1/40 to 1/2 of
    the CPU — not a proof: a dip narrower than those slopes can hide (the laser focus pair's estimate says
    fits by 10 µm where it jams by 3.6 µm)."""

    @model_validator(mode="after")
    def _layers_differ(self) -> OutputParams:
        problems = Problems()
        if self.mark_layer.casefold() == self.cut_layer.casefold():
            problems.add(
                "mark_layer",
                self.mark_layer,
                f"must differ from output.cut_layer = {self.cut_layer!r} (DXF layer names ignore case)",
            )
        problems.raise_any()
        return self


PilotDiameter = number("a diameter in mm", ge=0, le=20)


class BoreParams(ParamsModel):
    """``[bore]``: the hole every gear gets for its shaft (mm); diameter 0 means none."""

    diameter: Diameter = 0.0
    """Bore diameter, mm (0: no bore)."""
    keyway_width: LengthOrZero = 0.0
    """Width of a keyway cut into the gear beyond the bore's edge, at polar angle 0, mm."""
    keyway_depth: LengthOrZero = 0.0
    """Depth of the keyway beyond the bore's edge, mm."""
    flat: LengthOrZero = 0.0
    """D-flat: the distance from the bore's centre (the pivot) to the flat, which faces +x, mm (0: none);
    under the bore radius, e.g. 2.5 for a 6 mm shaft whose flat is ground 0.5 mm deep."""
    pilot: PilotDiameter = 1.0
    """Where no bore is given, a pilot hole of this diameter marks the pivot exactly (a noncircular
    gear works only on its exact pivot), mm; 0 for none (the engraved cross remains)."""

    @model_validator(mode="after")
    def _shape(self) -> BoreParams:
        problems = Problems()
        width, depth, flat, diameter = self.keyway_width, self.keyway_depth, self.flat, self.diameter
        if (width > 0) != (depth > 0):
            problems.add(
                "keyway_depth" if width > 0 else "keyway_width",
                depth if width > 0 else width,
                "must be > 0: a keyway needs both bore.keyway_width and bore.keyway_depth",
            )
        if flat > 0 and width > 0:
            problems.add("flat", flat, "give a keyway or a flat, not both (set bore.flat = 0 or the keyway to 0)")
        if (width > 0 or flat > 0) and diameter <= 0:
            problems.add("diameter", diameter, "must be > 0: a keyway or a flat needs a bore")
        elif flat > 0 and flat >= diameter / 2:
            problems.add(
                "flat", flat, f"must be under the bore radius {diameter / 2:g} mm (it is the distance from the centre)"
            )
        elif width > 0 and width >= diameter:
            problems.add("keyway_width", width, f"must be under the bore diameter {diameter:g} mm")
        problems.raise_any()
        return self
