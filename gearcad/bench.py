"""``gearcad bench``: speed against accuracy, side by side, and where methods break down.

Writes PNG charts, ``results.csv`` and ``results.md`` into the output folder.  Not a test:
timings depend on the machine (the numbers in the README come from the 2-core reference one).
"""

from __future__ import annotations

import csv
import logging
import math
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

__all__ = ["run_bench", "stability_map"]

log = logging.getLogger("gearcad")


class _Progress:
    """A one-line progress bar on stderr."""

    def __init__(self, total: int):
        self.total, self.done = total, 0

    def step(self, label: str) -> None:
        self.done += 1
        filled = int(30 * self.done / self.total)
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} {label:<40}")
        sys.stderr.flush()
        if self.done == self.total:
            sys.stderr.write("\n")


def _best_time(func, repeat: int = 3):
    best, result = math.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        result = func()
        best = min(best, time.perf_counter() - start)
    return best, result


# ------------------------------------------------------------------ quadrature


def bench_quadrature(quick: bool) -> list[dict]:
    """The centre-pivoted ellipse's closure turn ∫ r/(E − r) dφ at E = 40 mm by every method,
    and the walker's i by the paper's method against the closed form."""
    from numpy.polynomial.legendre import leggauss
    from scipy.integrate import quad

    from .pitch import shapes
    from .pitch import walker as W
    from .pitch.pair import angle_map

    curve = shapes.ellipse_centre(25.0, 15.0)
    e = 40.0

    def f(p):
        r = curve.r(p)
        return r / (e - r)

    with warnings.catch_warnings():  # QUADPACK warns that it cannot prove 1e-14; it reaches it
        warnings.simplefilter("ignore")
        reference = quad(f, 0, math.pi / 2, epsabs=1e-14, epsrel=1e-14, limit=400)[0] * 4
    rows = []
    for n in [8, 32, 128] if quick else [4, 8, 16, 32, 64, 128, 256, 1024]:
        t, v = _best_time(lambda n=n: 2 * math.pi / n * float(np.sum(f(np.arange(n) * 2 * math.pi / n))))
        rows.append(
            {"study": "quadrature", "method": "trapezoid (periodic)", "n": n, "seconds": t, "error": abs(v - reference)}
        )
        x, w = leggauss(n)

        def gauss(x=x, w=w):
            return math.pi * float(np.sum(w * f(math.pi * (x + 1))))

        t, v = _best_time(gauss)
        rows.append(
            {"study": "quadrature", "method": "Gauss-Legendre", "n": n, "seconds": t, "error": abs(v - reference)}
        )
    for eps in [1e-6, 1e-10] if quick else [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t, v = _best_time(lambda eps=eps: quad(f, 0, 2 * math.pi, epsabs=eps, epsrel=eps, limit=400)[0])
        rows.append(
            {
                "study": "quadrature",
                "method": "adaptive (QUADPACK)",
                "n": eps,
                "seconds": t,
                "error": abs(v - reference),
            }
        )
    t, amap = _best_time(lambda: angle_map(curve, e))
    rows.append(
        {
            "study": "quadrature",
            "method": "gearcad (Chebyshev, Clenshaw-Curtis)",
            "n": amap.forward.degree,
            "seconds": t,
            "error": abs(amap.turn - reference),
        }
    )
    g = W.WalkerGeometry(75.0, 100.0, 50.0, 322.0)
    t, (i_paper, _) = _best_time(lambda: W.paper_ratio_constant(g), 1)
    exact = W.ratio_law(g).i
    rows.append(
        {
            "study": "walker-i",
            "method": "paper: trapezoid 0.1°/0.4°, successive approximation",
            "n": 0,
            "seconds": t,
            "error": abs(i_paper - exact),
        }
    )
    t, law = _best_time(lambda: W.ratio_law(g))
    rows.append(
        {
            "study": "walker-i",
            "method": "gearcad: closure, closed form",
            "n": 0,
            "seconds": t,
            "error": abs(law.i - 2 * math.pi / (math.pi / 2 + 3 * g.b / g.K)),
        }
    )
    return rows


# ------------------------------------------------------------------ envelope


def bench_envelope(quick: bool) -> list[dict]:
    """Closed-form envelope against boolean subtraction of N rack copies: largest flank
    deviation from a converged reference (the envelope at 1e-6 mm; on a circle, the exact
    involute) against time."""
    import shapely

    from .pitch import shapes
    from .teeth.frame import arc_frame
    from .teeth.gear import cut_teeth
    from .teeth.rack import Rack, RackParams
    from .teeth.reference import rack_cut

    rows = []
    cases = [("circle z=20", shapes.circle(20.0), 20), ("ellipse z=41", shapes.ellipse_focus(25.0, 15.0), 41)]
    for label, curve, z in cases:
        frame = arc_frame(curve)
        rack = Rack.from_params(RackParams(module=frame.perimeter / (z * math.pi)))
        exact = cut_teeth(frame, rack, z, rack.pitch / 2, tolerance=1e-5 if quick else 1e-6).outline.outer
        exact_ring = shapely.LinearRing(exact)

        def deviation(ring):
            pts = shapely.points(np.asarray(ring))
            back = shapely.points(exact[:: max(1, len(exact) // 20000)])
            return float(
                max(shapely.distance(pts, exact_ring).max(), shapely.distance(back, shapely.LinearRing(ring)).max())
            )

        for tol in [1e-2, 1e-3] if quick else [1e-2, 1e-3, 1e-4]:
            t, gear = _best_time(
                lambda tol=tol: cut_teeth(frame, rack, z, rack.pitch / 2, tolerance=tol), 1 if quick else 3
            )
            rows.append(
                {
                    "study": f"envelope {label}",
                    "method": "gearcad closed-form envelope",
                    "n": tol,
                    "seconds": t,
                    "error": deviation(gear.outline.outer),
                }
            )
        for steps in [6] if quick else [6, 12, 24, 48, 96]:
            t, poly = _best_time(lambda s=steps: rack_cut(frame, rack, z, rack.pitch / 2, steps_per_pitch=s), 1)
            rows.append(
                {
                    "study": f"envelope {label}",
                    "method": "boolean: blank minus N rack copies",
                    "n": steps,
                    "seconds": t,
                    "error": deviation(np.asarray(poly.exterior.coords)[:-1]),
                }
            )
    return rows


# ------------------------------------------------------------------ output size


def bench_output(quick: bool, folder: Path) -> list[dict]:
    from .batch import build
    from .profiles import load_profile

    root = Path(__file__).resolve().parent.parent / "profiles"
    rows = []
    for tol in [0.01, 0.001] if quick else [0.1, 0.01, 0.001, 0.0001]:
        for flavour in ("polyline", "polyline-flat"):
            params = load_profile(
                root / "elliptic_focus.toml",
                [f"output.tolerance={tol}", f'output.dxf="{flavour}"', "output.charts=false", "output.animation=false"],
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


# ------------------------------------------------------------------ whole builds


_CHILD = """
import resource, sys, time, logging
logging.disable(logging.WARNING)
from pathlib import Path
from gearcad.profiles import load_profile
from gearcad.batch import build
p = load_profile(sys.argv[1], sys.argv[3:])
t = time.perf_counter()
r = build([p], Path(sys.argv[2]) / "out")
seconds = time.perf_counter() - t
try:  # this process's own high-water mark (ru_maxrss would include the parent's, kept across exec)
    hwm = next(int(l.split()[1]) for l in open("/proc/self/status") if l.startswith("VmHWM"))
except (OSError, StopIteration):
    hwm = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
Path(sys.argv[2], "measure.txt").write_text(f"{seconds} {hwm}")
"""


def _child_build(profile: Path, folder: Path, overrides: list[str]) -> tuple[float, float]:
    folder.mkdir(parents=True, exist_ok=True)
    subprocess.run(
        [sys.executable, "-c", _CHILD, str(profile), str(folder), *overrides],
        capture_output=True,
        text=True,
        check=True,
    )
    seconds, rss_kb = (folder / "measure.txt").read_text().split()
    return float(seconds), float(rss_kb) / 1024


def bench_builds(quick: bool, folder: Path, progress: _Progress | None) -> list[dict]:
    root = Path(__file__).resolve().parent.parent / "profiles"
    rows = []
    profiles = sorted(root.glob("*.toml"))
    if quick:
        profiles = [root / "spur_pair.toml"]
    for profile in profiles:
        seconds, mb = _child_build(profile, folder / "builds", ["output.charts=false", "output.animation=false"])
        rows.append({"study": "build", "method": profile.stem, "n": 0, "seconds": seconds, "error": 0.0, "peak_mb": mb})
        if progress:
            progress.step(f"build {profile.stem}")
    counts = [10, 40] if quick else [10, 20, 40, 80, 160, 400]
    for z in counts:
        seconds, mb = _child_build(
            root / "spur_pair.toml",
            folder / "scaling",
            [
                f"teeth.count={z}",
                f"gear1.radius={z}",
                "output.charts=false",
                "output.animation=false",
                "output.sheet=[5000, 5000]",
                "output.bed=[5000, 5000]",
            ],
        )
        rows.append(
            {
                "study": "teeth-scaling",
                "method": "spur pair, module 2",
                "n": z,
                "seconds": seconds,
                "error": 0.0,
                "peak_mb": mb,
            }
        )
    if progress:
        progress.step("scaling with teeth")
    return rows


# ------------------------------------------------------------------ stability map


def stability_map(quick: bool = False) -> list[dict]:
    """Hard designs and what gearcad does with each: 'ok', a warning code, or a clear error —
    never NaN, a hang or a silently wrong outline."""
    from .errors import GearcadError
    from .mechanisms import design
    from .profiles import parse_profile

    def attempt(label: str, value, data: dict, teeth: bool = True) -> dict:
        start = time.perf_counter()
        try:
            # large designs need a sheet and a bed to match: the map is about the design
            data = {**data, "output": {"sheet": [1e5, 1e5], "bed": [1e5, 1e5], **data.get("output", {})}}
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
    for ecc in [0.5, 0.9, 0.99] if quick else [0.0, 0.3, 0.6, 0.8, 0.9, 0.95, 0.99]:
        data = {
            "gear1": {"curve": "ellipse", "pivot": "centre", "a": 25.0, "eccentricity": ecc},
            "gear2": {"lobes": 2},
            "teeth": {"count": 40},
        }
        rows.append(attempt("ellipse (centre) eccentricity, 40 teeth", ecc, data))
    for z in [6, 17, 400] if quick else [6, 8, 12, 16, 17, 18, 40, 100, 400]:
        data = {"gear1": {"curve": "circle", "radius": float(z)}, "gear2": {"lobes": 1}, "teeth": {"count": z}}
        rows.append(attempt("spur pair 1:1, tooth count", z, data))
    for width in (0.0, 6.0):
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


# ------------------------------------------------------------------ report


def _write_csv(rows: list[dict], path: Path) -> None:
    keys = sorted({k for r in rows for k in r})
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def _markdown(rows: list[dict], stability: list[dict]) -> str:
    out = [
        "# gearcad benchmark",
        "",
        "| study | method | n / tol | time (ms) | error | extra |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        extra = ", ".join(
            f"{k} {r[k]:.0f}" if isinstance(r[k], float) else f"{k} {r[k]}"
            for k in ("vertices", "triangles", "bytes", "peak_mb")
            if k in r
        )
        out.append(
            f"| {r['study']} | {r['method']} | {r['n']:g} | {1000 * r['seconds']:.2f} | {r['error']:.2e} | {extra} |"
        )
    out += ["", "## Stability map", "", "| case | value | outcome | time (ms) |", "|---|---|---|---|"]
    out += [f"| {s['case']} | {s['value']:g} | {s['outcome']} | {1000 * s['seconds']:.0f} |" for s in stability]
    return "\n".join(out) + "\n"


def run_bench(out: Path, *, quick: bool = False) -> list[dict]:
    """Run every study and write the charts, CSV and markdown into ``out``."""
    from .export.charts import bench as charts_bench

    logging.disable(logging.WARNING)
    out.mkdir(parents=True, exist_ok=True)
    work = out / "work"
    builds = 1 if quick else len(list((Path(__file__).resolve().parent.parent / "profiles").glob("*.toml")))
    progress = _Progress(7 + builds)
    rows = bench_quadrature(quick)
    progress.step("quadrature")
    rows += bench_envelope(quick)
    progress.step("envelope")
    rows += bench_output(quick, work)
    progress.step("output size")
    rows += bench_builds(quick, work, progress)
    stability = stability_map(quick)
    progress.step("stability map")
    _write_csv(rows, out / "results.csv")
    _write_csv(stability, out / "stability.csv")
    (out / "results.md").write_text(_markdown(rows, stability), encoding="utf-8")
    charts_bench.speed_accuracy(rows, out / "speed_accuracy.png")
    charts_bench.output_size(rows, out / "output_size.png")
    charts_bench.builds(rows, out / "builds.png")
    progress.step("charts")
    charts_bench.stability(stability, out / "stability.png")
    progress.step("done")
    logging.disable(logging.NOTSET)
    return rows
