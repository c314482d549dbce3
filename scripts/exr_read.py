#!/usr/bin/env python3
"""exr_read.py FILE.exr - reads the OpenEXR files passgraph writes (image/exr.c: one part, scan
lines, NO or ZIPS/ZIP compression, HALF / FLOAT / UINT channels) into a numpy array (height, width,
channels in R, G, B, A order, then any others by name; or the channels asked for), with numpy and
zlib only, so the scripts that read passgraph's images (lightcut_bound.py, tables/cross_device_table.py)
need no OpenEXR or OpenCV module. Written from the OpenEXR file layout document (header attributes, the line offset
table, ZIP's byte split and delta predictor). Run as a script it prints the size, channels and
range of each channel.

Anything else (tiles, deep or multi-part files, PIZ and the lossy codecs) raises ValueError naming
the file and what it holds."""
import struct
import sys
import zlib

import numpy as np

_TYPES = {0: np.dtype("<u4"), 1: np.dtype("<f2"), 2: np.dtype("<f4")}
_LINES = {0: 1, 2: 1, 3: 16}  # compression -> scan lines a chunk (NO, ZIPS, ZIP)
_ORDER = {"R": 0, "G": 1, "B": 2, "A": 3}


def _header(data, path):
    """The attributes as {name: (type, bytes)} and the offset just past the header."""
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("%s: not a single-part scanline OpenEXR file (magic %s)" % (path, data[:4].hex()))
    flags = struct.unpack_from("<I", data, 4)[0]
    if flags & ~0xFF & ~0x400:  # version 2; only the long-names bit (0x400) is understood
        raise ValueError("%s: tiled, deep or multi-part file (flags 0x%x): not read here" % (path, flags))
    attrs, i = {}, 8
    while data[i] != 0:
        j = data.index(b"\0", i)
        k = data.index(b"\0", j + 1)
        size = struct.unpack_from("<i", data, k + 1)[0]
        attrs[data[i:j].decode()] = (data[j + 1:k].decode(), data[k + 5:k + 5 + size])
        i = k + 5 + size
    return attrs, i + 1


def _channels(raw):
    out, i = [], 0
    while raw[i] != 0:
        j = raw.index(b"\0", i)
        ptype, _, _, xs, ys = struct.unpack_from("<iB3sii", raw, j + 1)
        out.append((raw[i:j].decode(), ptype, xs, ys))
        i = j + 1 + 16
    return out


def _unzip(block, path):
    """ZIP(S): zlib, then the predictor (each byte the running sum of deltas biased by 128), then
    the two halves (even bytes first, odd bytes second) interleaved again."""
    try:
        t = np.frombuffer(zlib.decompress(block), dtype=np.uint8)
    except zlib.error as e:
        raise ValueError("%s: a chunk does not decompress (%s): truncated or damaged" % (path, e))
    t = np.cumsum(np.concatenate(([t[0]], t[1:].astype(np.int64) - 128))).astype(np.uint8) if t.size else t
    out = np.empty_like(t)
    half = (t.size + 1) // 2
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def read_exr(path, names=None):
    """The image as float32 (height, width, channels): every channel (R, G, B, A first), or the ones
    named, in that order. OSError when the file cannot be read, ValueError for anything else."""
    with open(path, "rb") as f:
        data = f.read()
    try:
        planes = _read(data, path)
    except (struct.error, IndexError, KeyError) as e:
        raise ValueError("%s: truncated or damaged (%s)" % (path, e))
    if names is None:
        names = sorted(planes, key=lambda c: (_ORDER.get(c, 4), c))
    elif any(c not in planes for c in names):
        raise ValueError("%s: no %s channels" % (path, ", ".join(names)))
    return np.stack([planes[c].astype(np.float32) for c in names], axis=2)


def _read(data, path):
    attrs, pos = _header(data, path)
    comp = attrs["compression"][1][0]
    if comp not in _LINES:
        raise ValueError("%s: compression %d is not read here (NO, ZIPS and ZIP are)" % (path, comp))
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    chans = _channels(attrs["channels"][1])
    if any(xs != 1 or ys != 1 or t not in _TYPES for _, t, xs, ys in chans):
        raise ValueError("%s: subsampled channels or an unknown pixel type: not read here" % path)
    per_line = _LINES[comp]
    chunks = (h + per_line - 1) // per_line
    offsets = struct.unpack_from("<%dQ" % chunks, data, pos)
    planes = {name: np.empty((h, w), dtype=_TYPES[t]) for name, t, _, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        block = data[off + 8:off + 8 + size]
        lines = min(per_line, y1 + 1 - y)
        need = lines * w * sum(_TYPES[t].itemsize for _, t, _, _ in chans)
        raw = block if comp == 0 or size == need else _unzip(block, path)
        if len(raw) != need:
            raise ValueError("%s: chunk at line %d holds %d bytes, %d expected" % (path, y, len(raw), need))
        at = 0
        for line in range(lines):
            for name, t, _, _ in chans:  # the file's channel order: by name
                n = w * _TYPES[t].itemsize
                planes[name][y - y0 + line] = np.frombuffer(raw, dtype=_TYPES[t], count=w, offset=at)
                at += n
    return planes


def main(argv):
    if len(argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    try:
        img = read_exr(argv[1])
    except (OSError, ValueError) as e:
        print("exr_read.py: %s" % e, file=sys.stderr)
        return 1
    print("%s: %dx%d, %d channels" % (argv[1], img.shape[1], img.shape[0], img.shape[2]))
    for c in range(img.shape[2]):
        print("  channel %d: min %g max %g" % (c, img[..., c].min(), img[..., c].max()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
