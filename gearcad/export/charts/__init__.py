"""PNG charts a reviewer would rather look at than read: one module per kind of mechanism.

matplotlib is imported only when a chart is drawn (it costs a quarter of a second to import).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["draw_charts"]


def draw_charts(design, folder: Path) -> list[str]:
    """Draw the design's charts into ``folder``; return the file names written."""
    if design.mechanism == "gear-pair":
        from . import pair

        return pair.draw(design, folder)
    from . import mechanisms

    return mechanisms.draw(design, folder)
