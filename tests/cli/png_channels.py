#!/usr/bin/env python3
"""png_channels.py FILE.png: prints 'MEAN_R MEAN_G MEAN_B MAX_R MAX_G MAX_B' (8-bit values over every
pixel) of an 8-bit RGB/RGBA PNG. Used by cli_test.sh (the tint plug-in's colour)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_read import read_png  # noqa: E402

w, h, bpp, rows = read_png(sys.argv[1])
sums, maxs = [0, 0, 0], [0, 0, 0]
for r in rows:
    for x in range(0, w * bpp, bpp):
        for c in range(3):
            sums[c] += r[x + c]
            maxs[c] = max(maxs[c], r[x + c])
n = w * h
print(" ".join("%.2f" % (s / n) for s in sums), " ".join(str(m) for m in maxs))
