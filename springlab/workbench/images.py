"""A figure file is rewritten only when what it shows changed.

The figures under ``figures/`` are committed, and rerunning the notebooks on another machine must
leave them unchanged. Their data can move in the last digits from one CPU to another (SIMD paths,
BLAS kernels, an optimiser's last iterations); a PNG rasterises the figure at its resolution, so
two runs whose PNGs have the same pixels show the same figure, while their SVGs may still differ
in a coordinate's sixth digit. :func:`save_png_and_svg` therefore renders the PNG in memory,
compares its pixels with the file already there, and writes the PNG and the SVG only when the
pixels differ (or a file is missing). :func:`unchanged_gif` does the same for an animation's
frames. The pixels are the digest: nothing is kept beside the figures.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np


def _pixels(source) -> tuple:
    from PIL import Image

    with Image.open(source) as im:
        return im.mode, im.size, np.asarray(im).tobytes()


def same_pixels(path, png: bytes) -> bool:
    """True when the PNG file ``path`` exists and has the same mode, size and pixels as the PNG
    in ``png`` (bytes)."""
    path = Path(path)
    if not path.is_file():
        return False
    try:
        return _pixels(path) == _pixels(io.BytesIO(png))
    except OSError:  # not a readable image: rewrite it
        return False


def save_png_and_svg(fig, png_path, svg_path, *, png_options: dict, svg_options: dict) -> bool:
    """Save ``fig`` as PNG and SVG unless the PNG on disk already has the same pixels and the SVG
    exists; returns True when the files were written."""
    png_path, svg_path = Path(png_path), Path(svg_path)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", **png_options)
    data = buffer.getvalue()
    if svg_path.is_file() and same_pixels(png_path, data):
        return False
    png_path.write_bytes(data)
    fig.savefig(svg_path, format="svg", **svg_options)
    return True


def unchanged_gif(path, frames: list, duration_ms: int) -> bool:
    """True when the GIF ``path`` exists with the same number of frames, the same frame duration
    and the same pixels in every frame as ``frames`` (Pillow images), each read in RGB."""
    from PIL import Image, ImageSequence

    path = Path(path)
    if not path.is_file():
        return False
    try:
        with Image.open(path) as gif:
            old = [(np.asarray(f.convert("RGB")).tobytes(), f.info.get("duration")) for f in ImageSequence.Iterator(gif)]
    except OSError:
        return False
    new = [np.asarray(f.convert("RGB")).tobytes() for f in frames]
    return len(old) == len(new) and all(o == n and d == duration_ms for (o, d), n in zip(old, new, strict=True))
