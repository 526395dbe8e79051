"""Episode media: an MP4 at the policy camera and PNGs of the first and last frame."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ladev_lib.arrays import Array


def write_png(path: Path, image: Array) -> None:
    from PIL import Image

    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp.png")
    Image.fromarray(np.ascontiguousarray(image, dtype=np.uint8)).save(tmp)
    tmp.replace(path)


def write_mp4(path: Path, frames: Sequence[Array], fps: int) -> None:
    import imageio.v2 as imageio

    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp.mp4")
    # H.264 needs even sides; yuv420p plays everywhere (browsers, slides).
    h, w = frames[0].shape[:2]
    h2, w2 = h - h % 2, w - w % 2
    with imageio.get_writer(
        tmp, fps=fps, codec="libx264", pixelformat="yuv420p", macro_block_size=1
    ) as writer:
        for f in frames:
            # imageio types get_writer's result as its plugin base class, which does not declare
            # append_data; the ffmpeg writer it returns has it (imageio v2 API, pinned).
            writer.append_data(np.ascontiguousarray(f[:h2, :w2], dtype=np.uint8))  # type: ignore[attr-defined]
    tmp.replace(path)
