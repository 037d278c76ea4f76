"""A grey PNG height image as a :class:`~robodesc.meshes.heightfield.HeightGrid`, read by Pillow.

Gazebo's heightmap convention: black is the lowest point, white ``size[2]`` above it, the image
spans ``size[0]`` by ``size[1]`` metres centred on its frame's origin, and the image's top row is
the +y edge. 8- and 16-bit grey images are read as they are; colour images by their luminance."""

from __future__ import annotations

import numpy as np

from robodesc.ir.geometry import Vec3
from robodesc.meshes.heightfield import MAX_CELLS, HeightfieldError, HeightGrid

MAX_PIXELS = MAX_CELLS


def read_height_image(path: str, size: Vec3) -> HeightGrid:
    from PIL import Image  # Pillow: only for a PNG terrain

    Image.MAX_IMAGE_PIXELS = MAX_PIXELS  # a decompression bomb is refused before it is decoded
    try:
        with Image.open(path) as image:
            if image.width * image.height > MAX_PIXELS:
                raise HeightfieldError(f"{image.width} x {image.height} pixels: more than {MAX_PIXELS:,}")
            if image.width < 2 or image.height < 2:
                raise HeightfieldError("a height image needs at least 2 x 2 pixels")
            if image.mode in ("I;16", "I;16B", "I;16L", "I"):
                pixels = np.asarray(image, dtype=np.float64)
                top = 65535.0
            else:
                pixels = np.asarray(image.convert("L"), dtype=np.float64)
                top = 255.0
    except (OSError, Image.DecompressionBombError) as exc:
        raise HeightfieldError(f"not a readable PNG height image: {exc}") from None
    rows, cols = pixels.shape
    if not (size[0] > 0 and size[1] > 0 and size[2] >= 0):
        raise HeightfieldError(f"size {size}: extents must be positive")
    # The grid's row 0 is the lowest y; the image's row 0 is its top (+y) edge.
    z = np.flipud(pixels) / top * size[2]
    step_x, step_y = size[0] / (cols - 1), size[1] / (rows - 1)
    if abs(step_x - step_y) > 1e-9 * max(step_x, step_y):
        z, step = _square(z, step_x, step_y)
    else:
        step = step_x
    rows, cols = z.shape
    return HeightGrid(z, -(cols - 1) * step / 2, -(rows - 1) * step / 2, step, 0.0, 0, 0)


def _square(z: np.ndarray, step_x: float, step_y: float) -> tuple[np.ndarray, float]:
    """Resample to square cells at the finer of the two steps (HeightGrid's cells are square)."""
    rows, cols = z.shape
    step = min(step_x, step_y)
    new_cols = round((cols - 1) * step_x / step) + 1
    new_rows = round((rows - 1) * step_y / step) + 1
    xs = np.linspace(0, cols - 1, new_cols)
    ys = np.linspace(0, rows - 1, new_rows)
    along_x = np.array([np.interp(xs, np.arange(cols), row) for row in z])
    out = np.array([np.interp(ys, np.arange(rows), col) for col in along_x.T]).T
    return out, step
