#!/usr/bin/env python3
"""eval_counts_table.py LABEL=CSV [LABEL=CSV ...] - markdown table comparing the light evaluation counts
(column evals_per_pixel of `passgraph bench` results.csv) of several runs of the same pipeline, one
row per light count: each run's count a pixel and its ratio to the first run's. Runs made with a
diagnostic count in the shaders (PG_COUNT_IDLE_LANES, PG_COUNT_REACHING: docs/decisions/tile-lanes.md)
against the plain count. Rows that are not status ok are left out (a dropped reference changes
the lists). Used for docs/decisions/tile-lanes.md:

    scripts/tables/eval_counts_table.py evaluated=docs/results/lavapipe-2026-12-05-9900ca7/evaluated/results.csv \\
        idle_lanes=docs/results/lavapipe-2026-12-05-9900ca7/idle_lanes/results.csv ...
"""
import csv
import sys


def load(path):
    with open(path, newline="") as f:
        return {int(r["lights"]): float(r["evals_per_pixel"])
                for r in csv.DictReader(f) if r["status"] == "ok" and r["evals_per_pixel"]}


def main(args):
    runs = []
    for a in args:
        label, sep, path = a.partition("=")
        if not sep:
            sys.exit("eval_counts_table.py: expected LABEL=CSV, got '%s'" % a)
        runs.append((label, load(path)))
    first = runs[0][0]
    head = ["lights", first + " a pixel"]
    for label, _ in runs[1:]:
        head += [label + " a pixel", label + " / " + first]
    print("| " + " | ".join(head) + " |")
    print("|" + "---:|" * len(head))
    for n in sorted(runs[0][1]):
        if any(n not in r for _, r in runs):
            continue
        base = runs[0][1][n]
        cells = ["{:,}".format(n), "%.2f" % base]
        for _, r in runs[1:]:
            cells += ["%.2f" % r[n], "%.3f" % (r[n] / base)]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
