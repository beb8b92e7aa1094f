# SPDX-License-Identifier: BSD-3-Clause
"""A PNG writer on NumPy and zlib alone (no VTK, no Pillow), for films."""
import struct
import zlib

import numpy as np


def write_png(values, path):
    """Writes a (ny, nx) array in [0, 1] as 8-bit grey, or (ny, nx, 3) as colour; row 0 of the
    film is its bottom (as the film's y axis), so it is written last. Values are clipped."""
    v = np.clip(np.nan_to_num(np.asarray(values, dtype=float)), 0.0, 1.0)
    ny, nx = v.shape[:2]
    colour = v.ndim == 3
    pixels = (255.0 * v + 0.5).astype(np.uint8)[::-1].reshape(ny, -1)
    raw = b"".join(b"\x00" + row.tobytes() for row in pixels)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", nx, ny, 8, 2 if colour else 0, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))
