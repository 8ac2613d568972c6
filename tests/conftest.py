import json
import logging
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
def built(tmp_path_factory) -> Path:
    """Every profile built once, with every output, shared by the tests that read files back."""
    from gearcad.cli import main

    out = tmp_path_factory.mktemp("build") / "out"
    assert main(["build", *map(str, PROFILES), "--out", str(out)]) == 0
    return out


@pytest.fixture(scope="session")
def golden() -> dict:
    """Every number the README states, with where it comes from (tests/data/golden.json)."""
    return json.loads((DATA / "golden.json").read_text(encoding="utf-8"))


@pytest.fixture(autouse=True)
def _quiet_design_warnings(caplog):
    caplog.set_level(logging.ERROR, logger="gearcad")
