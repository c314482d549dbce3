#!/usr/bin/env python3
"""png_stats.py FILE.png: prints 'W H COVER MEAN' for an 8-bit RGB/RGBA PNG (any filter types):
COVER = fraction of pixels whose largest channel is > 8 (not black), MEAN = mean 8-bit luma
(0.2126 R + 0.7152 G + 0.0722 B) of those pixels (0 when there are none). Used by cli_test.sh to
check that a default render of a model is framed (covers part of the image) and lit."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_read import read_png  # noqa: E402


w, h, bpp, rows = read_png(sys.argv[1])
lit, total = 0, 0.0
for r in rows:
    for x in range(0, w * bpp, bpp):
        R, G, B = r[x], r[x + 1], r[x + 2]
        if max(R, G, B) > 8:
            lit += 1
            total += 0.2126 * R + 0.7152 * G + 0.0722 * B
print(w, h, "%.4f" % (lit / (w * h)), "%.1f" % (total / lit if lit else 0.0))
