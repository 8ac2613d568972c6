"""Teeth: the closed-form envelope against boolean subtraction of rack copies.

y: the largest distance between the outline and a converged reference (the same envelope cut
at 1e-6 mm, 1e-5 in a quick run), both ways along the whole outline.  x: time per cut, the
fastest of interleaved rounds (the median beside it shows how loaded the machine was).  Times
of a few milliseconds on a shared machine swing by 2-3× between calls; best-of-3 in a row once
made the coarsest tolerance look slower than a finer one.
"""

from __future__ import annotations

import math

import numpy as np

from .outlines import deviation
from .timing import time_interleaved

__all__ = ["bench_envelope"]


def bench_envelope(quick: bool) -> list[dict]:
    """Closed-form envelope against boolean subtraction of N rack copies: largest outline
    deviation from the envelope cut at 1e-6 mm, against time."""
    from ..pitch import shapes
    from ..teeth.frame import arc_frame
    from ..teeth.gear import cut_teeth
    from ..teeth.rack import Rack, RackParams
    from ..teeth.reference import rack_cut

    rows = []
    cases = [("circle z=20", shapes.circle(20.0), 20), ("ellipse z=41", shapes.ellipse_focus(25.0, 15.0), 41)]
    for label, curve, z in cases:
        frame = arc_frame(curve)
        rack = Rack.from_params(RackParams(module=frame.perimeter / (z * math.pi)))
        phase = rack.pitch / 2
        exact = cut_teeth(frame, rack, z, phase, tolerance=1e-5 if quick else 1e-6).outline.outer
        cuts = {
            tol: (lambda tol=tol: cut_teeth(frame, rack, z, phase, tolerance=tol).outline.outer)
            for tol in ([1e-2, 1e-3] if quick else [1e-2, 1e-3, 1e-4])
        }
        for tol, t in time_interleaved(cuts, 1 if quick else 9).items():  # quick: measured once
            rows.append(
                {
                    "study": f"envelope {label}",
                    "method": "gearcad closed-form envelope",
                    "n": tol,
                    "seconds": t.best,
                    "seconds_median": t.median,
                    "error": deviation(t.result, exact),
                }
            )
        copies = {
            steps: (lambda s=steps: np.asarray(rack_cut(frame, rack, z, phase, steps_per_pitch=s).exterior.coords)[:-1])
            for steps in ([6] if quick else [6, 12, 24, 48, 96])
        }
        for steps, t in time_interleaved(copies, 1 if quick else 3).items():
            rows.append(
                {
                    "study": f"envelope {label}",
                    "method": "boolean: blank minus N rack copies",
                    "n": steps,
                    "seconds": t.best,
                    "seconds_median": t.median,
                    "error": deviation(t.result, exact),
                }
            )
    return rows
