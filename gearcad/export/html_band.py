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
        f'<td><span class="{"good" if b["verdict"] == "fits" else "bad"}">{escape(str(b["verdict"]))}</span>'
        f"{_how(b)}</td>"
        f"<td class='num'>{mm(b['needed_backlash'], 3)}</td></tr>"
        for b in bands
    )
    return (
        f'<h2 id="fit">Fit when made ({escape(kind)})</h2>'
        "<p>Play on the pitch curve (mm): as drawn over one cycle, and over the process's tolerances "
        "(edges largest with the centres closer, smallest with them apart), measured on the offset outlines.</p>"
        "<table><tr><th>mesh</th><th>as drawn</th><th>made</th><th>tightest (driver tooth, angle)</th>"
        f"<th>verdict</th><th>backlash to add</th></tr>{rows}</table>" + _contact(bands)
    )


def _how(b: dict) -> str:
    """How the least play the verdict rests on is known: by the slope estimate or proven
    (``output.certificate``); nothing for a band without a certificate or one not settled."""
    kind = b.get("certificate")
    if kind is None or (kind == "theorem" and not b.get("proven")):
        return ""
    return f" (least {min(b['min'], b['certified_min']):.4f} mm, {'proven' if kind == 'theorem' else 'estimated'})"


def _contact(bands: list[dict]) -> str:
    """Contact ratio and working pressure angle of the meshes whose band carries them (a carrier
    train's, a body's rollers; a gear pair gives its own under the teeth)."""
    rows = "".join(
        f"<tr><td>{escape(str(b['mesh']))}{' (internal)' if b.get('internal') else ''}</td>"
        f"<td class='num'>{c['ratio_min']:.3f} at {c['ratio_min_at_phi1_deg']:.1f}° … "
        f"{c['ratio_max']:.3f} at {c['ratio_max_at_phi1_deg']:.1f}°</td>"
        f"<td class='num'>{c['pressure_angle_min_deg']:.2f}° … {c['pressure_angle_max_deg']:.2f}°</td></tr>"
        for b in bands
        if (c := b.get("contact"))
    )
    if not rows:
        return ""
    return (
        "<p>Contact ratio (smallest, largest and where: the driver's turn) and working pressure angle:</p>"
        f"<table><tr><th>mesh</th><th>contact ratio</th><th>working pressure angle</th></tr>{rows}</table>"
    )
