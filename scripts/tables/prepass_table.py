#!/usr/bin/env python3
"""prepass_table.py DIR - the lavapipe table of docs/performance.md "Depth pre-pass: none, less or
equal": median over the rounds of each round's median frame GPU ms, per scene and light count,
for prepass=false, prepass_test=less and prepass_test=equal.

DIR holds r<round>_<scene>_{test,off}/results.csv as written by its run.sh (e.g.
docs/results/lavapipe-2026-12-02-435d898/prepass; summary.py there prints every round)."""
import collections
import csv
import glob
import os
import statistics
import sys

NAMES = {"default": "atrium", "sponza": "Sponza"}


def main(d):
    rows = collections.defaultdict(list)
    for f in glob.glob(os.path.join(d, "r*/results.csv")):
        scene = os.path.basename(os.path.dirname(f)).split("_")[1]
        for r in csv.DictReader(open(f)):
            rows[(scene, int(r["lights"]), r["variant"] or "prepass=false")].append(float(r["gpu_ms_median"]))
    print("| scene, lights | prepass=false | prepass=true, test less | test equal |")
    print("|---|---:|---:|---:|")
    for scene, lights in sorted({(k[0], k[1]) for k in rows}, key=lambda k: (k[0] != "sponza", k[0], k[1])):
        med = [statistics.median(rows[(scene, lights, v)])
               for v in ("prepass=false", "prepass_test=less", "prepass_test=equal")]
        print("| %s, %d | %.1f | %.1f | %.1f |" % ((NAMES.get(scene, scene), lights) + tuple(med)))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
