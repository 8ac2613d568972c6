"""Build profiles into folders of files: design every profile, then write and publish them.

Everything is designed (and so checked) before anything is written; files are written into a
staging folder and published into ``out`` only when every profile has built.
"""

from __future__ import annotations

import shutil
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from .errors import GearcadError, ProfileError
from .export.write import write_design
from .mechanisms import Design, design
from .profiles import ProfileParams

__all__ = ["BuildResult", "build", "design_all"]


@dataclass(frozen=True)
class BuildResult:
    """A built profile: its design, the files written (the report's files block) and the time."""

    design: Design
    files: dict[str, dict]
    seconds: float

    @property
    def name(self) -> str:
        return self.design.name

    @property
    def summary(self) -> str:
        return self.design.summary


def design_all(profiles: Sequence[ProfileParams]) -> list[Design]:
    """Design every profile; an error names the profile it came from."""
    names = [p.name for p in profiles]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ProfileError(f"name = {duplicates[0]!r}: two profiles build into the same folder")
    designs = []
    for params in profiles:
        try:
            designs.append(design(params))
        except GearcadError as exc:
            raise type(exc)(f"{params.name}: {exc}") from None
    return designs


def build(
    profiles: Sequence[ProfileParams],
    out: str | Path,
    progress: Callable[[int, int, BuildResult], None] | None = None,
) -> list[BuildResult]:
    """Build every profile into ``out/<name>/``; all or nothing."""
    out = Path(out)
    designs = design_all(profiles)
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}-staging-", dir=out.parent))
    try:
        results = []
        for n, d in enumerate(designs, 1):
            start = time.perf_counter()
            folder = staging / d.name
            folder.mkdir()
            files = write_design(d, folder)
            result = BuildResult(d, files, d.seconds + time.perf_counter() - start)
            results.append(result)
            if progress:
                progress(n, len(designs), result)
        out.mkdir(exist_ok=True)
        for d in designs:
            target = out / d.name
            if target.exists():
                target.rename(staging / f".previous-{d.name}")
            (staging / d.name).rename(target)
        return results
    finally:
        shutil.rmtree(staging, ignore_errors=True)
