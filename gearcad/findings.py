"""Findings about a design: stable warning codes, carried as data and logged."""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

from .errors import ProfileError

__all__ = ["CODES", "ERRORS", "Finding", "finding", "failing", "check_codes", "listed", "amount"]

log = logging.getLogger("gearcad")
log.addHandler(logging.NullHandler())  # a library says nothing on stderr unless its user asks

CODES: dict[str, str] = {
    "corner": "a pitch curve has a tangent discontinuity (teeth cannot follow it exactly)",
    "concave": "a pitch curve has a concave stretch or notch (limits the cutter and the teeth)",
    "not-closed": "a pair checked against a paper's construction does not close over a turn",
    "not-identical": "a paper's 'identical mate' claim fails: the mate that rolls is another curve",
    "slips": "a paper's construction does not roll: the pitch curves slide on each other",
    "blend": "corners were blended: the ratio law differs from the required one near the seams",
    "paper-table": "a printed table value differs from the paper's own formula",
    "paper-formula": "a printed formula does not follow from the paper's own equations; the derived one is used",
    "paper-claim": "a statement in a paper's text does not hold against its own equations; the report has the numbers",
    "paper-root": "a printed closed form takes the wrong root over part of the allowed range; the right root is used",
    "teeth-fit": "a dimension was adjusted so that a whole number of teeth fits (the report gives both)",
    "undercut": "the rack cuts into the lower flanks of some teeth (weaker teeth, shorter contact)",
    "pointed": "some teeth have pointed or nearly pointed tips (under 0.2 module of tip land)",
    "interference": "the toothed pair overlaps in mesh beyond the tolerance, or loses contact",
    "relief": "a gear's teeth were trimmed by the mate's sweep where the rack's envelope is not conjugate",
    "rack-overcut": "a generating rack or hob would cut beyond the outline on a concave stretch (cut it as drawn)",
    "jams": "a mesh's play falls below zero somewhere over the process's tolerances: the made pair can bind",
    "loose": "a mesh's worst-case play exceeds what a maker would accept (process.max_play)",
    "backlash-fixed": "the profile fixes teeth.backlash below what the process's worst case needs",
    "bed": "a part is larger than the printer's bed (output.bed): no print plate holds it",
    "kerf-ignored": "output.kerf is set but the process's cutter is used (process.kerf, or a router's tool)",
    "pressure-angle": "a pair's working pressure angle exceeds teeth.max_pressure_angle_deg (45° by default)",
}
"""Every warning code gearcad emits, with what it means.  Codes never change meaning."""

ERRORS = frozenset({"interference", "jams"})
"""Codes that fail ``gearcad check`` and ``build`` (exit status 3) unless allowed by name: the
parts as designed, or as made under the process's tolerances, do not move."""


@dataclass(frozen=True)
class Finding:
    """One warning about a design: a stable ``code``, a sentence, and where it applies."""

    code: str
    message: str
    where: str = ""

    def as_dict(self) -> dict[str, str]:
        return {"code": self.code, "message": self.message, "where": self.where}


def finding(code: str, message: str, where: str = "") -> Finding:
    """Make a :class:`Finding` (the code must be a known one) and log it."""
    if code not in CODES:
        raise KeyError(f"unknown warning code {code!r}")
    log.warning("%s: %s", code, message)
    return Finding(code, message, where)


def check_codes(codes) -> tuple[str, ...]:
    """``codes`` as a tuple, each a known code (else a :class:`~.errors.ProfileError` naming the
    known ones)."""
    for code in codes:
        if code not in CODES:
            raise ProfileError(f"--allow {code!r}: not a finding code; one of {', '.join(sorted(CODES))}")
    return tuple(codes)


def failing(findings, allow=()) -> tuple[Finding, ...]:
    """The findings that are errors (:data:`ERRORS`) and not allowed by code."""
    return tuple(f for f in findings if f.code in ERRORS and f.code not in allow)


def amount(value: float, spec: str = ".4g", *, infinite: str = "none") -> str:
    """A number as a message shows it to a person: ``spec``-formatted, and ``infinite`` (a word:
    "none", "no limit") where Python would print ``inf`` or ``nan``."""
    value = float(value)
    return format(value, spec) if math.isfinite(value) else infinite


def listed(values, spec: str = "g", *, empty: str = "none") -> str:
    """Numbers (or words) as a person writes them: "0.2, 0.3 and 0.4", not ``[0.2, 0.3, 0.4]``."""
    items = [format(v, spec) if isinstance(v, int | float) else str(v) for v in values]
    if not items:
        return empty
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"
