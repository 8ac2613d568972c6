"""Findings about a design: stable warning codes, carried as data and logged."""

from __future__ import annotations

import logging
from dataclasses import dataclass

__all__ = ["CODES", "Finding", "finding"]

log = logging.getLogger("gearcad")

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
}
"""Every warning code gearcad emits, with what it means.  Codes never change meaning."""


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
