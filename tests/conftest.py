import fcntl
import json
import logging
import os
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).parent.parent
PROFILES = sorted((ROOT / "profiles").glob("*.toml"))


@pytest.fixture(scope="session")
def seed_tables() -> dict:
    """The papers' tables exactly as printed (copied from shared/reference/seed_tables.json)."""
    return json.loads((DATA / "seed_tables.json").read_text(encoding="utf-8"))


@pytest.fixture(scope="session")
def built(tmp_path_factory, worker_id) -> Path:
    """Every profile built once, with every output, shared by the tests that read files back —
    once for the whole run, also when pytest-xdist runs the tests in several processes (the
    first to arrive builds under a lock, the others wait and read)."""
    from gearcad.cli import main

    def build_all(out: Path) -> None:  # every chart audited as it is drawn (tests/test_pictures.py)
        os.environ["GEARCAD_CHART_AUDIT"] = str(out.parent / "chart_audit.jsonl")
        try:
            assert main(["build", *map(str, PROFILES), "--out", str(out)]) == 0
        finally:
            del os.environ["GEARCAD_CHART_AUDIT"]

    if worker_id == "master":  # one process
        out = tmp_path_factory.mktemp("build") / "out"
        build_all(out)
        return out
    shared = tmp_path_factory.getbasetemp().parent / "built"
    shared.mkdir(exist_ok=True)
    out, done = shared / "out", shared / "done"
    with open(shared / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not done.exists():
            build_all(out)
            done.write_text("ok")
    return out


@pytest.fixture(scope="session")
def golden() -> dict:
    """Every number the README states, with where it comes from (tests/data/golden.json)."""
    return json.loads((DATA / "golden.json").read_text(encoding="utf-8"))


@pytest.fixture(autouse=True)
def _quiet_design_warnings(caplog):
    caplog.set_level(logging.ERROR, logger="gearcad")
