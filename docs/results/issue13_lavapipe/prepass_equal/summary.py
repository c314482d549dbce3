#!/usr/bin/env python3
"""summary.py - per scene, light count and variant: every round's frame ms (the round's median of
5 frames) and the median over the rounds, from the r<round>_<scene>_{test,off}/results.csv here
(run.sh). The README's lavapipe table of the depth pre-pass is this output."""
import collections
import csv
import glob
import os
import statistics

here = os.path.dirname(os.path.abspath(__file__))
rows = collections.defaultdict(list)
for f in sorted(glob.glob(os.path.join(here, 'r*/results.csv')),
                key=lambda p: int(os.path.basename(os.path.dirname(p))[1:].split('_')[0])):
    scene = os.path.basename(os.path.dirname(f)).split('_')[1]
    for r in csv.DictReader(open(f)):
        rows[(scene, int(r['lights']), r['variant'] or 'prepass=false')].append(float(r['gpu_ms_median']))
for k in sorted(rows):
    v = rows[k]
    print('%s %d %s: %s -> median %.1f' % (k[0], k[1], k[2], ' / '.join('%.1f' % x for x in v), statistics.median(v)))
