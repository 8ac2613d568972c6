"""An animated GIF of the pair turning through one full cycle (drawn with Pillow)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from ..geometry.arcfit import decimate
from ..geometry.outline import place

__all__ = ["write_gif"]

_COLOURS = ((31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40))


def write_gif(
    path: Path, rings: list[np.ndarray], pivots: list, angles: np.ndarray, *, size=(640, 400), frame_ms: int = 60
) -> int:
    """One frame per row of ``angles`` (frames, parts): each part's ring turned by its angle
    about its pivot (``pivots``: one per part, or (frames, parts, 2) where they move).  A part
    given as a list of rings is its outer ring and holes (a ring gear's toothed hole shows what
    turns in it); the largest parts are drawn first.  Returns the number of frames."""
    shapes = [list(r) if isinstance(r, (list, tuple)) else [r] for r in rings]
    reach = np.array([float(np.max(np.hypot(*r[0].T))) for r in shapes])
    order = np.argsort(-reach, kind="stable")
    moving = np.asarray(pivots, dtype=float)
    if moving.ndim == 2:
        moving = np.broadcast_to(moving, (len(angles), *moving.shape))
    lo = np.min(moving - reach[None, :, None], axis=(0, 1))
    hi = np.max(moving + reach[None, :, None], axis=(0, 1))
    margin = 10
    scale = min((size[0] - 2 * margin) / (hi[0] - lo[0]), (size[1] - 2 * margin) / (hi[1] - lo[1]))
    # a tenth of a pixel is all a frame can show: thin the rings to that once, not every frame
    shapes = [[decimate(r, 0.1 / scale) for r in rs] for rs in shapes]
    frames = []
    for row, pivots in zip(angles, moving):
        # index 0 white (the background every viewer shows), 1 black (outlines), then the parts'
        # colours; the palette is complete so that no viewer fills an unset entry with black
        image = Image.new("P", size, 0)
        image.putpalette([255, 255, 255, 0, 0, 0, *sum((list(c) for c in _COLOURS), [])] + [255, 255, 255] * 250)
        draw = ImageDraw.Draw(image)
        for k in order.tolist():
            pivot, angle = pivots[k], row[k]
            for j, ring in enumerate(shapes[k]):
                pts = place(ring, float(angle), pivot)
                xy = np.column_stack(
                    [(pts[:, 0] - lo[0]) * scale + margin, size[1] - ((pts[:, 1] - lo[1]) * scale + margin)]
                )
                draw.polygon(xy.round(1).ravel().tolist(), fill=0 if j else 2 + k % len(_COLOURS), outline=1)
            cx, cy = (pivot[0] - lo[0]) * scale + margin, size[1] - ((pivot[1] - lo[1]) * scale + margin)
            draw.ellipse([cx - 2, cy - 2, cx + 2, cy + 2], fill=1)
        frames.append(image)
    frames[0].save(path, save_all=True, append_images=frames[1:], duration=frame_ms, loop=0, optimize=False)
    return len(frames)
