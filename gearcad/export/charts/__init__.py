"""PNG charts a reviewer would rather look at than read: one module per kind of chart, each drawing the
charts a design's ``charts`` name (the mechanism chose them).

matplotlib is imported only when a chart is drawn (it costs a quarter of a second to import).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["draw_charts"]


def draw_charts(design, folder: Path) -> list[str]:
    """Draw the charts the design's ``charts`` name into ``folder``; return the file names written."""
    from . import mechanisms, pair

    return pair.draw(design, folder) + mechanisms.draw(design, folder)
