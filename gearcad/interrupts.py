"""SIGINT and SIGTERM during a build: turned into one error, or held off while a step must finish;
and a worker process that ends with its parent.

:func:`interrupt_guard` makes either signal an :class:`Interrupted` (the one line to print, exit
code 128 + signal); :func:`held_signals` holds them off inside a block that must not be cut in
two (a publishing rename, a worker being forked and recorded) and delivers the first afterwards.
Python lets only the main thread handle signals: elsewhere both do nothing.  :func:`end_with_parent`,
run first in a pool's worker, makes the worker end when its parent does, whatever ended it
(SIGKILL, the out-of-memory killer, a CI timeout).
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time
from contextlib import contextmanager, nullcontext
from pathlib import Path

from .errors import GearcadError

__all__ = ["Interrupted", "interrupt_guard", "held_signals", "end_with_parent", "WATCH_SECONDS"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(GearcadError):
    """SIGINT or SIGTERM ended the build; the message is one line, ``exit_code`` 128 + signal."""

    def __init__(self, message: str, signum: int) -> None:
        super().__init__(message)
        self.signum = signum
        self.exit_code = 128 + signum

    def __reduce__(self):  # raised in a process pool's worker, it crosses back by pickle
        return type(self), (str(self), self.signum)


def interrupt_guard(out: Path | str | None = None):
    """A context manager turning SIGINT and SIGTERM into :class:`Interrupted` (main thread only).

    Parameters
    ----------
    out : path, optional
        The output folder, named in the message ``interrupted; <out> left as it was``.
    """

    def interrupt(signum, frame):
        raise Interrupted(f"interrupted; {out} left as it was" if out else "interrupted", signum)

    if threading.current_thread() is not threading.main_thread():  # Python lets only it handle signals
        return nullcontext()
    return _handling(interrupt)


@contextmanager
def _handling(handler):
    previous = {s: signal.signal(s, handler) for s in _SIGNALS}
    try:
        yield
    finally:
        for s, old in previous.items():
            signal.signal(s, signal.SIG_DFL if old is None else old)


@contextmanager
def held_signals(*, deliver: bool = True):
    """Hold SIGINT and SIGTERM off inside the block; deliver the first one afterwards.

    The block gets the list of signals caught so far: a loop that waits in short steps can
    leave as soon as one comes, and so take it at a point of its own choosing (never inside a
    library's lock, which an exception raised from a handler could leave held).
    """
    caught: list[int] = []
    main = threading.current_thread() is threading.main_thread()
    try:
        with _handling(lambda signum, frame: caught.append(signum)) if main else nullcontext():
            yield caught
    finally:
        if caught and deliver:
            signal.raise_signal(caught[0])


_PR_SET_PDEATHSIG = 1
WATCH_SECONDS = 0.5
"""How often a worker looks for its parent, where the system cannot tell it (the fallback)."""


def end_with_parent(parent: int) -> None:
    """End this process (a pool's worker) when ``parent``, the process that forked it, ends.

    On Linux the kernel sends SIGKILL at once (``prctl(PR_SET_PDEATHSIG)``; it fires when the
    *thread* that forked this process ends, so pools are forked from the main thread); a daemon
    thread checks every :data:`WATCH_SECONDS` that the parent is still this process's parent
    (an orphan is adopted by another), for systems without prctl and as a second guard.  A
    parent already gone before this ran is caught by the same check, at once.
    """
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):  # no libc prctl: the watchdog alone
            pass
    if os.getppid() != parent:
        os._exit(1)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(WATCH_SECONDS)
        os._exit(1)

    threading.Thread(target=watch, name="gearcad-watch-parent", daemon=True).start()
