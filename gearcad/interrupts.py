"""SIGINT and SIGTERM during a build: turned into one error, or held off while a step must finish.

:func:`interrupt_guard` makes either signal an :class:`Interrupted` (the one line to print, exit
code 128 + signal); :func:`held_signals` holds them off inside a block that must not be cut in
two (a publishing rename, a worker being forked and recorded) and delivers the first afterwards.
Python lets only the main thread handle signals: elsewhere both do nothing.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager, nullcontext
from pathlib import Path

from .errors import GearcadError

__all__ = ["Interrupted", "interrupt_guard", "held_signals"]

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
    """Hold SIGINT and SIGTERM off inside the block; deliver the first one afterwards."""
    caught: list[int] = []
    main = threading.current_thread() is threading.main_thread()
    try:
        with _handling(lambda signum, frame: caught.append(signum)) if main else nullcontext():
            yield
    finally:
        if caught and deliver:
            signal.raise_signal(caught[0])
