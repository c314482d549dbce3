#!/usr/bin/env python3
"""error_time_table.py [NAME=]CSV... - markdown table of error against time from `passgraph bench` results
(results.csv): per scenario (scene, size, light count) and configuration (pipeline, swept knobs,
--accumulate) the median GPU frame, the accumulated time (frames x frame), the dominant pass, the
light references stored, and the error against the reference: RMSE (linear HDR), LDR-FLIP, SSIM and
flicker (mean frame-to-frame change with a static scene; 0 for a deterministic pipeline). "front"
marks the rows on the Pareto front of FLIP against accumulated time within their scenario (no
other row of the scenario is both faster and lower in FLIP). NAME=CSV names the configuration of a
file's rows in the knobs column (variants run as separate benches, e.g. two data folders). Used for
docs/performance.md:

    scripts/tables/error_time_table.py docs/results/h100-2026-12-06-3f9da6e/manylight/results.csv ...
"""
import csv
import os
import sys

from results_table import fmt_ms, num, passes


def fmt(v, digits=3):
    if v is None:
        return "-"
    if v == 0:
        return "0"
    return "%.*g" % (digits, v)


def dominant(row):
    ps = passes(row)
    return max(ps, key=lambda x: x[1]) if ps else None


def main(paths):
    rows = []
    for p in paths:
        label = None
        if "=" in p and not os.path.exists(p):  # NAME=CSV: its rows' knobs read NAME (variants run apart)
            label, p = p.rsplit("=", 1)
        with open(p, newline="") as f:
            for r in csv.DictReader(f):
                if label:
                    r["variant"] = label + (";" + r["variant"] if r.get("variant") else "")
                rows.append(r)
    key = lambda r: (os.path.basename(r["scene"]), r["width"] + "x" + r["height"], int(r["lights"]))
    groups = {}
    for r in rows:
        groups.setdefault(key(r), []).append(r)
    print("| scene, size | lights | pipeline | knobs | frames | ms a frame | ms in all | dominant pass (ms) "
          "| refs | RMSE | FLIP | SSIM | flicker | front |")
    print("|---|---:|---|---|---:|---:|---:|---|---:|---:|---:|---:|---:|:-:|")
    for k in sorted(groups):
        g = groups[k]
        pts = [(num(r, "accumulated_ms_median"), num(r, "flip")) for r in g]
        for r, (t, e) in zip(g, pts):
            ok = r["status"] in ("ok", "inexact") and t is not None and e is not None
            front = ok and not any(t2 is not None and e2 is not None and t2 <= t and e2 <= e and (t2 < t or e2 < e)
                                   for (t2, e2) in pts)
            dom = dominant(r)
            knobs = r.get("variant") or ""
            print("| %s, %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                k[0], k[1], r["lights"], r["pipeline"] + ("" if r["status"] == "ok" else " (%s)" % r["status"]),
                knobs or "default", r.get("accumulate") or "1", fmt_ms(num(r, "gpu_ms_median")), fmt_ms(t),
                "%s (%s)" % (dom[0], fmt_ms(dom[1])) if dom else "-", r.get("light_refs") or "-",
                fmt(num(r, "rmse_linear")), fmt(num(r, "flip")), fmt(num(r, "ssim"), 4), fmt(num(r, "flicker")),
                "yes" if front else ""))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
