"""Study "helical": solid generation time and triangle count of the herringbone focus-ellipse
pair against face width and tolerance (moved whole from export/loft.py: exporters read only a
design, a benchmark builds its own)."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import replace

from ..export.loft import loft

__all__ = ["helical_benchmark"]


def helical_benchmark(
    *, quick: bool = False, face_widths: Sequence[float] | None = None, tolerances: Sequence[float] | None = None
) -> list[dict]:
    """Solid generation time and triangle count of the herringbone focus-ellipse pair (a = 25,
    b = 15 mm, m_n = 1, β = 25°) against face width and tolerance: rows for ``gearcad bench``
    (study "helical"; ``n`` the triangles of both solids, ``seconds`` sections + both lofts,
    ``error`` the tolerance)."""
    from ..mechanisms.pair_pitch import pitch_design
    from ..profiles import parse_profile
    from ..teeth.helical import pair_sections
    from ..teeth.helix import transverse_teeth
    from ..teeth.pair import cut_pair
    from ..tolerances import DEFAULT

    if face_widths is None:
        face_widths = (5.0,) if quick else (5.0, 10.0, 20.0)
    if tolerances is None:
        tolerances = (0.02,) if quick else (0.04, 0.02, 0.01, 0.005)
    beta = math.radians(25)
    rows = []
    for tol in tolerances:
        params = parse_profile(
            {
                "gear1": {"name": "driver", "curve": "ellipse", "pivot": "focus", "a": 25.0, "b": 15.0},
                "gear2": {"name": "follower", "lobes": 1},
                "teeth": {"module": 1.0},
                "output": {"tolerance": tol},
            },
            default_name="helical_bench",
        )
        t = replace(DEFAULT, outline_mm=tol)
        pitch = pitch_design(params, tol=t)
        teeth = cut_pair(
            pitch.pair, pitch.gears, transverse_teeth(params.teeth, beta), mate_rotation=pitch.mate_rotation, tol=t
        )
        for width in face_widths:
            start = time.perf_counter()
            sections = pair_sections(teeth, helix_angle=beta, herringbone=True, face_width=width, tolerance=tol)
            cut = time.perf_counter()
            solids = [loft(g.heights, g.rings, name=f"gear{i + 1}") for i, g in enumerate(sections.gears)]
            end = time.perf_counter()
            g = sections.gears[0]
            triangles = sum(s.triangle_count for s in solids)
            rows.append(
                {
                    "study": "helical",
                    "method": f"herringbone pair, b = {width:g} mm",
                    "n": triangles,
                    "seconds": end - start,
                    "error": tol,
                    "face_width": width,
                    "tolerance": tol,
                    "sections": len(g.heights),
                    "section_vertices": g.rings.shape[1],
                    "spacing": sections.spacing.spacing,
                    "sections_seconds": cut - start,
                    "loft_seconds": end - cut,
                }
            )
    return rows
