"""Every example profile with a D-flat and a keyway bore at kerf 0.1, 0.15, 0.2 and 0.3 mm.

    .venv/bin/python scripts/kerf_matrix.py [profile.toml ...]

Prints one line per case: built (with the cut paths' largest distance from the exact offset and
whether every written ring is simple) or the refusal; exits 1 when any case is refused.
"""

from __future__ import annotations

import logging
import sys
import time
from pathlib import Path

import gearcad
from gearcad.errors import DesignError, GearcadError
from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.rings import offset_outline
from gearcad.geometry.verify import is_simple, max_distance

KERFS = (0.1, 0.15, 0.2, 0.3)
FLAT = {"large": {"bore.diameter": 6.0, "bore.flat": 2.5}, "small": {"bore.diameter": 3.0, "bore.flat": 1.2}}
KEYWAY = {
    "large": {"bore.diameter": 8.0, "bore.keyway_width": 2.0, "bore.keyway_depth": 1.0},
    "small": {"bore.diameter": 4.0, "bore.keyway_width": 1.0, "bore.keyway_depth": 0.5},
}
BORES = {"D-flat": FLAT, "keyway": KEYWAY}
"""Each bore at the size a pivot has room for: "small" where "large" leaves too little wall."""


def verify(d) -> tuple[float, bool]:
    """The written cut paths' largest distance from the exact kerf offset, and all simple."""
    out = d.params.output
    worst, simple = 0.0, True
    for part in d.parts():
        exact = offset_outline(part.fine, out.kerf / 2, out.tolerance / 16, what="kerf")
        for ring, want in zip(part.cut, exact.rings):
            pts = arc_points(ring, out.tolerance / 16)
            simple &= is_simple(pts)
            worst = max(worst, max_distance(pts, want), max_distance(want, pts))
    return worst, simple


def main(paths: list[str]) -> int:
    logging.disable(logging.WARNING)  # the findings are not what this script is about
    failed = 0
    for path in paths or sorted(Path("profiles").glob("*.toml")):
        for label, sizes in BORES.items():
            bore = sizes["large"]
            for kerf in KERFS:
                over = {**bore, "output.kerf": kerf}
                start = time.perf_counter()
                try:
                    try:
                        d = gearcad.design(gearcad.load_profile(path, over))
                    except DesignError as exc:
                        if not str(exc).startswith("bore."):
                            raise
                        bore = sizes["small"]
                        over = {**bore, "output.kerf": kerf}
                        d = gearcad.design(gearcad.load_profile(path, over))
                    worst, simple = verify(d)
                    ok = simple and worst <= d.params.output.tolerance
                    failed += not ok
                    shape = "simple" if simple else "NOT SIMPLE"
                    text = f"built, cut paths {shape}, {1000 * worst:.2f} µm from the exact offset"
                except GearcadError as exc:
                    failed += 1
                    text = f"REFUSED: {exc}"
                bore_text = ", ".join(f"{k.split('.')[1]}={v:g}" for k, v in bore.items())
                seconds = time.perf_counter() - start
                print(
                    f"{Path(path).stem:22s} {label:6s} ({bore_text}) kerf {kerf:<4g}: {text} [{seconds:.1f} s]",
                    flush=True,
                )
    print(f"{failed} case(s) failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
