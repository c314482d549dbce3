#!/usr/bin/env python3
"""results_table.py CSV... - markdown tables of `passgraph bench` results (results.csv): per light
count and pipeline the median GPU frame, the pass that dominates it, light assignment and lighting
time, references stored, list memory, dropped references and the error against the reference.
Rows keep the order of the files and of their rows. Used for docs/performance.md:

    scripts/tables/results_table.py docs/results/h200-2026-12-01-a74bb02/sponza/results.csv docs/results/h200-2026-12-01-a74bb02/sponza_naive/results.csv
"""
import csv
import sys


def num(row, key):
    v = row.get(key, "")
    try:
        return float(v)
    except ValueError:
        return None


def passes(row):
    """(name, median ms) of every pass the row ran, in column order"""
    out = []
    for k, v in row.items():
        if k.startswith("pass_") and k.endswith("_ms_median") and v not in ("", None):
            out.append((k[len("pass_"):-len("_ms_median")], float(v)))
    return out


def fmt_ms(v):
    if v is None:
        return "-"
    return "%.3f" % v if v < 10 else "%.1f" % v


def main(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            rows.extend(csv.DictReader(f))
    rows.sort(key=lambda r: (int(r["lights"]),))
    print("| lights | pipeline | frame ms | dominant pass (ms, share) | assignment ms | lighting ms | refs | lists MiB | dropped | RMSE | PSNR dB |")
    print("|---:|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        if r["status"] not in ("ok", "inexact"):
            print("| %s | %s | %s | | | | | | | | |" % (r["lights"], r["pipeline"], r["status"]))
            continue
        frame = num(r, "gpu_ms_median")
        ps = passes(r)
        dom = max(ps, key=lambda x: x[1]) if ps else ("-", 0.0)
        assign = next((ms for n, ms in ps if n == "assign_lights"), None)
        light = next((ms for n, ms in ps if n in ("lighting", "lighting_oct16", "lighting_packed", "shade")), None)
        refs = r.get("light_refs", "")
        lb = num(r, "list_bytes")
        label = r["pipeline"] + (" " + r["variant"] if r.get("variant") else "")
        print("| %s | %s | %s | %s (%s, %.0f%%) | %s | %s | %s | %s | %s | %s | %s |" % (
            r["lights"], label, fmt_ms(frame), dom[0], fmt_ms(dom[1]), 100.0 * dom[1] / frame if frame else 0,
            fmt_ms(assign), fmt_ms(light), refs or "-", "%.1f" % (lb / 1048576.0) if lb is not None else "-",
            r.get("overflow_dropped", "") or "-",
            "%.3g" % num(r, "rmse_linear") if num(r, "rmse_linear") is not None else "-",
            r.get("psnr_linear", "") or "-"))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
