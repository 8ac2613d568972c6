#!/usr/bin/env python3
"""Set up and run gearcad with nothing but python3 and pip.

    python3 tasks.py build      # build every profile in profiles/ into out/
    python3 tasks.py test       # run the test suite
    python3 tasks.py consumers  # install the makers' programs (Debian) and run every consumer check

Each command first makes .venv (once) and installs gearcad into it (again only when
pyproject.toml changes; about 70 packages, 80 s on a fast connection, a line per package, the
whole log in .venv/pip-install.log), then runs.  Afterwards ``.venv/bin/gearcad`` is the command
line, with no activation needed.  Extra arguments are passed on: ``python3 tasks.py build
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
import time
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if os.name == "nt" else "bin")
PYTHON = BIN / ("python.exe" if os.name == "nt" else "python")
STAMP = VENV / ".gearcad-installed"
LOG = VENV / "pip-install.log"
LAUNCHER = f"{VENV.name}/{BIN.name}/gearcad"


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
    _say(INSTALLING)
    start = time.monotonic()
    extras = "test,sweep,optimise"
    command = [*pip, "install", "--disable-pip-version-check", "--progress-bar", "off", "-e", f"{ROOT}[{extras}]"]
    with (
        open(LOG, "w", encoding="utf-8") as log,
        subprocess.Popen(
            command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace"
        ) as pip_run,
    ):
        for shown in progress(_logged(pip_run.stdout, log)):
            _say(shown)
    if pip_run.returncode != 0:
        raise SystemExit(f"tasks: pip failed (exit {pip_run.returncode}); its whole output is in {LOG}")
    _say(f"installed in {time.monotonic() - start:.0f} s; the command line is now {LAUNCHER}")
    STAMP.write_text(want)


def _logged(lines, log):
    for line in lines:
        log.write(line)
        yield line


INSTALLING = (
    f"installing gearcad and the ~70 packages it needs (numpy, scipy, shapely, OpenCASCADE, matplotlib, "
    f"pytest, …; about 1 GB) into {VENV.name}/ — first run only, and again when pyproject.toml changes. "
    "It took 80 s on a fast connection; allow several minutes on a busy machine. One line per package:"
)


def progress(lines):
    """The lines to show of pip's output, each as it comes: one per package pip collects (with
    its download's size, or "cached"), one when it installs them all, pip's warnings and errors.
    The rest (requirements already met, hashes, metadata) goes only to the log."""
    pending = None
    for line in lines:
        text = line.strip()
        size = text.rsplit("(", 1)[1].rstrip(")") if text.endswith(")") and "(" in text else ""
        if pending and text.startswith("Downloading "):
            yield f"  {pending} ({size})" if size else f"  {pending}"
            pending = None
            continue
        if pending and text.startswith("Using cached "):
            yield f"  {pending} (cached)"
            pending = None
            continue
        if pending:
            yield f"  {pending}"
            pending = None
        if text.startswith("Collecting "):
            pending = text.removeprefix("Collecting ").split(" ", 1)[0]
        elif text.startswith("Installing collected packages:"):
            count = len(text.split(":", 1)[1].split(","))
            wait = " (unpacking and compiling: silent for a minute or so)" if count > 10 else ""
            yield f"  installing {count} package{'s' if count > 1 else ''}{wait}"
        elif text.startswith("Building wheels for collected packages:"):
            yield "  building " + text.split(":", 1)[1].strip()
        elif text.startswith(("ERROR", "WARNING", "error:")):
            yield "  " + text
    if pending:
        yield f"  {pending}"


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
        count = len(list(Path("profiles").glob("*.toml")))
        what = "the profiles given" if argv[1:] else f"the {count} profiles in profiles/ (a minute or so in all)"
        _say(f"{LAUNCHER} build: {what}, a line as each is built")
        return subprocess.run([str(BIN / "gearcad"), "build", *argv[1:]], env=_bytecode_kept()).returncode
    _say("running the test suite: pytest -q on every core (about 3 minutes on 2 cores; a dot per test)")
    return subprocess.run([str(PYTHON), "-m", "pytest", "-q", *argv[1:]], env=_bytecode_kept()).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
