import fcntl
import functools
import gc
import json
import logging
import math
import os
from pathlib import Path

import numpy as np
import pytest

if os.environ.get("PYTEST_XDIST_WORKER"):  # a test process on every core: designs run no threads beside
    os.environ.setdefault("GEARCAD_THREADS", "1")  # (gearcad.threads; tests/test_threads.py runs both ways)


def pytest_collection_finish(session):
    """What the imports and the collection made lives to the end of the run: frozen out of the
    garbage collector's full passes, which walked those ~400 000 objects some 16 times a worker
    (about 5 CPU-s of the suite's 140); and young objects collected every 10 000 allocations, not
    700, so that full passes come about 8 times a worker, not 35.  In turn with the same tests
    without it: 117 against 124 s of user CPU."""
    gc.collect()
    gc.freeze()
    gc.set_threshold(10_000, 10, 10)


DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).parent.parent
EXAMPLES = ROOT / "profiles"
PROFILES = sorted(EXAMPLES.glob("*.toml"))
QUICK = {"output.charts": False, "output.animation": False}
"""Overrides for a design read in memory: no chart data, no animation."""
COARSE = {**QUICK, "output.tolerance": 0.01}
"""And at a coarse tolerance: cheap, and exact where the mechanism tests look (closed forms)."""


def profile(name: str, overrides=(), **kwargs):
    """The example profile ``name`` (profiles/NAME.toml) loaded with ``overrides``."""
    from gearcad.profiles import load_profile

    return load_profile(EXAMPLES / f"{name}.toml", overrides, **kwargs)


def drawn(params):
    """The design of ``params`` as drawn and finished, with no fit search and no band (what
    ``gearcad.design`` makes less the fitting): for tests of the drawing alone — the cut paths,
    a reference outline — where the fit's proof is most of the CPU and changes no vertex."""
    from gearcad.fitting.fit import made
    from gearcad.mechanisms.finish import finish
    from gearcad.mechanisms.registry import MECHANISMS

    return finish(MECHANISMS[params.mechanism].design(made(params)))


def drafted(name: str, design, overrides=()):
    """The example profile ``name`` at :data:`COARSE` (and ``overrides``) and what a mechanism
    module's ``design`` draws of it: (params, draft)."""
    params = profile(name, {**COARSE, **dict(overrides)})
    return params, design(params)


def reach(ring: np.ndarray, placement, toward):
    """How far a placed ring reaches from its pivot in the direction ``toward`` (rad, global):
    its radius there (a float; an array for an array of directions), interpolated between the
    ring's vertices (mm).  Independent of the code's own placement: the turn is undone on the
    angle, not applied to the points."""
    angle, radius = np.arctan2(ring[:, 1], ring[:, 0]), np.hypot(ring[:, 0], ring[:, 1])
    out = np.interp(np.asarray(toward) - placement.angle, angle, radius, period=2 * np.pi)
    return float(out) if out.ndim == 0 else out


def tooth_angle(ring: np.ndarray, placement, toward: float, pitch: float, *, space: bool = False) -> float:
    """The global direction (rad) of the middle of the tooth (``space``: of the tooth space) of a
    placed ring nearest ``toward``, found from the ring's radius alone within half a ``pitch``
    (rad) either way: the mean direction where it comes within 1 % of its depth of its farthest
    (nearest) reach."""
    t = toward + np.linspace(-pitch / 2, pitch / 2, 4001)
    r = reach(ring, placement, t) * (-1 if space else 1)
    return float(np.mean(t[r >= r.max() - 0.01 * (r.max() - r.min())]))


def bulge_arc(a: np.ndarray, b: np.ndarray, bulge: float) -> tuple[np.ndarray, float, float]:
    """The circle of a DXF bulge segment from ``a`` to ``b``, worked out by hand (not with
    gearcad's own bulge code): (centre, radius, sweep), sweep = 4·atan(bulge) (rad, positive
    counter-clockwise), radius = chord / (2·|sin(sweep/2)|)."""
    chord = float(np.hypot(*(b - a)))
    sweep = 4 * math.atan(bulge)
    radius = chord / (2 * abs(math.sin(sweep / 2)))
    left = np.array([a[1] - b[1], b[0] - a[0]]) / chord
    centre = (a + b) / 2 + left * radius * math.cos(sweep / 2) * math.copysign(1, sweep)
    return centre, radius, sweep


