"""Output size: vertices, triangles and bytes of one 41-tooth elliptic gear against tolerance."""

from __future__ import annotations

from pathlib import Path

from .commands import PROFILES

__all__ = ["bench_output"]


def bench_output(quick: bool, folder: Path) -> list[dict]:
    from ..batch import build
    from ..profiles import load_profile

    rows = []
    for tol in [0.01] if quick else [0.1, 0.01, 0.001, 0.0001]:
        for flavour in ("polyline",) if quick else ("polyline", "polyline-flat"):
            params = load_profile(
                PROFILES / "elliptic_focus.toml",
                [
                    f"output.tolerance={tol}",
                    f'output.dxf="{flavour}"',
                    'output.formats=["dxf", "stl"]' if flavour == "polyline" else 'output.formats=["dxf"]',
                    "output.charts=false",
                    "output.animation=false",
                ],
            )
            result = build([params], folder / f"size-{tol}-{flavour}")[0]
            f = result.files
            rows.append(
                {
                    "study": "output",
                    "method": f"DXF {flavour}",
                    "n": tol,
                    "seconds": result.seconds,
                    "error": tol,
                    "vertices": f["driver.dxf"]["vertices"],
                    "bytes": f["driver.dxf"]["bytes"],
                }
            )
            if flavour == "polyline":
                rows.append(
                    {
                        "study": "output",
                        "method": "STL",
                        "n": tol,
                        "seconds": result.seconds,
                        "error": tol,
                        "triangles": f["driver.stl"]["triangles"],
                        "bytes": f["driver.stl"]["bytes"],
                    }
                )
    return rows
