"""The HTML page's "Fit when made" section: each mesh's play as drawn and over the process."""

from __future__ import annotations

import math
from html import escape

__all__ = ["section_bands"]


def section_bands(report: dict) -> str:
    """A table of ``report["bands"]`` (empty when the design has none)."""
    bands = report.get("bands") or []
    if not bands:
        return ""
    kind = (report.get("process") or {}).get("kind", "none")

    def mm(value, digits: int = 4) -> str:  # a value not measured (null in the report) shows as –
        return "–" if value is None else f"{value:.{digits}f}"

    rows = "".join(
        f"<tr><td>{escape(str(b['mesh']))}</td>"
        f"<td class='num'>{mm(b['nominal_min'])} … {mm(b['nominal_max'])}</td>"
        f"<td class='num'>{mm(b['min'])} … {mm(b['max'])}</td>"
        f"<td class='num'>{b['worst_tooth']} at "
        f"{'–' if b['worst_phi'] is None else format(math.degrees(b['worst_phi']), '.1f')}°</td>"
        f'<td><span class="{"good" if b["verdict"] == "fits" else "bad"}">{escape(str(b["verdict"]))}</span></td>'
        f"<td class='num'>{mm(b['needed_backlash'], 3)}</td></tr>"
        for b in bands
    )
    return (
        f'<h2 id="fit">Fit when made ({escape(kind)})</h2>'
        "<p>Play on the pitch curve (mm): as drawn over one cycle, and over the process's tolerances "
        "(edges largest with the centres closer, smallest with them apart), measured on the offset outlines.</p>"
        "<table><tr><th>mesh</th><th>as drawn</th><th>made</th><th>tightest (driver tooth, angle)</th>"
        f"<th>verdict</th><th>backlash to add</th></tr>{rows}</table>"
    )
