#!/usr/bin/env python3
"""cost_ratio_table.py [--label NAME=CSV ...] [--by-variant] BASE - a markdown table of median GPU frame
times of `passgraph bench` results, one row per (pipeline, lights), one column per variant, and each
variant's ratio to the BASE variant. Two ways to name the variants:

  --by-variant: the `variant` column of one results.csv (a --sweep), e.g. the light models:
      scripts/tables/cost_ratio_table.py --by-variant shading=lambert \\
          --label all=docs/results/DIR/shading_cost/results.csv
  --label NAME=CSV (repeated): each file is one variant named NAME, e.g. points against spots:
      scripts/tables/cost_ratio_table.py points --label points=.../spot_cost_points/results.csv \\
          --label spots=.../spot_cost_spots/results.csv

--variant V keeps only the rows of one --sweep value (e.g. the environment on and off, one light model
at a time: --variant shading=pbr). Each cell also names the pass that dominates the frame.
--steps PASS: one row per other variant instead (e.g. successive versions of a change), its ratio to
BASE in each pipeline, the light references its lists hold and PASS's median ms (of the first
pipeline), e.g. --steps assign_lights. --time PASS[,PASS...]: the ratios of a pass instead of the
frame: in each row the first of these passes it has (e.g. shade,lighting,lighting_oct16,lighting_packed:
the shading pass of each pipeline), ratios to three decimals. Used for docs/performance.md."""
import argparse
import csv


def dominant(row):
    best = None
    for k, v in row.items():
        if k.startswith("pass_") and k.endswith("_ms_median") and v not in ("", None):
            name, ms = k[len("pass_"):-len("_ms_median")], float(v)
            if best is None or ms > best[1]:
                best = (name, ms)
    return best


TIME_PASSES = []  # --time: the passes whose time the ratios compare (empty: the frame)


def ms(row):
    """The time a ratio compares: the frame, or with --time the first of its passes the row has."""
    for p in TIME_PASSES:
        v = row.get("pass_%s_ms_median" % p)
        if v:
            return float(v)
    if TIME_PASSES:
        raise SystemExit("cost_ratio_table.py: %s %s has none of the passes %s" % (row["pipeline"], row["lights"],
                                                                                ",".join(TIME_PASSES)))
    return float(row["gpu_ms_median"])


def ratio(b, r):
    return ("%.3fx" if TIME_PASSES else "%.2fx") % (ms(r) / ms(b))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("base", help="the variant the ratios are taken against")
    ap.add_argument("--label", action="append", default=[], metavar="NAME=CSV")
    ap.add_argument("--by-variant", action="store_true", help="variants are the `variant` column of the files")
    ap.add_argument("--variant", help="keep only the rows of this `variant` (a --sweep value, e.g. shading=pbr)")
    ap.add_argument("--steps", metavar="PASS", help="one row per other variant: ratios, references, PASS ms")
    ap.add_argument("--time", metavar="PASS[,PASS]", help="ratios of the first of these passes a row has")
    a = ap.parse_args()
    global TIME_PASSES
    TIME_PASSES = a.time.split(",") if a.time else []
    cells = {}  # (pipeline, lights) -> {variant: row}
    seen = {}  # path -> (scene, width, height) of its rows
    order, variants = [], []
    for lab in a.label:
        name, _, path = lab.partition("=")
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                if row.get("status") != "ok" or (a.variant is not None and row.get("variant") != a.variant):
                    continue
                v = row["variant"] if a.by_variant else name
                key = (row["pipeline"], row["lights"])
                # one size and scene a table: a second one overwrote the first's rows without a word
                where = (row.get("scene"), row.get("width"), row.get("height"))
                if seen.setdefault(path, where) != where:
                    raise SystemExit("cost_ratio_table.py: %s holds rows of more than one scene or size (%s and %s): "
                                     "one a table" % (path, "/".join(map(str, seen[path])), "/".join(map(str, where))))
                if key not in cells:
                    cells[key] = {}
                    order.append(key)
                cells[key][v] = row
                if v not in variants:
                    variants.append(v)
    if a.base not in variants:
        raise SystemExit("cost_ratio_table.py: no variant %r (have %s)" % (a.base, ", ".join(variants)))
    others = [v for v in variants if v != a.base]
    if a.steps:
        steps_table(cells, order, a.base, others, a.steps)
        return
    head = ["pipeline", "lights"] + ["%s ms (dominant pass)" % v for v in variants] + ["%s / %s" % (v, a.base) for v in others]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * 2 + "---:|" * (len(variants) + len(others)))
    for key in order:
        c = cells[key]
        line = [key[0], key[1]]
        for v in variants:
            r = c.get(v)
            if r is None:
                line.append("-")
                continue
            d = dominant(r)
            line.append("%.3f (%s %.3f)" % (float(r["gpu_ms_median"]), d[0], d[1]) if d else "%.3f" % float(r["gpu_ms_median"]))
        for v in others:
            b, r = c.get(a.base), c.get(v)
            line.append(ratio(b, r) if b and r else "-")
        print("| " + " | ".join(line) + " |")


def steps_table(cells, order, base, others, pass_name):
    """One row per variant in `others`: its frame (or --time pass) time over BASE's in each (pipeline, lights)."""
    head = ["variant"] + ["%s %s" % k if len({k[1] for k in order}) > 1 else k[0] for k in order]
    head += ["references", "%s ms" % pass_name]
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * (len(order) + 2))
    for v in others:
        line = [v]
        for key in order:
            b, r = cells[key].get(base), cells[key].get(v)
            line.append(ratio(b, r) if b and r else "-")
        first = cells[order[0]].get(v, {})
        line.append("{:,}".format(int(first["light_refs"])) if first.get("light_refs") else "-")
        pass_ms = first.get("pass_%s_ms_median" % pass_name)
        line.append("%.2f" % float(pass_ms) if pass_ms else "-")
        print("| " + " | ".join(line) + " |")


if __name__ == "__main__":
    main()
