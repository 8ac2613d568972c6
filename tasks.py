#!/usr/bin/env python3
"""Set up and run gearcad with nothing but python3 and pip.

    python3 tasks.py build      # build every profile in profiles/ into out/
    python3 tasks.py test       # run the test suite
    python3 tasks.py consumers  # install the makers' programs (Debian) and run every consumer check

Each command first makes .venv (once) and installs gearcad into it (again only when
pyproject.toml changes), then runs.  Extra arguments are passed on: ``python3 tasks.py build
profiles/walker.toml --out /tmp/x`` or ``python3 tasks.py test -k walker``.

``consumers`` installs, with apt-get (as root, or through sudo), the programs that
tests/test_consumers.py drives — OpenSCAD, LibreCAD, Inkscape (with the Python modules its DXF
import needs), PrusaSlicer, lib3mf, poppler-utils (pdftoppm, pdftocairo), Chromium (the HTML
report's browser test) and FreeCAD (the STEP files) — printing each command before it runs it,
then runs that test file, FreeCAD's DXF import and the STEP read-back on every part of every
profile (``GEARCAD_CONSUMERS=all``).  ``consumers --install-only`` stops after installing;
``consumers --no-install`` only runs the checks.
"""

from __future__ import annotations

import hashlib
import os
import shutil
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
    subprocess.run([*pip, "install", "--quiet", "--disable-pip-version-check", "-e", f"{ROOT}[test,sweep]"], check=True)
    STAMP.write_text(want)


CONSUMER_PACKAGES = (
    "openscad",
    "librecad",
    "inkscape",
    "python3-lxml",  # Inkscape's extensions (its DXF import) run on the system python3
    "python3-numpy",
    "python3-cssselect",
    "prusa-slicer",
    "lib3mf1",
    "poppler-utils",
    "chromium",
    "freecad",  # the STEP solids (tests/test_consumers.py) and the DXF import's settings (tests/test_freecad_dxf.py)
)


def _run(command: list[str]) -> None:
    _say("running: " + " ".join(command))
    subprocess.run(command, check=True)


def install_consumers() -> None:
    """apt-get update, then apt-get install the consumer programs (no recommended extras)."""
    if shutil.which("apt-get") is None:
        raise SystemExit(
            f"tasks: no apt-get here; install these with your package manager: {' '.join(CONSUMER_PACKAGES)}"
        )
    sudo = [] if os.name != "nt" and os.geteuid() == 0 else ["sudo"]
    if sudo and shutil.which("sudo") is None:
        raise SystemExit("tasks: installing needs root: run this as root, or install sudo")
    env = ["env", "DEBIAN_FRONTEND=noninteractive"]
    _run([*sudo, *env, "apt-get", "update"])
    _run([*sudo, *env, "apt-get", "install", "-y", "--no-install-recommends", *CONSUMER_PACKAGES])


def consumers(args: list[str]) -> int:
    if "--no-install" not in args:
        install_consumers()
    if "--install-only" in args:
        return 0
    ensure_environment()
    os.chdir(ROOT)
    rest = [a for a in args if a not in {"--no-install", "--install-only"}]
    env = dict(os.environ, GEARCAD_CONSUMERS="all")
    command = [
        str(PYTHON),
        "-m",
        "pytest",
        "-q",
        "tests/test_consumers.py",
        "tests/test_freecad_dxf.py",
        "tests/test_step_profiles.py",
        *rest,
    ]
    _say("running: GEARCAD_CONSUMERS=all " + " ".join(command))
    return subprocess.run(command, env=env).returncode


def _bytecode_kept() -> dict[str, str]:
    """The environment less ``PYTHONDONTWRITEBYTECODE``: the checkout's modules are compiled once
    into their ``__pycache__`` (ignored by git), as pip compiles an installed package, and pytest
    keeps its rewritten test modules there.  With the variable set (some shells and containers
    set it) every test worker and every ``gearcad`` process the tests start compiled them all
    again: about 2 s of CPU a worker, 0.1 s a process."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in {"build", "test", "consumers"}:
        print(__doc__.strip())
        return 2
    if argv[0] == "consumers":
        return consumers(argv[1:])
    ensure_environment()
    os.chdir(ROOT)
    if argv[0] == "build":
        return subprocess.run([str(BIN / "gearcad"), "build", *argv[1:]], env=_bytecode_kept()).returncode
    return subprocess.run([str(PYTHON), "-m", "pytest", "-q", *argv[1:]], env=_bytecode_kept()).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
