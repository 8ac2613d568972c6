"""The one PNG writer of the charts: matplotlib without a display, no creation time."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

__all__ = ["plt", "save_png", "PolyCollection"]

_META = {"Software": "gearcad"}  # no creation time: the same design gives the same bytes


def save_png(fig, path: Path) -> None:
    """Write a figure without a creation time (the same chart gives the same bytes) and free it."""
    fig.savefig(path, dpi=110, metadata=_META)
    plt.close(fig)
