#!/usr/bin/env python3
"""pass_share_table.py PASS LABEL=CSV... - a markdown table of one pass's share of the frame in
`passgraph bench` results (results.csv): per file (its label), pipeline and light count the median
GPU frame, the pass's median time and its share of the frame. Used for docs/performance.md:

    scripts/tables/pass_share_table.py animate_geometry \
        "compute queue on=docs/results/h200-2026-12-03-6d20be5/anim_on/results.csv" \
        "compute queue off=docs/results/h200-2026-12-03-6d20be5/anim_off/results.csv"
"""
import csv
import sys


def main(argv):
    if len(argv) < 2 or any("=" not in a for a in argv[1:]):
        sys.exit("usage: pass_share_table.py PASS LABEL=CSV...")
    name = argv[0]
    col = "pass_%s_ms_median" % name
    print("| run | pipeline | lights | frame ms | %s ms | share |" % name)
    print("|---|---|---:|---:|---:|---:|")
    for arg in argv[1:]:
        label, path = arg.split("=", 1)
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                frame, part = row.get("gpu_ms_median", ""), row.get(col, "")
                if not frame or not part:
                    continue
                frame, part = float(frame), float(part)
                print("| %s | %s | %s | %.3f | %.4f | %.2f%% |" % (label, row["pipeline"], row["lights"], frame, part,
                                                                   100.0 * part / frame if frame else 0.0))


if __name__ == "__main__":
    main(sys.argv[1:])
