#!/usr/bin/env python3
"""evals_table.py CSV... - markdown table of light evaluations from `passgraph bench` results
(results.csv, columns light_evals and evals_per_pixel: what the compute shading pass evaluated in
the error frame): per light count and pipeline the evaluations a pixel and a frame, the shading
pass's median time, and the rate it achieved (evaluations per second of that pass). Used for
docs/performance.md:

    scripts/tables/evals_table.py docs/results/h100-2026-12-06-3f9da6e/evals/results.csv
"""
import csv
import sys

from results_table import num, passes

SHADING_PASSES = ("shade", "lighting", "lighting_oct16", "lighting_packed")


def main(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            # rows that were timed (a failed or skipped row has no times: it crashed the table)
            rows.extend(r for r in csv.DictReader(f) if r.get("status") in ("ok", "inexact"))
    rows.sort(key=lambda r: int(r["lights"]))
    print("| lights | pipeline | evaluations a pixel | evaluations a frame | shading pass | its ms | G evaluations/s | frame ms |")
    print("|---:|---|---:|---:|---|---:|---:|---:|")
    for r in rows:
        ev, pp = num(r, "light_evals"), num(r, "evals_per_pixel")
        name, ms = next(((n, t) for n, t in passes(r) if n in SHADING_PASSES), (None, None))
        rate = ev / ms / 1e6 if ev is not None and ms else None
        print("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["lights"], (r["pipeline"] + (" " + r["variant"] if r.get("variant") else "")), "%.1f" % pp if pp is not None else "-",
            "%.3g" % ev if ev is not None else "-", name or "-", "%.3f" % ms if ms is not None else "-",
            "%.1f" % rate if rate is not None else "-", "%.3f" % num(r, "gpu_ms_median")))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
