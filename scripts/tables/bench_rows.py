#!/usr/bin/env python3
"""bench_rows.py RESULTS.csv: one line per row of a `passgraph bench` results.csv (pipeline,
variant, lights, status, frame GPU ms, RMSE, pass medians, light references, dropped)."""
import csv
import sys

for r in csv.DictReader(open(sys.argv[1])):
    ps = {k[5:-10]: r[k] for k in r if k.startswith("pass_") and k.endswith("_ms_median") and r[k]}
    print(r["pipeline"], r["variant"], r["lights"], r["status"], "gpu", r["gpu_ms_median"], "rmse",
          r["rmse_linear"], ps, "refs", r.get("light_refs"), "dropped", r.get("overflow_dropped"))
