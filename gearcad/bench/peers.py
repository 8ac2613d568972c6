"""gearcad beside its peer ncgears on the same pair, in the same run.

The pair: two ellipses a = 25 mm, e = 0.8 (b = 15 mm), each pivoted at a focus, 39 teeth each,
1:1, centre distance 2a = 50 mm; module = perimeter / (39π); 20° rack with gearcad's default
proportions (addendum 1, dedendum 1.25, tip radius 0.38, in modules); outlines written to DXF
within 0.001 mm.  ncgears builds it from the polar centrode r = b²/a / (1 − e·cos φ) (far apex at
φ = 0, as gearcad's) with ``generate_from_centrode`` and writes ``GearPair.export_dxf`` with
``max_error`` set to the same 0.001 mm.

Measured: whole-process wall time (fresh interpreter per run, runs interleaved, median), the
first call in process after the imports, the same call repeated warm in one process, peak
memory, vertices per written outline (read back with ezdxf), and how far each written outline is
from the exact one: from gearcad's closed-form envelope cut at 1e-6 mm on the exact ellipse (the
same method as gearcad's output, converged) and from the independent boolean rack cut (blank
minus rack copies, whose own floor is the distance between the two references).
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .commands import FOCUS_TEETH
from .outlines import deviation, deviations, largest_outline, signed_depth
from .process import Command, Measured, measure

if TYPE_CHECKING:
    from ..teeth.rack import Rack, RackParams

__all__ = ["PEER", "peer_version", "peer_command", "bench_peers", "GEARCAD_KEYS"]

PEER = "ncgears"
A, ECCENTRICITY = 25.0, 0.8
TOLERANCE = 1e-3
"""mm: what both tools are asked to write within."""
GEARCAD_KEYS = {"dxf": "gearcad, DXF only", "all": "gearcad, every output"}

_PEER_BODY = """
_encode = json.JSONEncoder.default
# ncgears 0.3.1 puts numpy.bool_ into metadata.json, which json cannot encode (numpy 2): without
# this it fails after generating; it costs nothing measurable
json.JSONEncoder.default = lambda self, o: o.item() if hasattr(o, "item") else _encode(self, o)
import numpy as np
import ncgears
imported = time.perf_counter()
calls = []
for _ in range(spec["calls"]):
    t = time.perf_counter()
    pair = ncgears.generate_from_centrode(spec["centrode"], name="pair", output_directory=".", **spec["options"])
    pair.export_dxf("pair.dxf", max_error=spec["max_error"])
    calls.append(time.perf_counter() - t)
np.save("drive_full.npy", pair.drive_outline)
extra = {"center_distance": pair.center_distance, "version": getattr(ncgears, "__version__", "?")}
"""


def peer_version() -> str | None:
    """The peer's version if it can be imported here, else None (without importing it)."""
    if importlib.util.find_spec(PEER) is None:
        return None
    try:
        return importlib.metadata.version(PEER)
    except importlib.metadata.PackageNotFoundError:
        return "?"


@dataclass(frozen=True)
class _Pair:
    """The exact pair: pitch curve, and gearcad's teeth on it."""

    module: float
    rack: Rack
    pitch_ring: np.ndarray
    envelope: np.ndarray
    rack_cut: np.ndarray | None
    rack_cut_seconds: float


def _perimeter() -> float:
    from scipy.special import ellipe

    return 4 * A * float(ellipe(ECCENTRICITY**2))


def peer_command(folder: Path, rack_params: RackParams) -> Command:
    """The peer building the pair and writing its DXF, as a child."""
    b2_over_a = A * (1 - ECCENTRICITY**2)
    module = _perimeter() / (FOCUS_TEETH * math.pi)
    options = {
        "teeth": FOCUS_TEETH,
        "module": module,
        "pressure_angle_deg": math.degrees(rack_params.pressure_angle),
        "addendum_factor": rack_params.addendum,
        "dedendum_factor": rack_params.dedendum,
        "fillet_factor": rack_params.tip_radius,
    }
    spec = {
        "centrode": f"{b2_over_a!r}/(1 - {ECCENTRICITY!r}*cos(phi))",
        "options": options,
        "max_error": TOLERANCE / module,  # ncgears takes it in modules
    }
    return Command(PEER, _PEER_BODY, spec, folder)


