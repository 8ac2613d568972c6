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
import stat
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager, nullcontext, suppress
from dataclasses import dataclass
from pathlib import Path

from .errors import GearcadError, OutputError, ProfileError, shown
from .findings import Finding
from .fitting import design
from .interrupts import Interrupted, end_with_parent, held_signals, interrupt_guard
from .mechanisms import Design
from .profiles import ProfileParams
from .publish import Publisher, check_out, out_lock
from .threads import cores, set_threads

__all__ = ["BuildResult", "build", "design_all", "worker_pool", "submit_all", "finished"]


@dataclass(frozen=True)
class BuildResult:
    """A built profile: its one-line summary, findings, the files written (the report's files
    block) and the time.  (The design itself stays in the worker: ``gearcad.design`` gives it.)"""

    name: str
    summary: str
    findings: tuple[Finding, ...]
    files: dict[str, dict]
    seconds: float
    failures: tuple[Finding, ...] = ()
    """The findings that fail a check (``Design.failures``), before any ``--allow``."""


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


def design_all(profiles: Sequence[ProfileParams], stage: str = "full") -> list[Design]:
    """Design every profile (every check a build makes, or a stage's, no file written)."""
    _unique(profiles)
    return [_named(p, lambda p=p: design(p, stage)) for p in profiles]


def _build_one(job: tuple[ProfileParams, Path, bool]) -> BuildResult:
    params, folder, beside = job
    start = time.perf_counter()
    d = _named(params, lambda: design(params))
    files = _named(params, lambda: _write(d, folder, beside))
    return BuildResult(d.name, d.summary, d.findings, files, time.perf_counter() - start, d.failures())


def _write(d: Design, folder: Path, beside: bool) -> dict[str, dict]:
    """The design's files in ``folder``; a write the system refuses is an :class:`OutputError`."""
    from .export.write import write_design  # the file libraries only when files are written

    try:
        return write_design(d, folder, beside=beside)
    except OSError as exc:  # a full disk (ENOSPC, EDQUOT), a read-only or failing filesystem
        if isinstance(exc, BrokenPipeError):  # the reader of our output has gone: the CLI's to handle
            raise
        where = shown(Path(exc.filename).name) if exc.filename else "its files"
        raise OutputError(f"{where}: cannot write ({exc.strerror or exc}); nothing was published") from None


def _worker_init(parent: int, busy: bool) -> None:
    end_with_parent(parent)  # killed by any signal, the parent takes its workers with it
    # the parent handles Ctrl-C and SIGTERM for the whole build and ends the workers
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if busy:  # a worker on every core: threads beside a design would only add CPU time
        set_threads(1)


@contextmanager
def worker_pool(count: int, *, busy: bool) -> Iterator[ProcessPoolExecutor]:
    """A pool of ``count`` worker processes, forked, that never outlive this one.

    Leaving the block — at its end, on an error or an interrupt — cancels the queued work and
    ends the workers at once (not after their running tasks); a parent killed outright (SIGKILL,
    the out-of-memory killer) takes them with it (:func:`gearcad.interrupts.end_with_parent`).
    ``busy``: a worker on every core, so each runs one thread.  Submit with :func:`submit_all`.
    An executor, not ``multiprocessing.Pool``: a worker killed breaks it, never hangs it.
    """
    before = set(multiprocessing.active_children())
    pool = ProcessPoolExecutor(
        count, mp_context=multiprocessing.get_context("fork"), initializer=_worker_init, initargs=(os.getpid(), busy)
    )
    try:
        yield pool
    finally:
        with held_signals(deliver=False):  # one interrupt is being handled: a second may not cut this short
            _stop(pool, before)


def submit_all(pool: ProcessPoolExecutor, fn: Callable, items: Sequence[tuple]) -> list[Future]:
    """``pool.submit(fn, *item)`` for each item, every worker forked (from this thread: the main
    one, as :func:`gearcad.interrupts.end_with_parent` needs) and recorded before an interrupt lands."""
    with held_signals():
        return [pool.submit(fn, *item) for item in items]


STEP = 0.1
"""Seconds a wait on the pool's work lasts before it looks for a held signal."""


def finished(futures: Sequence[Future], *, ordered: bool = False) -> Iterator[Future]:
    """Each of ``futures`` once it is done: in the order given, or as they finish.

    Ctrl-C and SIGTERM are held while waiting and delivered between waits (within
    :data:`STEP` s): raised at any moment, they could land inside the executor's own locks and
    leave them held, and its shutdown — and the exit — would hang.
    """
    pending = list(futures)
    while pending:
        with held_signals() as caught:
            done: set = set()
            while not caught and not done:
                done = wait(pending[:1] if ordered else pending, timeout=STEP, return_when=FIRST_COMPLETED).done
        for future in [f for f in pending if f in done]:
            pending.remove(future)
            yield future


def _in_order(futures: list, jobs: list) -> Iterator[BuildResult]:
    """The pool's results in the jobs' order; a worker that died is one line naming its profiles."""
    for future in finished(futures, ordered=True):
        try:
            yield future.result()
        except BrokenProcessPool:
            lost = [job[0].name for job, f in zip(jobs, futures, strict=True) if _broken(f)]
            raise GearcadError(
                f"{', '.join(lost)}: the build process ended abruptly (killed, e.g. by the out-of-memory "
                "killer?); nothing was published"
            ) from None


