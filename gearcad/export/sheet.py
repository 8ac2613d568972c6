"""The cutting sheet as a drawing: every part laid out flat (``design.sheet``, made with the design)."""

from __future__ import annotations

from dataclasses import replace

from ..mechanisms import Design
from .drawing import Drawing, assembly_drawing

__all__ = ["sheet_drawing"]


def sheet_drawing(design: Design) -> Drawing:
    """The parts' cut rings (kerf applied) and marks, placed as ``design.sheet`` lays them out."""
    return assembly_drawing(replace(design, placements=design.sheet), cut=True)
