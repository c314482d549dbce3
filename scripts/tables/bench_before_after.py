#!/usr/bin/env python3
"""bench_before_after.py DIR - the before/after table of docs/performance.md from bench CSVs of two builds.

DIR holds results CSVs named {old,final}_ROUND.csv and naive_{old,final}_ROUND.csv (as
a device run writes them, one bench per build and round, rounds alternating). Prints a
markdown table: per pipeline and light count the median over rounds of each run's median GPU and
CPU ms, the device transient memory before -> after aliasing, and the RMSE against the reference.
"""
import csv, glob, os, re, statistics, sys
from collections import defaultdict

def main(d):
    rows = defaultdict(lambda: defaultdict(list))
    for p in sorted(glob.glob(os.path.join(d, '*.csv'))):
        m = re.match(r'(?:naive_)?(old|final)_\d+\.csv$', os.path.basename(p))
        if not m:
            continue
        for r in csv.DictReader(open(p)):
            if r['status'] in ('ok', 'inexact'):
                rows[(r['pipeline'], int(r['lights']))][m.group(1)].append(r)
    med = lambda rs, c: statistics.median(float(x[c]) for x in rs)
    mib = lambda rs, c: float(rs[0][c]) / 1048576
    print('| pipeline | lights | GPU ms old | GPU ms new | CPU ms old | CPU ms new | transient MiB old | new | RMSE old | new |')
    print('|---|---:|---:|---:|---:|---:|---|---|---:|---:|')
    for k in sorted(rows):
        o, f = rows[k]['old'], rows[k]['final']
        if not o or not f:
            continue
        print(f"| {k[0]} | {k[1]} | {med(o, 'gpu_ms_median'):.3f} | {med(f, 'gpu_ms_median'):.3f} | "
              f"{med(o, 'cpu_ms_median'):.3f} | {med(f, 'cpu_ms_median'):.3f} | "
              f"{mib(o, 'device_transient_bytes_unaliased'):.1f} -> {mib(o, 'device_transient_bytes_aliased'):.1f} | "
              f"{mib(f, 'device_transient_bytes_unaliased'):.1f} -> {mib(f, 'device_transient_bytes_aliased'):.1f} | "
              f"{float(o[0]['rmse_linear']):.3g} | {float(f[0]['rmse_linear']):.3g} |")
    return 0

if __name__ == '__main__':
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else 'docs/results/h200-2026-12-01-2db02e5'))
