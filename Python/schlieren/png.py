# SPDX-License-Identifier: BSD-3-Clause
"""A PNG writer on NumPy and zlib alone (no VTK, no Pillow), for films, and show() for Jupyter."""
import struct
import zlib

import numpy as np


def encode_png(values):
    """A (ny, nx) array in [0, 1] as the bytes of an 8-bit grey PNG, or (ny, nx, 3) as colour; row
    0 of the film is its bottom (as the film's y axis), so it is written last. Values are
    clipped, NaN is 0."""
    v = np.clip(np.nan_to_num(np.asarray(values, dtype=float)), 0.0, 1.0)
    if v.ndim not in (2, 3) or (v.ndim == 3 and v.shape[2] != 3) or v.size == 0:
        raise ValueError("a PNG needs a (ny, nx) or (ny, nx, 3) array with pixels; got shape %s"
                         % (v.shape,))
    ny, nx = v.shape[:2]
    colour = v.ndim == 3
    pixels = (255.0 * v + 0.5).astype(np.uint8)[::-1].reshape(ny, -1)
    raw = b"".join(b"\x00" + row.tobytes() for row in pixels)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", nx, ny, 8, 2 if colour else 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def write_png(values, path):
    """Writes encode_png(values) to path."""
    data = encode_png(values)
    with open(path, "wb") as f:
        f.write(data)


class Image:
    """A film as a picture: Jupyter and IPython show it (_repr_png_); save(path) writes the PNG."""

    def __init__(self, values):
        self.values = np.asarray(values)
        self._png = encode_png(self.values)

    def _repr_png_(self):
        return self._png

    def save(self, path):
        with open(path, "wb") as f:
            f.write(self._png)
        return path

    def __repr__(self):
        return "<schlieren.png.Image %d x %d%s>" % (self.values.shape[1], self.values.shape[0],
                                                     " rgb" if self.values.ndim == 3 else "")


def show(values):
    """An Image of values ((ny, nx) in [0, 1], or (ny, nx, 3)): the last line of a notebook cell
    shows it, with no package beyond NumPy."""
    return Image(values)
