#!/usr/bin/env python3
"""lightcut_bound.py EXACT.exr LIGHTCUT.exr EPS [NAME] - how much of the lightcut's stated per-pixel
bound a lightcut image uses against the exact image of the same frame (both linear HDR written by
`passgraph render --set hdr_format=rgba32f --hdr-out`): per pixel and RGB channel
|lightcut - exact| / (EPS |exact| + 1e-4 |exact| + 1e-6 peak), the bound test_gpu_lightcut asserts
(EPS the pipeline's lightcut_error; 1e-4 and 1e-6 of the peak cover float rounding). Prints one
line: the worst usage, where, and how many channels exceed 1. Exit 1 when any does, 2 on bad input.
Reads the scanline OpenEXR files passgraph writes (NONE, ZIPS or ZIP compression, HALF or FLOAT
channels) with numpy and zlib only, so that it runs where no OpenEXR reader is installed."""
import os
import struct
import sys
import zlib

import numpy as np


def bad(path, why):
    sys.stderr.write("%s: %s\n" % (path, why))
    sys.exit(2)


def read(path):
    """The R, G, B channels of a scanline OpenEXR file as an h x w x 3 float64 array."""
    try:
        data = open(path, "rb").read()
    except OSError as e:
        bad(path, e.strerror)
    if data[:4] != b"\x76\x2f\x31\x01" or data[5] & 0x02:
        bad(path, "not a single-part scanline OpenEXR file")
    pos, attrs = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        attrs[data[pos:name_end].decode()] = data[type_end + 5:type_end + 5 + size]
        pos = type_end + 5 + size
    pos += 1
    channels, q = [], attrs["channels"]
    while q[0] != 0:
        e = q.index(b"\0")
        channels.append((q[:e].decode(), struct.unpack_from("<i", q, e + 1)[0]))
        q = q[e + 17:]
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
    w, h, comp = x1 - x0 + 1, y1 - y0 + 1, attrs["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}.get(comp)
    if lines is None:
        bad(path, "compression %d is not NONE, ZIPS or ZIP" % comp)
    dtypes = {1: np.float16, 2: np.float32}
    if any(t not in dtypes for _, t in channels):
        bad(path, "a channel is neither HALF nor FLOAT")
    chunks = (h + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % chunks, data, pos)
    planes = {name: np.zeros((h, w)) for name, _ in channels}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        raw = data[off + 8:off + 8 + size]
        n = min(lines, y0 + h - y)
        full = sum(n * w * np.dtype(dtypes[t]).itemsize for _, t in channels)
        if comp != 0 and size < full:  # ZIP(S): zlib, then the byte predictor and interleave undone
            b = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int32)
            b = ((np.cumsum(b - 128) + 128) & 0xFF).astype(np.uint8)  # t[i] = t[i-1] + d[i] - 128, t[0] = d[0]
            half = (len(b) + 1) // 2
            out = np.empty(len(b), np.uint8)
            out[0::2], out[1::2] = b[:half], b[half:]
            raw = out.tobytes()
        at = 0
        for row in range(n):
            for name, t in channels:  # channels in the file's (alphabetical) order, a line each
                dt = np.dtype(dtypes[t]).newbyteorder("<")
                planes[name][y - y0 + row] = np.frombuffer(raw, dt, w, at)
                at += w * dt.itemsize
    if not all(c in planes for c in "RGB"):
        bad(path, "no R, G and B channels")
    return np.stack([planes["R"], planes["G"], planes["B"]], axis=2)


def main(argv):
    if len(argv) not in (4, 5):
        sys.stderr.write(__doc__)
        return 2
    ex, lc, eps = read(argv[1]), read(argv[2]), float(argv[3])
    name = argv[4] if len(argv) == 5 else os.path.basename(argv[2])
    if ex.shape != lc.shape:
        sys.stderr.write("sizes differ: %s against %s\n" % (ex.shape, lc.shape))
        return 2
    if not (np.isfinite(ex).all() and np.isfinite(lc).all()):
        sys.stderr.write("non-finite pixels\n")
        return 2
    peak = float(np.abs(ex).max())
    bound = eps * np.abs(ex) + 1e-4 * np.abs(ex) + 1e-6 * peak
    use = np.abs(lc - ex) / np.where(bound > 0, bound, np.inf)
    use[(bound == 0) & (lc != ex)] = np.inf
    worst = float(use.max())
    y, x, c = np.unravel_index(int(np.argmax(use)), use.shape)
    over = int((use > 1).sum())
    print("%s: eps %g, %dx%d, peak %.4g: worst bound usage %.4f at (%d, %d) channel %d, mean %.4f, "
          "%d of %d channels over the bound" % (name, eps, ex.shape[1], ex.shape[0], peak, worst, x, y, c,
                                                float(use[np.isfinite(use)].mean()), over, use.size))
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