def _broken(future) -> bool:
    return future.done() and not future.cancelled() and isinstance(future.exception(), BrokenProcessPool)


def _stop(pool: ProcessPoolExecutor, before: set) -> None:
    """End the pool's workers now (an error or an interrupt in the parent), not after their builds."""
    workers = list((getattr(pool, "_processes", None) or {}).values())  # no public way before 3.14
    # and any child forked since the pool was made but not yet recorded by it: none may outlive it
    workers += [w for w in multiprocessing.active_children() if w not in workers and w not in before]
    pool.shutdown(wait=False, cancel_futures=True)
    # SIGKILL, not SIGTERM: a worker forked a moment ago still has the parent's handlers (the
    # one that holds signals while workers are forked) until its initializer runs, and would
    # take SIGTERM as held and go on to build a whole profile while this waited for it
    for worker in workers:
        worker.kill()
    # until none is left: a worker forked while this collected them (the executor's own thread
    # may spawn one as another dies) is taken too; joining one never killed would wait forever
    # (one left waiting on the call queue's lock, held by a worker killed here, never returns)
    while alive := [w for w in {*workers, *multiprocessing.active_children()} - before if w.is_alive()]:
        for worker in alive:
            worker.kill()
        for worker in alive:
            worker.join(timeout=STEP)
    for worker in workers:
        worker.join()


def _workers(count: int) -> int:
    return max(1, min(count, cores()))


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
    check_out(out)
    _unique(profiles)
    if not profiles:  # nothing to publish: out is left as it is (not made)
        return []
    count = _workers(len(profiles)) if workers is None else max(1, workers)
    results: list[BuildResult] = []
    with interrupt_guard(out), Publisher(out) as publisher:
        # a core left over (one profile on two cores): each build draws its pictures beside its files
        beside = _workers(len(profiles) + 1) > count
        with _writing(f"--out {shown(out)}: cannot make a folder to build in"):
            jobs = [(p, publisher.folder(p.name), beside) for p in profiles]
        with worker_pool(count, busy=count >= cores()) if count > 1 else nullcontext() as pool:
            if pool is None:
                built = map(_build_one, jobs)
            else:
                built = _in_order(submit_all(pool, _build_one, [(job,) for job in jobs]), jobs)
            for n, result in enumerate(built, 1):
                results.append(result)
                if progress:
                    progress(n, len(jobs), result)
        publisher.commit()
    with _writing(f"--out {shown(out)}: the profiles were published, but not index.html over them"):
        _write_index(publisher.path)
    return results


@contextmanager
def _writing(what: str):
    """A full disk (ENOSPC, EDQUOT), a read-only or failing filesystem: one line, not a traceback."""
    try:
        yield
    except OSError as exc:
        if isinstance(exc, BrokenPipeError):  # the reader of our output has gone: the CLI's to handle
            raise
        raise OutputError(f"{what} ({exc.strerror or exc})") from None


def _write_index(out: Path) -> None:
    """``out/index.html`` over every profile folder in ``out`` (this build's and earlier ones'),
    replaced in one step.

    ``out`` is the resolved output folder (one resolution for every write).  Only reports that
    gearcad wrote are read: a regular file (never a link, FIFO or device, so nothing blocks),
    of bounded size, a JSON object with gearcad's schema number and the folder's own name.  The
    page is written into a new file made exclusively under a random name (a planted link is
    never followed), then renamed over ``index.html``.
    """
    try:
        with out_lock(out):  # a concurrent build's page, read before this one published, is not the last
            _write_page(out)
    except OSError as exc:
        reason = exc.strerror or exc
        raise OutputError(f"{out / 'index.html'}: cannot write ({reason}); the profiles were published") from None


def _write_page(out: Path) -> None:
    from .export.html_index import index_entry, index_page

    entries = []
    for folder in sorted(out.iterdir(), key=lambda p: p.name):
        report = _our_report(folder)
        if report is None:
            continue
        try:
            entries.append(index_entry(report, f"{folder.name}/index.html", str(report.get("summary", ""))))
        except (KeyError, TypeError, AttributeError, ValueError):  # a report.json not of ours after all
            continue
    fd, staged = tempfile.mkstemp(prefix=".gearcad-index-", suffix=".tmp", dir=out)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(index_page(entries))
        os.chmod(staged, 0o666 & ~_umask())
        os.replace(staged, out / "index.html")
    except BaseException:
        with suppress(OSError):
            os.unlink(staged)
        raise


_REPORT_LIMIT = 64 << 20
"""The largest report.json the index reads (a build's is well under 1 MB)."""


def _our_report(folder: Path) -> dict | None:
    """The report in ``folder`` if gearcad wrote it there, else ``None``."""
    from .mechanisms.base import SCHEMA_VERSION

    path = folder / "report.json"
    try:
        if not stat.S_ISDIR(os.lstat(folder).st_mode):
            return None
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > _REPORT_LIMIT:
            return None
        with os.fdopen(fd, "rb") as fh:
            fd = -1
            report = json.loads(fh.read(_REPORT_LIMIT + 1))
    except (OSError, ValueError, RecursionError):
        return None
    finally:
        if fd >= 0:
            os.close(fd)
    if not isinstance(report, dict) or report.get("schema") != SCHEMA_VERSION or report.get("name") != folder.name:
        return None
    return report


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
