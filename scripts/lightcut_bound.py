#!/usr/bin/env python3
"""lightcut_bound.py EXACT.exr LIGHTCUT.exr EPS [NAME] - how much of the lightcut's stated per-pixel
bound a lightcut image uses against the exact image of the same frame (both linear HDR written by
`passgraph render --set hdr_format=rgba32f --hdr-out`): per pixel and RGB channel
|lightcut - exact| / (EPS |exact| + 1e-4 |exact| + 1e-6 peak), the bound test_gpu_lightcut asserts
(EPS the pipeline's lightcut_error; 1e-4 and 1e-6 of the peak cover float rounding). Prints one
line: the worst usage, where, and how many channels exceed 1. Exit 1 when any does, 2 on bad input.
Reads passgraph's OpenEXR files with exr_read.py (numpy and zlib only), so that it runs where no
OpenEXR reader is installed."""
import os
import sys

import numpy as np

from exr_read import read_exr


def bad(path, why):
    sys.stderr.write("%s: %s\n" % (path, why))
    sys.exit(2)


def read(path):
    """The R, G, B channels of a scanline OpenEXR file as an h x w x 3 float64 array."""
    try:
        return read_exr(path, ("R", "G", "B")).astype(np.float64)
    except OSError as e:
        bad(path, e.strerror)
    except ValueError as e:
        sys.stderr.write("%s\n" % e)
        sys.exit(2)


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
