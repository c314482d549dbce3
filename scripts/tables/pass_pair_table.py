#!/usr/bin/env python3
"""pass_pair_table.py ROUND_DIR... -- PAIR... - a markdown table comparing one pass of a user-written
pipeline with the built-in pass doing the same work, from `passgraph bench` results.csv files
(scripts/device-run.sh user-passes, run once per ROUND_DIR). A PAIR is
    "LABEL|USER_RUN|USER_VARIANT|USER_PASS|BUILTIN_RUN|BUILTIN_VARIANT|BUILTIN_PASS"
where RUN is the folder of a results.csv inside each round, VARIANT its `variant` column ("" for
none) and PASS a pass name. Each cell is the median over the rounds of the pass's median GPU time.
Used for docs/performance.md ("User passes against built-in ones")."""
import csv
import os
import statistics
import sys


def pass_ms(rounds, run, variant, name):
    vals = []
    for d in rounds:
        with open(os.path.join(d, run, "results.csv"), newline="") as f:
            for row in csv.DictReader(f):
                v = row.get("pass_%s_ms_median" % name, "")
                if row["variant"] == variant and v:
                    vals.append(float(v))
                    lights = row["lights"]
    if not vals:
        sys.exit("pass_pair_table.py: no %s/%s variant '%s' in %s" % (run, name, variant, rounds))
    return statistics.median(vals), lights, len(vals)


def main(argv):
    if "--" not in argv:
        sys.exit(__doc__)
    k = argv.index("--")
    rounds, pairs = argv[:k], argv[k + 1:]
    print("| work | lights | user pass | ms | built-in pass | ms | user / built-in |")
    print("|---|---:|---|---:|---|---:|---:|")
    for p in pairs:
        label, ur, uv, up, br, bv, bp = p.split("|")
        u, lights, n = pass_ms(rounds, ur, uv, up)
        b, _, _ = pass_ms(rounds, br, bv, bp)
        print("| %s | %s | `%s`%s | %.4f | `%s`%s | %.4f | %.3f |" % (label, lights, up, " (%s)" % uv if uv else "", u, bp,
                                                                  " (%s)" % bv if bv else "", b, u / b))


if __name__ == "__main__":
    main(sys.argv[1:])
