#!/usr/bin/env bash
# bench_shard_test.sh PASSGRAPH_BINARY - `passgraph bench --shard K/N` and `passgraph bench-merge`:
# a sweep run whole and the same sweep run as two shards (validation on) and merged give the same
# results.csv apart from the measured-time columns (every column named *_ms_median, *_ms_mean,
# *_ms_min, *_ms_max, *_ms_p95: gpu_ms_*, cpu_ms_*, wait_ms_*, pass_<name>_ms_*), and the same
# results.json rows apart from those times; the error columns (deterministic) must be equal and
# present. bench-merge must refuse a missing shard, a shard given twice, shards of different
# sweeps, an unsharded run given with a shard (and merged alone: its table and charts again) and a
# shard lacking a configuration; bad --shard values
# exit 2.
set -u
PG=$1
. "$(dirname "$0")/check_lib.sh"


# expect_fail "description" expected-rc "substring of stderr" args...
expect_fail() {
  local what=$1 want=$2 needle=$3
  shift 3
  "$PG" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [ $rc -ne "$want" ]; then bad "$what: exit $rc, want $want"; cat "$tmp/err"; return; fi
  if ! grep -qF -- "$needle" "$tmp/err"; then bad "$what: stderr lacks '$needle':"; cat "$tmp/err"; return; fi
  ok
}

# 2 pipelines (deferred swept over two G-buffer layouts: 3 variants) x 2 light counts = 6 configurations
SWEEP=(--pipelines forward_plus,deferred --sweep gbuffer=float,packed --lights 16,64 --size 160x90
       --frames 2 --warmup 1 --validation --quiet)

"$PG" bench "${SWEEP[@]}" --out "$tmp/full" >"$tmp/full.log" 2>&1 || { bad "unsharded bench: exit $?"; cat "$tmp/full.log"; }
"$PG" bench "${SWEEP[@]}" --shard 1/2 --out "$tmp/s1" >"$tmp/s1.log" 2>&1 || { bad "bench --shard 1/2: exit $?"; cat "$tmp/s1.log"; }
"$PG" bench "${SWEEP[@]}" --shard 2/2 --device 0 --out "$tmp/s2" >"$tmp/s2.log" 2>&1 \
  || { bad "bench --shard 2/2 --device 0: exit $?"; cat "$tmp/s2.log"; }
grep -q "shard 1/2: 3 of 6 configurations" "$tmp/s1.log" && ok || bad "shard 1/2 does not announce 3 of 6 configurations"

if "$PG" bench-merge --out "$tmp/merged" "$tmp/s2" "$tmp/s1" >"$tmp/m.log" 2>&1; then ok; else bad "bench-merge: exit $?"; cat "$tmp/m.log"; fi
for d in s1 s2 merged; do
  for f in gpu_time_vs_lights passes_stacked error_vs_time flip_vs_time; do
    [ "$(head -c 5 "$tmp/$d/$f.svg" 2>/dev/null)" = "<svg " ] && tail -1 "$tmp/$d/$f.svg" | grep -q '</svg>' \
      && ok || bad "$d/$f.svg missing or not an SVG"
  done
done

python3 - "$tmp" <<'EOF' && ok || bad "merged results differ from the unsharded run (see above)"
import csv, json, re, sys
t = sys.argv[1]
TIME = re.compile(r"_ms_(median|mean|min|max|p95)$")   # the measured-time columns
def rows(p):
    with open(p, newline="") as f:
        r = list(csv.reader(f))
    return r[0], r[1:]
hf, full = rows(t + "/full/results.csv")
hm, merged = rows(t + "/merged/results.csv")
assert hf == hm, "headers differ:\n%s\n%s" % (hf, hm)
assert len(full) == 6 and len(merged) == 6, (len(full), len(merged))
keep = [i for i, h in enumerate(hf) if not TIME.search(h)]
timed = [h for h in hf if TIME.search(h)]
assert "gpu_ms_median" in timed and "rmse_linear" not in timed
for a, b in zip(full, merged):
    da = [a[i] for i in keep]; db = [b[i] for i in keep]
    assert da == db, "row differs:\n%s\n%s" % (list(zip([hf[i] for i in keep], da, db)),)
# the error columns are compared too, and are not empty (each row has a reference frame)
for c in ("rmse_linear", "psnr_display", "max_abs_linear", "flip", "hdr_flip", "ssim", "flicker"):
    k = hf.index(c)
    assert all(r[k] != "" for r in full), c
    assert [r[k] for r in full] == [r[k] for r in merged], c
# each shard holds its own rows: configuration i in shard i % 2 + 1
s1 = rows(t + "/s1/results.csv")[1]; s2 = rows(t + "/s2/results.csv")[1]
assert [r[:7] for r in s1] == [r[:7] for r in full[0::2]], "shard 1/2 rows"
assert [r[:7] for r in s2] == [r[:7] for r in full[1::2]], "shard 2/2 rows"
# results.json: the same rows apart from the times
def untimed(row):
    row = dict(row)
    for k in ("gpu_ms", "cpu_ms", "wait_ms"):
        row[k] = row[k]["n"]
    row["passes"] = [(p["name"], p["n"]) for p in row["passes"]]
    return row