def _exact_pair(rack_cut_steps: int | None) -> _Pair:
    """The exact pair, built here rather than by gearcad's pipeline: the ellipse r = b²/(a − c·cos φ),
    gearcad's default rack, a tooth centred on the far apex (φ = 0)."""
    from ..pitch import shapes
    from ..teeth.frame import arc_frame
    from ..teeth.gear import cut_teeth
    from ..teeth.rack import Rack, RackParams
    from ..teeth.reference import rack_cut

    frame = arc_frame(shapes.ellipse_focus(A, A * math.sqrt(1 - ECCENTRICITY**2)))
    rack = Rack.from_params(RackParams(module=frame.perimeter / (FOCUS_TEETH * math.pi)))
    phase = rack.pitch / 2  # tooth space k centred at phase + k·pitch: a tooth at s = 0
    envelope = cut_teeth(frame, rack, FOCUS_TEETH, phase, tolerance=1e-6).outline.outer
    phi = np.linspace(0, 2 * math.pi, 1 << 12, endpoint=False)  # to sort points by depth: 1e-4 mm will do
    r = A * (1 - ECCENTRICITY**2) / (1 - ECCENTRICITY * np.cos(phi))
    cut, seconds = None, float("nan")
    if rack_cut_steps:
        start = time.perf_counter()
        poly = rack_cut(frame, rack, FOCUS_TEETH, phase, steps_per_pitch=rack_cut_steps, samples=1600)
        cut, seconds = np.asarray(poly.exterior.coords)[:-1], time.perf_counter() - start
    ring = np.column_stack([r * np.cos(phi), r * np.sin(phi)])
    return _Pair(rack.params.module, rack, ring, envelope, cut, seconds)


def _accuracy(points: np.ndarray, pair: _Pair) -> dict:
    """How far a written outline ((n, 2) mm) is from the exact one, whole and by region."""
    root = signed_depth(points, pair.pitch_ring) < pair.rack.v_low
    found = deviations(points, pair.envelope, {"flanks": ~root, "roots": root})  # each point measured once
    out = {"error": found["all"], "error_flanks": found["flanks"], "error_roots": found["roots"]}
    if pair.rack_cut is not None:
        out["error_rack_cut"] = deviation(points, pair.rack_cut)
    return out


def _row(method: str, m: Measured, **fields) -> dict:
    return {
        "study": "peers",
        "method": method,
        "n": FOCUS_TEETH,
        "seconds": m.wall,
        "seconds_cpu": m.cpu,
        "seconds_imports": m.imports,
        "seconds_in_process": m.in_process,
        "seconds_warm": m.warm_median,
        "peak_mb": m.peak_mb,
        "runs": len(m.runs),
        **fields,
    }


def bench_peers(
    gearcad: dict[str, Command],
    work: Path,
    *,
    runs: int,
    warm: dict[str, int],
    rack_cut_steps: int | None,
    step: Callable[[str], None] | None = None,
) -> tuple[list[dict], dict[str, Measured]]:
    """Rows of the peers study (gearcad's commands by key, the peer) and the measurements.

    ``warm`` gives extra in-process calls per key (``PEER`` for the peer)."""
    pair = _exact_pair(rack_cut_steps)
    peer = peer_command(work / PEER, pair.rack.params)
    measured = measure({**gearcad, PEER: peer}, runs=runs, warm_calls=warm, step=step)
    rows = []
    for key, command in gearcad.items():
        out = Path(command.spec["argv"][command.spec["argv"].index("--out") + 1]) / "elliptic_focus"
        written = largest_outline(out / "driver.dxf", "CUT")
        report = json.loads((out / "report.json").read_text(encoding="utf-8"))
        rows.append(
            _row(
                GEARCAD_KEYS.get(key, key),
                measured[key],
                vertices=written.vertices,
                arcs=written.arcs,
                centre_distance_error=abs(report["pair"]["center_distance"] - 2 * A),
                **_accuracy(written.points, pair),
            )
        )
    p = measured[PEER]
    written = largest_outline(peer.folder / "pair.dxf", "DRIVE")
    full = np.load(peer.folder / "drive_full.npy")
    version = p.runs[-1].extra.get("version", "?")
    rows.append(
        _row(
            f"{PEER} {version}, pair + DXF",
            p,
            vertices=written.vertices,
            arcs=written.arcs,
            centre_distance_error=abs(p.runs[-1].extra["center_distance"] - 2 * A),
            error_unsimplified=deviation(full, pair.envelope),
            **_accuracy(written.points, pair),
        )
    )
    if pair.rack_cut is not None:  # the two references against each other: the rack cut's own floor
        rows.append(
            {
                "study": "peers",
                "method": f"reference: boolean rack cut, {rack_cut_steps} copies per pitch",
                "n": FOCUS_TEETH,
                "seconds": pair.rack_cut_seconds,
                "error": deviation(pair.rack_cut, pair.envelope),
            }
        )
    for row in rows[: len(gearcad)]:
        row["speedup"] = p.wall / row["seconds"]
        row["speedup_in_process"] = p.in_process / row["seconds_in_process"]
        row["speedup_warm"] = p.warm_median / row["seconds_warm"] if p.warm else float("nan")
    return rows, measured
