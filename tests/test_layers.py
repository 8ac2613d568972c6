"""The package's layer order is a contract: profile → mechanism design → parts → files."""

import subprocess
import sys
from pathlib import Path

from .conftest import ROOT


def test_import_contracts_hold():
    """import-linter (configured in pyproject.toml) finds no import against the flow."""
    lint = Path(sys.executable).parent / "lint-imports"
    result = subprocess.run([str(lint)], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:]
    assert "broken" in result.stdout and "0 broken" in result.stdout


def test_no_module_is_a_catch_all():
    """Small modules named for what they hold: none over ~400 lines, no *_more / misc / utils."""
    for path in (ROOT / "gearcad").rglob("*.py"):
        lines = len(path.read_text(encoding="utf-8").splitlines())
        assert lines <= 450, f"{path.relative_to(ROOT)} has {lines} lines"
        assert not any(word in path.stem for word in ("_more", "misc", "utils", "other")), path


def test_import_gearcad_is_cheap():
    """``import gearcad`` loads neither the numerical stack's heavy parts nor any exporter."""
    heavy = "('matplotlib', 'ezdxf', 'manifold3d', 'scipy')"
    code = f"import sys, gearcad; print(sorted(m for m in {heavy} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
