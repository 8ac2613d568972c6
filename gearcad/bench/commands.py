"""The gearcad runs that the peers and goals sections time, as command lines.

Each is what a user types (``gearcad build …``), run as :func:`gearcad.cli.main` in a fresh
process; the same run serves both sections when both are on.
"""

from __future__ import annotations

from pathlib import Path

from .process import Command, cli_command

__all__ = ["PROFILES", "FOCUS_TEETH", "gearcad_commands", "DXF_ONLY"]

PROFILES = Path(__file__).resolve().parents[2] / "profiles"
FOCUS_TEETH = 39
"""Teeth on each gear of the focus-pivoted ellipse pair (a = 25 mm, e = 0.8) timed against the peer."""

DXF_ONLY = ['output.formats=["dxf"]', "output.charts=false", "output.animation=false"]

_LARGE_SHEET = ["output.sheet=[10000, 10000]", "output.bed=[10000, 10000]"]
"""A sheet and a bed as large as a 2000-tooth gear of module 2 (4 m across): layout is not timed."""


def _build(profiles: list[Path], sets: list[str], out: Path) -> list[str]:
    argv = ["build", *map(str, profiles)]
    for value in sets:
        argv += ["--set", value]
    return [*argv, "--out", str(out)]


def gearcad_commands(work: Path) -> dict[str, tuple[str, Command]]:
    """key → (description, command); every command writes under ``work/<key>``."""
    focus = PROFILES / "elliptic_focus.toml"
    count = [f"teeth.count={FOCUS_TEETH}", "teeth.backlash=0"]  # the exact teeth the references cut
    specs = {
        "dxf": ("focus pair, 39 teeth, DXF only", _build([focus], count + DXF_ONLY, work / "dxf" / "out")),
        "all": ("focus pair, 39 teeth, every output", _build([focus], count, work / "all" / "out")),
        "check": ("gearcad check elliptic_focus.toml", ["check", str(focus)]),
        "profiles": (
            "gearcad build of every profile",
            _build(sorted(PROFILES.glob("*.toml")), [], work / "profiles" / "out"),
        ),
        "teeth2000": (
            "spur pair 1000:2000 teeth (module 2), DXF + STL",
            _build(
                [PROFILES / "spur_pair.toml"],
                [
                    "teeth.count=1000",
                    "gear1.radius=1000",
                    'output.formats=["dxf", "stl"]',
                    "output.charts=false",
                    "output.animation=false",
                    *_LARGE_SHEET,
                ],
                work / "teeth2000" / "out",
            ),
        ),
        "nc_square": (
            "the square noncircular planetary set (issue 38), every output",
            _build([PROFILES / "nc_square.toml"], [], work / "nc_square" / "out"),
        ),
        "nc_square_check": ("gearcad check nc_square.toml", ["check", str(PROFILES / "nc_square.toml")]),
        "tol1e-4": (
            "focus pair, 39 teeth, tolerance 1e-4 mm, DXF only",
            _build([focus], count + ["output.tolerance=0.0001", *DXF_ONLY], work / "tol1e-4" / "out"),
        ),
    }
    return {key: (text, cli_command(key, argv, work / key)) for key, (text, argv) in specs.items()}
