"""Mechanism designs: one module per mechanism, each a pure ``design(params) -> Draft`` of what
is its own; :func:`~.finish.finish` makes any draft the complete :class:`Design` (:func:`gearcad.fitting.design`
fits the process and checks the bands between the two).

No files are written here; every check a build makes is made here, so ``gearcad check`` and
``gearcad build`` refuse and accept the same profiles.
"""

from __future__ import annotations

from .base import Design
from .finish import Draft
from .parts import Part, Placement
from .registry import MECHANISMS

__all__ = ["Design", "Draft", "Part", "Placement", "MECHANISMS"]
