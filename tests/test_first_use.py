"""The first ten minutes: the README's shell blocks run as printed after the quick start, and
``tasks.py`` says what it installs and shows its progress.

The README's commands run in a fresh folder (a copy of ``profiles/`` and a ``.venv/bin/gearcad``
as the quick start leaves it) under ``bash -e`` with a bare ``PATH`` (``/usr/bin:/bin``), so a
command the quick start does not provide (a bare ``gearcad``) fails there as it fails for a
reader.  To stay cheap, that ``.venv/bin/gearcad`` records its arguments and each recorded call
is then run in this process; a ``build`` gets a coarse tolerance and DXF only appended.  Not run:
the quick start itself and ``pip install`` (they install packages: :data:`NOT_RUN`) and the
command line's synopsis (optional arguments in brackets)."""

import importlib.util
import re
import shutil
import subprocess
import tomllib

import pytest

from gearcad.cli import main

from .conftest import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")

NOT_RUN = {
    "python3 tasks.py build": "the quick start: makes .venv and installs ~70 packages before it builds",
    "python3 tasks.py test": "the quick start: installs as above, then runs this suite",
    "pip install": "installs packages into the reader's environment",
}
"""Commands of the README's shell blocks that this test does not run, and why."""

CHEAP = ["--set", "output.tolerance=0.1", "--set", "output.charts=false", "--set", "output.animation=false"]
CHEAP += ["--set", 'output.formats=["dxf"]']

_END = "--end-of-call--"


def shell_blocks(text: str) -> list[list[str]]:
    """The commands of each fenced block that is not Python: one per line, comments dropped."""
    blocks = []
    for info, body in re.findall(r"^```(\w*)\n(.*?)^```", text, flags=re.M | re.S):
        if info in ("", "sh", "shell", "bash", "console"):
            lines = [re.sub(r"\s+#.*$", "", ln).strip() for ln in body.splitlines()]
            blocks.append([ln for ln in lines if ln and not ln.startswith("#")])
    return blocks


def _synopsis(command: str) -> bool:
    return re.search(r"\[(--|[A-Z])", command) is not None


def _runnable(command: str) -> bool:
    return not _synopsis(command) and not any(command.startswith(skip) for skip in NOT_RUN)


def test_the_readme_shell_blocks_are_commands_run_skipped_or_a_synopsis():
    commands = [c for block in shell_blocks(README) for c in block]
    assert "python3 tasks.py build" in commands and any(c.startswith("pip install") for c in commands)
    run = [c for c in commands if _runnable(c)]
    assert [".venv/bin/gearcad", "new"] in [c.split()[:2] for c in run] and len(run) >= 2, run
    bare = [c for c in run if c.split()[0] == "gearcad"]
    assert not bare, f"{bare}: not on PATH after the quick start; write .venv/bin/gearcad"
    synopses = [c for c in commands if _synopsis(c)]
    assert all(c.startswith("gearcad ") for c in synopses) and len(synopses) >= 6


def test_the_readme_commands_run_as_printed_after_the_quick_start(tmp_path, monkeypatch):
    folder = tmp_path / "gearcad"
    shutil.copytree(ROOT / "profiles", folder / "profiles")
    calls = tmp_path / "calls"
    launcher = folder / ".venv" / "bin" / "gearcad"  # what pip makes of [project.scripts]
    launcher.parent.mkdir(parents=True)
    launcher.write_text(f'#!/bin/sh\nfor a in "$@" {_END}; do printf "%s\\0" "$a"; done >> "{calls}"\n')
    launcher.chmod(0o755)
    script = "\n".join(c for block in shell_blocks(README) for c in block if _runnable(c))
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path), "LANG": "C.UTF-8"}
    done = subprocess.run(["bash", "-e", "-c", script], cwd=folder, env=env, capture_output=True, text=True)
    assert done.returncode == 0, f"as printed, the README's commands fail in a fresh checkout: {done.stderr}"
    recorded = calls.read_text(encoding="utf-8").split("\0")[:-1]
    monkeypatch.chdir(folder)
    while recorded:
        argv = recorded[: recorded.index(_END)]
        del recorded[: len(argv) + 1]
        assert main(argv + (CHEAP if argv[0] == "build" else [])) == 0, argv
    profile = tomllib.loads((folder / "my_gears.toml").read_text(encoding="utf-8"))
    assert profile["name"] == "my_gears"
    assert (folder / "out" / "my_gears" / "report.json").is_file()


def test_the_launcher_the_readme_names_is_what_pip_installs():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert project["scripts"]["gearcad"] == "gearcad.cli:run"  # pip writes .venv/bin/gearcad
    assert "`.venv/bin/gearcad` is the command line" in README


def _tasks():
    spec = importlib.util.spec_from_file_location("tasks", ROOT / "tasks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


PIP = """\
Looking in indexes: https://example.invalid/simple
Obtaining file:///src/gearcad
  Installing build dependencies: started
  Preparing editable metadata (pyproject.toml): finished with status 'done'
Collecting numpy>=1.26 (from gearcad==0.1.0)
  Downloading numpy-2.1.0-cp311-cp311-manylinux_2_17_x86_64.whl (16.3 MB)
Collecting scipy>=1.11 (from gearcad==0.1.0)
  Using cached scipy-1.14.0-cp311-cp311-manylinux_2_17_x86_64.whl (41.2 MB)
Requirement already satisfied: pillow>=9.0 in ./.venv/lib/python3.11/site-packages (from gearcad==0.1.0) (10.4.0)
Collecting shapely>=2.0
  Obtaining dependency information for shapely>=2.0 from https://example.invalid/shapely.metadata
Building wheels for collected packages: gearcad
  Building editable for gearcad (pyproject.toml): started
  Created wheel for gearcad: filename=gearcad-0.1.0-0.editable-py3-none-any.whl size=2620 sha256=80a1
Installing collected packages: shapely, scipy, numpy, gearcad
Successfully installed gearcad-0.1.0 numpy-2.1.0 scipy-1.14.0 shapely-2.0.6
"""


def test_tasks_shows_a_line_per_package_it_installs():
    tasks = _tasks()
    shown = list(tasks.progress(PIP.splitlines(keepends=True)))
    assert shown == [
        "  numpy>=1.26 (16.3 MB)",
        "  scipy>=1.11 (cached)",
        "  shapely>=2.0",
        "  building gearcad",
        "  installing 4 packages",
    ]
    assert "80 s" in tasks.INSTALLING and "70 packages" in tasks.INSTALLING  # as measured (issue 37)


@pytest.mark.parametrize("command", ["build", "test"])
def test_tasks_says_what_it_runs_before_it_runs_it(command, monkeypatch, capsys):
    tasks = _tasks()
    ran = []
    monkeypatch.setattr(tasks, "ensure_environment", lambda: None)
    monkeypatch.setattr(tasks.os, "chdir", lambda path: None)
    monkeypatch.setattr(tasks.subprocess, "run", lambda argv, **kw: ran.append(capsys.readouterr().out) or _Done())
    assert tasks.main([command]) == 0
    assert ran and ran[0].startswith("tasks: ")
    assert ("pytest" if command == "test" else ".venv/bin/gearcad build") in ran[0]


class _Done:
    returncode = 0