jf = json.load(open(t + "/full/results.json")); jm = json.load(open(t + "/merged/results.json"))
assert [untimed(r) for r in jf["rows"]] == [untimed(r) for r in jm["rows"]], "results.json rows differ"
assert [r["index"] for r in jm["rows"]] == list(range(6))
# deterministic pipelines: no flicker; the merged rows keep the perceptual numbers
assert all(r["error"]["flicker"] == 0 for r in jm["rows"]) and all(r["accumulate"] == 1 for r in jm["rows"])
js = json.load(open(t + "/s2/results.json"))
assert js["meta"]["shard"] == {"k": 2, "n": 2}, js["meta"].get("shard")
assert "shard" not in jm["meta"] and jm["meta"]["merged_shards"] == 2
assert jm["meta"]["argv"] == jf["meta"]["argv"] and "--device" not in jm["meta"]["argv"]
for k in jf["meta"]:   # the merged meta is the unsharded run's, apart from the run time
    assert k == "elapsed_s" or jm["meta"].get(k) == jf["meta"][k], "meta.%s differs" % k
print("timing columns left out of the comparison:", len(timed))
EOF

# ---- refusals ----
for v in 0/2 3/2 a/b 2 1/0 "1/2x"; do
  expect_fail "bench --shard $v" 2 "--shard $v: expected K/N" bench "${SWEEP[@]}" --shard "$v" --out "$tmp/bad"
done
expect_fail "merge: missing shard" 1 "shard 2/2 missing" bench-merge --out "$tmp/m2" "$tmp/s1"
# the merge written over one of its shards would lose that shard's rows: refused, the shard kept
cp "$tmp/s1/results.json" "$tmp/s1.json.before"
expect_fail "merge: --out is a shard" 2 "--out $tmp/s1/ is the shard folder $tmp/s1" bench-merge --out "$tmp/s1/" "$tmp/s1" "$tmp/s2"
cmp -s "$tmp/s1/results.json" "$tmp/s1.json.before" && ok || bad "merge: --out a shard folder changed the shard"
cp -r "$tmp/s1" "$tmp/s1copy"
expect_fail "merge: shard twice" 1 "$tmp/s1copy: shard 1/2 given twice (also $tmp/s1)" \
  bench-merge --out "$tmp/m2" "$tmp/s1" "$tmp/s2" "$tmp/s1copy"
# an unsharded run is the one shard of 1: not part of a sweep in 2 shards, but merged alone it is
# the same run again
expect_fail "merge: whole run with a shard" 1 "$tmp/full is 1/1" bench-merge --out "$tmp/m2" "$tmp/full" "$tmp/s2"
"$PG" bench-merge --out "$tmp/again" "$tmp/full" >"$tmp/again.log" 2>&1 || bad "bench-merge of the unsharded run: exit $?"
for f in results.csv results.json gpu_time_vs_lights.svg flip_vs_time.svg; do
  [ -s "$tmp/again/$f" ] || bad "bench-merge of the unsharded run wrote no $f"
done
cmp -s <(cut -d, -f1-12 "$tmp/full/results.csv") <(cut -d, -f1-12 "$tmp/again/results.csv") ||
  bad "bench-merge of the unsharded run: results.csv rows differ from the run's"
"$PG" bench --pipelines forward_plus,deferred --sweep gbuffer=float,packed --lights 16,32 --size 160x90 --frames 2 \
  --warmup 1 --validation --quiet --shard 2/2 --out "$tmp/other" >"$tmp/other.log" 2>&1 || bad "bench (other sweep): exit $?"
expect_fail "merge: different sweeps" 1 "$tmp/other: not the same sweep as $tmp/s1: meta.lights differs" \
  bench-merge --out "$tmp/m2" "$tmp/s1" "$tmp/other"
python3 - "$tmp/s1copy/results.json" <<'EOF' || bad "could not edit the copy"
import json, sys
d = json.load(open(sys.argv[1])); d["rows"] = [r for r in d["rows"] if r["index"] != 2]
json.dump(d, open(sys.argv[1], "w"))
EOF
expect_fail "merge: configuration missing" 1 "$tmp/s1copy: configuration 2 (shard 1/2) missing" \
  bench-merge --out "$tmp/m2" "$tmp/s1copy" "$tmp/s2"
expect_fail "merge: no --out" 2 "--out DIR is required" bench-merge "$tmp/s1" "$tmp/s2"
# a shard count past 2^32 was cast to 0: no shard missing, then a division by zero (SIGFPE)
cp -r "$tmp/s1" "$tmp/s1huge"
python3 - "$tmp/s1huge/results.json" <<'EOF' || bad "could not edit the copy"
import json, sys
d = json.load(open(sys.argv[1])); d["meta"]["shard"] = {"k": 1, "n": 4294967296}
json.dump(d, open(sys.argv[1], "w"))
EOF
expect_fail "merge: shard count past the range" 1 "meta.shard: expected" bench-merge --out "$tmp/m2" "$tmp/s1huge"
[ ! -e "$tmp/m2" ] && ok || bad "a refused merge wrote $tmp/m2"
# shards whose rows failed (a pipeline file that does not load) merge, and exit 1 as the sweep run
# whole does (the merge said "1 failed" and exited 0)
printf '{ "name": broken' >"$tmp/broken.json"
for k in 1 2; do
  "$PG" bench --pipelines naive,"$tmp/broken.json" --lights 4 --size 32x18 --frames 1 --warmup 0 --quiet \
    --shard $k/2 --out "$tmp/f$k" >/dev/null 2>&1
done
"$PG" bench-merge --out "$tmp/fm" "$tmp/f1" "$tmp/f2" >"$tmp/out" 2>"$tmp/err"
[ $? = 1 ] && grep -q "2 rows (1 failed)" "$tmp/out" && [ -s "$tmp/fm/results.csv" ] && ok \
  || { bad "merge of shards with a failed row: want its outputs and exit 1"; cat "$tmp/out" "$tmp/err"; }

check_finish bench_shard_test
