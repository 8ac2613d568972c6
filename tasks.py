#!/usr/bin/env python3
"""Set up and run gearcad with nothing but python3 and pip.

    python3 tasks.py build     # build every profile in profiles/ into out/
    python3 tasks.py test      # run the test suite

Each command first makes .venv (once) and installs gearcad into it (again only when
pyproject.toml changes), then runs.  Extra arguments are passed on: ``python3 tasks.py build
profiles/walker.toml --out /tmp/x`` or ``python3 tasks.py test -k walker``.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if os.name == "nt" else "bin")
PYTHON = BIN / ("python.exe" if os.name == "nt" else "python")
STAMP = VENV / ".gearcad-installed"


def _say(message: str) -> None:
    print(f"tasks: {message}", flush=True)


def ensure_environment() -> None:
    """Create .venv and install gearcad with its test tools unless already up to date."""
    want = hashlib.sha256((ROOT / "pyproject.toml").read_bytes()).hexdigest()
    if STAMP.exists() and STAMP.read_text().strip() == want and PYTHON.exists():
        return
    if not PYTHON.exists():
        _say(f"creating {VENV.relative_to(ROOT)}")
        try:
            venv.create(VENV, with_pip=True, clear=True)
        except Exception as exc:  # noqa: BLE001 - Debian without python3-venv lacks ensurepip
            _say(f"venv with pip failed ({exc}); creating it without pip and using this pip")
            venv.create(VENV, with_pip=False, clear=True)
    pip = [str(PYTHON), "-m", "pip"]
    if subprocess.run([*pip, "--version"], capture_output=True).returncode != 0:
        pip = [sys.executable, "-m", "pip", "--python", str(PYTHON)]
    _say("installing gearcad and its dependencies (first run only)")
    subprocess.run([*pip, "install", "--quiet", "--disable-pip-version-check", "-e", f"{ROOT}[test]"], check=True)
    STAMP.write_text(want)


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in {"build", "test"}:
        print(__doc__.strip())
        return 2
    ensure_environment()
    os.chdir(ROOT)
    if argv[0] == "build":
        return subprocess.run([str(BIN / "gearcad"), "build", *argv[1:]]).returncode
    return subprocess.run([str(PYTHON), "-m", "pytest", "-q", *argv[1:]]).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
