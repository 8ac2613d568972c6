"""``gearcad bench``: speed against accuracy, side by side with the peer, the speed goals, and
where methods break down.

Writes PNG charts, ``results.csv``, ``stability.csv`` and ``results.md`` into the output folder.
Not a test: timings depend on the machine (the numbers in the README come from the 2-core
reference one).  One module per study: :mod:`.quadrature`, :mod:`.envelope`, :mod:`.output`,
:mod:`.builds`, :mod:`.stability`, :mod:`.peers`, :mod:`.goals`; :mod:`.process` runs whole
processes, :mod:`.timing` times in process, :mod:`.report` writes, :mod:`.run` runs them all.
"""

from __future__ import annotations

from .run import SECTIONS, run_bench
from .stability import stability_map

__all__ = ["run_bench", "stability_map", "SECTIONS"]
