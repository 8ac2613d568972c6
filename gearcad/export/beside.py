"""Work done beside the writing loop, in a forked process that shares the design as it is.

Charts and the animation take about as long as every other file together, and need nothing
but the design: when a core is free (one profile on a machine with two or more), a forked
child draws them while the parent writes the rest. Forking shares the design without
pickling it; the child sends back only its result (the files it wrote) or its error.

The child ignores SIGINT (the parent handles Ctrl-C for the whole build), dies with the
parent (Linux ``PR_SET_PDEATHSIG``), and is killed and reaped if the parent stops waiting
for it, so nothing outlives a build or writes after it ended.
"""

from __future__ import annotations

import ctypes
import os
import pickle
import signal
import threading
import traceback
from collections.abc import Callable
from typing import Any

from ..errors import GearcadError

__all__ = ["Beside", "can_fork"]

_PR_SET_PDEATHSIG = 1


def can_fork() -> bool:
    """Whether forking is safe here: POSIX, and no other Python thread that the child would lose
    halfway through its work.  (Native worker pools — manifold3d's TBB threads — are not seen;
    the child uses only matplotlib and Pillow, which do not touch them.)"""
    return hasattr(os, "fork") and threading.active_count() == 1


def _die_with_parent(parent: int) -> None:
    try:
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    except (OSError, AttributeError):  # not Linux: the parent still kills the child when it stops waiting
        pass
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)


class Beside:
    """``work()`` run in a forked child; :meth:`result` waits for its value (or raises its
    error), :meth:`cancel` ends it. Use ``try: … finally: job.cancel()``."""

    def __init__(self, work: Callable[[], Any]):
        parent = os.getpid()
        read, write = os.pipe()
        try:
            self._pid = os.fork()
        except BaseException:
            os.close(read)
            os.close(write)
            raise
        if self._pid == 0:  # the child: never returns
            os.close(read)
            try:
                signal.signal(signal.SIGINT, signal.SIG_IGN)
                signal.signal(signal.SIGTERM, signal.SIG_DFL)
                _die_with_parent(parent)
                try:
                    payload = ("ok", work())
                except BaseException as exc:  # noqa: BLE001 - every error goes back to the parent
                    payload = ("error", exc, traceback.format_exc())
                try:
                    data = pickle.dumps(payload)
                except Exception:  # noqa: BLE001 - an error that cannot be pickled: its text
                    exc = payload[1]
                    data = pickle.dumps(("error", GearcadError(f"{type(exc).__name__}: {exc}"), payload[2]))
                with os.fdopen(write, "wb") as fh:
                    fh.write(data)
            finally:
                os._exit(0)
        os.close(write)
        self._read: int | None = read
        self._done = False

    def result(self) -> Any:
        """The child's value, once it has finished; its error raised here (with the child's
        traceback as a note), or a :class:`GearcadError` if it ended without a result."""
        read, self._read = self._read, None
        with os.fdopen(read, "rb") as fh:
            data = fh.read()
        _, status = os.waitpid(self._pid, 0)
        self._done = True
        try:
            payload = pickle.loads(data)
        except Exception:  # noqa: BLE001 - nothing (killed), or an error that does not unpickle
            how = f"killed by signal {os.WTERMSIG(status)}" if os.WIFSIGNALED(status) else "without its result"
            raise GearcadError(f"the process drawing beside the build ended {how}") from None
        if payload[0] == "error":
            _, exc, child_traceback = payload
            exc.add_note(f"in the process drawing beside the build:\n{child_traceback}")
            raise exc
        return payload[1]

    def cancel(self) -> None:
        """End the child if it is still running (no-op after :meth:`result`)."""
        if self._done:
            return
        self._done = True
        try:
            os.kill(self._pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        os.waitpid(self._pid, 0)
        if self._read is not None:
            os.close(self._read)
            self._read = None
