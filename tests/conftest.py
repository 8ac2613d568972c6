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


@pytest.fixture(autouse=True)
def _quiet_design_warnings(caplog):
    caplog.set_level(logging.ERROR, logger="gearcad")
