"""In-process timing that a shared, loaded machine cannot bend much.

Each configuration is timed in rounds, all configurations once per round (interleaved), so a
burst of load from elsewhere slows every configuration alike instead of one of them; a call too
short for the clock is repeated within a measurement.  The minimum over rounds is the cost of
the work itself (load only ever adds to it); the median says how noisy the machine was.
"""

from __future__ import annotations

import statistics
import sys
import time
from collections.abc import Callable, Hashable, Mapping
from dataclasses import dataclass

__all__ = ["Progress", "Timing", "time_interleaved", "time_once"]

_MIN_MEASUREMENT = 2e-3
"""s: a measurement shorter than this is mostly clock and loop; short calls are repeated."""


class Progress:
    """A one-line progress bar on stderr."""

    def __init__(self, total: int):
        self.total, self.done = total, 0

    def step(self, label: str) -> None:
        self.done = min(self.done + 1, self.total)
        filled = int(30 * self.done / self.total)
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} {label:<40}")
        sys.stderr.flush()
        if self.done == self.total:
            sys.stderr.write("\n")

    def finish(self) -> None:
        """End the line even if fewer steps were taken than counted."""
        if self.done < self.total:
            self.done = self.total - 1
            self.step("done")


@dataclass(frozen=True)
class Timing:
    best: float
    """s per call: the fastest round."""
    median: float
    """s per call: the median round."""
    result: object
    """What the last call returned."""


def time_interleaved(funcs: Mapping[Hashable, Callable[[], object]], rounds: int) -> dict[Hashable, Timing]:
    """Time every function in ``rounds`` interleaved rounds (after one warm-up call each)."""
    results, number = {}, {}
    for key, func in funcs.items():  # warm-up, and how many calls make one measurement
        start = time.perf_counter()
        results[key] = func()
        once = max(time.perf_counter() - start, 1e-9)
        number[key] = max(1, min(1000, int(_MIN_MEASUREMENT / once) + 1)) if once < _MIN_MEASUREMENT else 1
    per_call: dict[Hashable, list[float]] = {key: [] for key in funcs}
    for _ in range(rounds):
        for key, func in funcs.items():
            start = time.perf_counter()
            for _ in range(number[key]):
                results[key] = func()
            per_call[key].append((time.perf_counter() - start) / number[key])
    return {key: Timing(min(t), statistics.median(t), results[key]) for key, t in per_call.items()}


def time_once(func: Callable[[], object], rounds: int) -> Timing:
    """One function, timed as :func:`time_interleaved` times each of several."""
    return time_interleaved({0: func}, rounds)[0]
