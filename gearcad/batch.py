"""Build a batch of profiles into folders of files: design, write into staging, publish atomically.

Every profile is designed (and so checked) and written into a staging folder; only when every
profile has built are the folders published into ``out``, each folder atomically (see
:mod:`gearcad.publish`).  Several profiles are built side by side, one process per core.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import signal
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from .errors import GearcadError, ProfileError
from .findings import Finding
from .mechanisms import Design, design
from .profiles import ProfileParams
from .publish import Interrupted, Publisher, check_out, interrupt_guard

__all__ = ["BuildResult", "build", "design_all"]


@dataclass(frozen=True)
class BuildResult:
    """A built profile: its one-line summary, findings, the files written (the report's files
    block) and the time.  (The design itself stays in the worker: ``gearcad.design`` gives it.)"""

    name: str
    summary: str
    findings: tuple[Finding, ...]
    files: dict[str, dict]
    seconds: float


def _unique(profiles: Sequence[ProfileParams]) -> None:
    names = [p.name for p in profiles]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ProfileError(f"name = {duplicates[0]!r}: two profiles build into the same folder")


def _named(params: ProfileParams, work: Callable[[], object]):
    """Run ``work``; an error names the profile it came from (an interrupt is the whole build's,
    and passes as it is).  The error's message is renamed, not the error made anew, so that one
    whose constructor takes more than a message keeps its type and fields."""
    try:
        return work()
    except Interrupted:
        raise
    except GearcadError as exc:
        exc.args = (f"{params.name}: {exc}", *exc.args[1:])
        raise exc from None


def design_all(profiles: Sequence[ProfileParams]) -> list[Design]:
    """Design every profile (every check a build makes, no file written)."""
    _unique(profiles)
    return [_named(p, lambda p=p: design(p)) for p in profiles]


def _build_one(job: tuple[ProfileParams, Path, bool]) -> BuildResult:
    params, folder, beside = job
    start = time.perf_counter()
    from .export.write import write_design  # the file libraries only when files are written

    d = _named(params, lambda: design(params))
    files = _named(params, lambda: write_design(d, folder, beside=beside))
    return BuildResult(d.name, d.summary, d.findings, files, time.perf_counter() - start)


def _worker_init() -> None:
    # the parent handles Ctrl-C and SIGTERM for the whole build and ends the workers
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _workers(count: int) -> int:
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(count, cores))


def build(
    profiles: Sequence[ProfileParams],
    out: str | Path,
    progress: Callable[[int, int, BuildResult], None] | None = None,
    *,
    workers: int | None = None,
) -> list[BuildResult]:
    """Build every profile into ``out/<name>/``; publish only when all have built.

    ``workers`` processes build side by side (default: one per available core, at most one per
    profile); results come back in the profiles' order.
    """
    out = Path(out)
    check_out(out)
    _unique(profiles)
    count = _workers(len(profiles)) if workers is None else max(1, workers)
    results: list[BuildResult] = []
    with interrupt_guard(out), Publisher(out) as publisher:
        # a core left over (one profile on two cores): each build draws its pictures beside its files
        beside = _workers(len(profiles) + 1) > count
        jobs = [(p, publisher.folder(p.name), beside) for p in profiles]
        if count == 1:
            built = map(_build_one, jobs)
            pool = None
        else:
            pool = multiprocessing.get_context("fork").Pool(count, initializer=_worker_init)
            built = pool.imap(_build_one, jobs)
        try:
            for n, result in enumerate(built, 1):
                results.append(result)
                if progress:
                    progress(n, len(jobs), result)
        finally:
            if pool is not None:
                pool.terminate()
                pool.join()
        publisher.commit()
    _write_index(out)
    return results


def _write_index(out: Path) -> None:
    """``out/index.html`` over every profile folder in ``out`` (this build's and earlier ones'),
    replaced in one step."""
    from .export.html_index import index_entry, write_index

    entries = []
    for report_path in sorted(out.glob("*/report.json")):
        try:
            report = json.loads(report_path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue  # a folder that is not a build of ours
        name = report_path.parent.name
        entries.append(index_entry(report, f"{name}/index.html", report.get("summary", "")))
    staged = out / ".index.html.tmp"
    write_index(staged, entries)
    os.replace(staged, out / "index.html")