@functools.cache
def read_dxf(path: Path):
    """A DXF file as ezdxf reads it, read once per test process: the ``built`` files are read
    by several tests (each only looks)."""
    import ezdxf

    return ezdxf.readfile(path)


@pytest.fixture(scope="session")
def seed_tables() -> dict:
    """The papers' tables exactly as printed: the package data the report's ``papers`` block reads
    (gearcad/data/seed_tables.json, copied from shared/reference/seed_tables.json)."""
    return json.loads((ROOT / "gearcad" / "data" / "seed_tables.json").read_text(encoding="utf-8"))


def _once(tmp_path_factory, worker_id, name: str, build) -> Path:
    """``build(out)`` run once for the whole test run, also when pytest-xdist runs the tests in
    several processes (the first to arrive builds under a lock, the others wait and read)."""
    if worker_id == "master":  # one process
        out = tmp_path_factory.mktemp(name) / "out"
        build(out)
        return out
    shared = tmp_path_factory.getbasetemp().parent / name
    shared.mkdir(exist_ok=True)
    out, done = shared / "out", shared / "done"
    with open(shared / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not done.exists():
            build(out)
            done.write_text("ok")
    return out


@pytest.fixture(scope="session")
def built(tmp_path_factory, worker_id) -> Path:
    """Every profile built once, with every output, shared by the tests that read files back."""
    from gearcad.cli import main

    def build_all(out: Path) -> None:  # every chart audited as it is drawn (tests/test_pictures.py)
        os.environ["GEARCAD_CHART_AUDIT"] = str(out.parent / "chart_audit.jsonl")
        try:
            assert main(["build", *map(str, PROFILES), "--out", str(out)]) == 0
        finally:
            del os.environ["GEARCAD_CHART_AUDIT"]

    return _once(tmp_path_factory, worker_id, "built", build_all)


STEP_BUILD = {**COARSE, "output.formats": ["step", "3mf", "dxf"]}
"""What :func:`built_step` sets: STEP beside the files it is checked against, at 0.01 mm."""
STEP_PROFILES = (
    PROFILES
    if os.environ.get("GEARCAD_CONSUMERS", "") == "all"
    else [EXAMPLES / f"{n}.toml" for n in ("elliptic_focus", "planetary_internal", "rolling_wheel", "walker")]
)
"""The profiles :func:`built_step` writes: in the suite one of each kind of straight part (teeth
on a noncircular curve, a ring's internal teeth, a plain wheel and a kerf, the walker's shoe) —
the twisted teeth are the herringbone profile's in tests/test_step.py, at 0.1 mm and 4 mm thick,
where a 0.01 mm build would add 4 CPU-s for the same faces; every profile, the herringbone at
0.01 mm among them, with ``GEARCAD_CONSUMERS=all`` (``python3 tasks.py consumers``)."""


@pytest.fixture(scope="session")
def built_step(tmp_path_factory, worker_id) -> Path:
    """Every profile's STEP files (every part and the assembly) with its 3MF and DXF, written
    once at :data:`STEP_BUILD` for the tests that read them back (tests/test_step_profiles.py,
    FreeCAD's import in tests/test_consumers.py), report.json beside them."""
    from gearcad.export.write import write_design

    def build_all(out: Path) -> None:  # in this process, one after another: no pool to start
        for path in STEP_PROFILES:
            design = drawn(profile(path.stem, STEP_BUILD))  # (the solids are tested: no fit, no band)
            folder = out / path.stem
            folder.mkdir(parents=True)
            write_design(design, folder)

    return _once(tmp_path_factory, worker_id, "built_step", build_all)


@pytest.fixture(scope="session")
def golden() -> dict:
    """Every number the README states, with where it comes from (tests/data/golden.json)."""
    return json.loads((DATA / "golden.json").read_text(encoding="utf-8"))


@pytest.fixture(autouse=True)
def _quiet_design_warnings(caplog):
    caplog.set_level(logging.ERROR, logger="gearcad")
