"""Where methods break down: hard designs end in ok, a warning code or one clear error."""

from __future__ import annotations

import time

import numpy as np

__all__ = ["stability_map"]

_QUICK = {"tolerance": 0.01, "charts": False, "animation": False}
"""A quick map's designs: where a design breaks down does not hang on the outline's last µm."""


def stability_map(quick: bool = False) -> list[dict]:
    """Hard designs and what gearcad does with each: 'ok', a warning code, or a clear error —
    never NaN, a hang or a silently wrong outline."""
    from ..errors import GearcadError
    from ..fitting import design
    from ..profiles import parse_profile

    def attempt(label: str, value, data: dict, teeth: bool = True) -> dict:
        start = time.perf_counter()
        try:
            # large designs need a sheet and a bed to match: the map is about the design
            output = {"sheet": [1e5, 1e5], "bed": [1e5, 1e5], **(_QUICK if quick else {}), **data.get("output", {})}
            data = {**data, "output": output}
            params = parse_profile(data)
            if not teeth and getattr(params, "teeth", None) is not None:
                params = parse_profile({k: v for k, v in data.items() if k != "teeth"})
            d = design(params)
            codes = {f.code for f in d.findings if not f.code.startswith("paper-")}  # about the paper, not the design
            if not all(np.all(np.isfinite(r)) for part in d.parts() for r in part.outline.rings):
                raise AssertionError("NaN in an outline")
            outcome = "warning: " + ", ".join(sorted(codes)) if codes else "ok"
        except GearcadError as exc:
            outcome = "error: " + str(exc).splitlines()[0]
        return {"case": label, "value": value, "outcome": outcome, "seconds": time.perf_counter() - start}

    rows = []
    for ecc in [0.5, 0.99] if quick else [0.0, 0.3, 0.6, 0.8, 0.9, 0.95, 0.99]:
        data = {
            "gear1": {"curve": "ellipse", "pivot": "centre", "a": 25.0, "eccentricity": ecc},
            "gear2": {"lobes": 2},
            "teeth": {"count": 40},
        }
        rows.append(attempt("ellipse (centre) eccentricity, 40 teeth", ecc, data))
    for z in [6, 40] if quick else [6, 8, 12, 16, 17, 18, 40, 100, 400]:
        data = {"gear1": {"curve": "circle", "radius": float(z)}, "gear2": {"lobes": 1}, "teeth": {"count": z}}
        rows.append(attempt("spur pair 1:1, tooth count", z, data))
    for width in (0.0,) if quick else (0.0, 6.0):
        data = {
            "gear1": {"curve": "walker", "a": 100.0, "b": 50.0, "c": 322.0, "blend_width_deg": width},
            "gear2": {"lobes": 1},
            "pair": {"center_distance": 75.0},
            "teeth": {"module": 1.5},
        }
        rows.append(attempt("walker blend width (deg)", width, data))
    for mean in (1.0, 1.2):
        data = {
            "gear1": {"curve": "ratio", "mean": mean, "harmonics": [[1, 0.3, 0.0]]},
            "pair": {"center_distance": 50.0},
        }
        rows.append(attempt("ratio law mean (1 closes)", mean, data))
    for a in (0.1, 0.2, 0.3):
        data = {"mechanism": "roller-body", "body": {"direction": "vertical", "m": 3, "amplitude": a}}
        rows.append(attempt("roller body amplitude, m = 3", a, data))
    return rows
