#!/usr/bin/env bash
# input_paths_test.sh PASSGRAPH_BINARY - every path input checked before it is read, every output
# path before the work: a FIFO (as --ocio-config, $OCIO, scene, pipeline, scenario, glTF buffer),
# a directory and /dev/zero as a scene, include escapes, a pipeline over the size cap, a file that
# is not JSON, unwritable --out, a bench-merge row with a field of the wrong type, and the memory
# estimate of a big --size. Each must fail at once with one clear line and a non-zero exit; every
# command runs under `timeout 20`, so a hang fails the test instead of stalling it.
set -u
PG=${1:?usage: input_paths_test.sh PASSGRAPH_BINARY}
root=$(cd "$(dirname "$0")/../.." && pwd)
. "$root/tests/cli/check_lib.sh"

SMALL=(--size 32x18 --lights 4)

# expect_fail "description" "expected stderr substring" args...: exit non-zero (not 124: a
# timeout is a hang), the substring in stderr
expect_fail() {
  local what=$1 want=$2
  shift 2
  timeout 20 "$PG" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [ $rc -eq 124 ]; then bad "$what: hung (killed after 20 s)"; return; fi
  if [ $rc -eq 0 ]; then bad "$what: exit 0"; cat "$tmp/err"; return; fi
  if grep -qF -- "$want" "$tmp/err"; then ok; else bad "$what: stderr lacks '$want':"; cat "$tmp/err"; fi
}

mkfifo "$tmp/fifo"
mkfifo "$tmp/fifo.json"
mkdir -p "$tmp/adir"

# ---- FIFOs: refused by name, never opened ----
expect_fail "FIFO as --ocio-config (render)" "OCIO config '$tmp/fifo': is a FIFO, not a regular file" \
  render --ocio-config "$tmp/fifo" "${SMALL[@]}" --out "$tmp/x.png"
expect_fail "FIFO as --ocio-config (dump)" "OCIO config '$tmp/fifo': is a FIFO, not a regular file" \
  dump --ocio-config "$tmp/fifo" "${SMALL[@]}"
timeout 20 env OCIO="$tmp/fifo" "$PG" render "${SMALL[@]}" --out "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ] && [ $rc -ne 124 ] && grep -qF "OCIO config '$tmp/fifo': is a FIFO, not a regular file" "$tmp/err"; then ok
else bad "FIFO as \$OCIO: rc $rc"; cat "$tmp/err"; fi
expect_fail "FIFO as --scene" "scene '$tmp/fifo': is a FIFO, not a regular file" \
  render --scene "$tmp/fifo" "${SMALL[@]}" --out "$tmp/x.png"
expect_fail "FIFO as --pipeline" "pipeline '$tmp/fifo.json': is a FIFO, not a regular file" \
  dump --pipeline "$tmp/fifo.json"
expect_fail "FIFO as --scenario" "scenario '$tmp/fifo.json': is a FIFO, not a regular file" \
  render --scenario "$tmp/fifo.json" "${SMALL[@]}" --out "$tmp/x.png"

# ---- a directory and a device as a scene ----
expect_fail "directory as --scene" "scene '$tmp/adir': is a directory, not a regular file" \
  render --scene "$tmp/adir" "${SMALL[@]}" --out "$tmp/x.png"
expect_fail "/dev/zero as --scene" "scene '/dev/zero': is a character device, not a regular file" \
  render --scene /dev/zero "${SMALL[@]}" --out "$tmp/x.png"

# ---- a glTF buffer that is a FIFO, an image that is /dev/zero ----
B64=AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA
cat >"$tmp/fifo_buffer.gltf" <<JSON
{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "buffers": [{"uri": "fifo.bin", "byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]}]}
JSON
mkfifo "$tmp/fifo.bin"
expect_fail "glTF buffer uri is a FIFO" "buffers[0]: 'fifo.bin' ($tmp/fifo.bin) is a FIFO, not a regular file" \
  render --scene "$tmp/fifo_buffer.gltf" "${SMALL[@]}" --out "$tmp/x.png"
ln -s /dev/zero "$tmp/zero.png"
sed -e 's/"fifo.bin"/"data:application\/octet-stream;base64,'$B64'"/' "$tmp/fifo_buffer.gltf" |
  sed -e 's/"accessors"/"images": [{"uri": "zero.png"}], "textures": [{"source": 0}], "accessors"/' >"$tmp/zero_image.gltf"
expect_fail "glTF image uri is /dev/zero" "images[0]: 'zero.png' ($tmp/zero.png) is a character device, not a regular file" \
  render --scene "$tmp/zero_image.gltf" "${SMALL[@]}" --out "$tmp/x.png"

# ---- include escapes, refused by name ----
mkdir -p "$tmp/pl"
cp "$root/pipelines/naive.json" "$tmp/pl/naive.json"
python3 - "$tmp/pl" <<'PY'
import json, sys
d = sys.argv[1]
p = json.load(open(d + "/naive.json"))
for name, inc in (("abs.json", "/etc/passwd"), ("up.json", "../../../../../../../../etc/passwd")):
    q = dict(p); q["include"] = [inc]
    json.dump(q, open(d + "/" + name, "w"))
PY
expect_fail "include absolute" "include[0]: include '/etc/passwd' is outside the allowed folders (the including file's folder, the data folder, --include-dir)" \
  dump --pipeline "$tmp/pl/abs.json"
grep -q "root:" "$tmp/err" && bad "include absolute: the file's text was printed" || ok
expect_fail "include ../ escape" "include '../../../../../../../../etc/passwd' is outside the allowed folders" \
  dump --pipeline "$tmp/pl/up.json"
# a fragment in a folder named with --include-dir is allowed
mkdir -p "$tmp/frags"
echo '{"description": "empty fragment"}' >"$tmp/frags/empty.json"
python3 - "$tmp/pl" "$tmp/frags/empty.json" "$root" <<'PY'
import json, sys
p = json.load(open(sys.argv[1] + "/naive.json"))
p["include"] = [sys.argv[3] + "/pipelines/" + i for i in p.get("include", [])] + [sys.argv[2]]
json.dump(p, open(sys.argv[1] + "/incdir.json", "w"))
PY
expect_fail "include outside without --include-dir" "is outside the allowed folders" dump --pipeline "$tmp/pl/incdir.json"
if timeout 20 "$PG" dump --include-dir "$tmp/frags" --pipeline "$tmp/pl/incdir.json" >"$tmp/out" 2>"$tmp/err"; then ok
else bad "--include-dir: include refused"; cat "$tmp/err"; fi

# ---- a pipeline over the 16 MiB cap: refused before reading ----
truncate -s 17M "$tmp/big.json"
# against the time of a refusal that reads nothing (a missing file): a fixed 1000 ms failed under
# ASan with two other tests running (1080 ms); reading and parsing 17 MiB would add far more
t0=$(date +%s%N)
"$PG" dump --pipeline "$tmp/missing.json" >/dev/null 2>&1
base=$(( ($(date +%s%N) - t0) / 1000000 ))
t0=$(date +%s%N)
expect_fail "pipeline over the cap" "pipeline '$tmp/big.json': is 17.0 MiB, over the 16 MiB cap for pipeline files" \
  dump --pipeline "$tmp/big.json"
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
[ "$ms" -lt $((2 * base + 1000)) ] && ok || bad "pipeline over the cap took $ms ms, a missing file $base ms (read before refused?)"
truncate -s 2200M "$tmp/big.gltf"
expect_fail "scene over the cap" "scene '$tmp/big.gltf': is 2.1 GiB, over the 2 GiB cap for scene files" \
  render --scene "$tmp/big.gltf" "${SMALL[@]}" --out "$tmp/x.png"

# ---- a file that is not JSON: line and column, never its text ----
printf 'root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:daemon:/usr/sbin:/usr/sbin/nologin\n' >"$tmp/passwd.json"
expect_fail "not JSON as --pipeline" "$tmp/passwd.json:1:1: JSON syntax error" dump --pipeline "$tmp/passwd.json"
grep -q "root:x\|daemon" "$tmp/err" && bad "not JSON: the file's text was printed: $(cat "$tmp/err")" || ok
expect_fail "not JSON as --scenario" "$tmp/passwd.json:1:1: JSON syntax error" \
  render --scenario "$tmp/passwd.json" "${SMALL[@]}" --out "$tmp/x.png"
grep -q "root:x\|daemon" "$tmp/err" && bad "not JSON scenario: the file's text was printed" || ok
printf '{"asset": {"version": "2.0"}, "x": root:x:0:0:root }' >"$tmp/passwd.gltf"
expect_fail "broken JSON as a .gltf scene" "JSON syntax error: parse error at line 1, column 36" \
  dump --scene "$tmp/passwd.gltf"
grep -q "root:x\|\"x\"" "$tmp/err" && bad "broken glTF: the file's text was printed: $(cat "$tmp/err")" || ok

# ---- outputs that cannot be written: at once, with the OS reason ----
t0=$(date +%s%N)
expect_fail "render --out missing folder" "render: --out '/missing/dir/x.png': cannot write: No such file or directory" \
  render "${SMALL[@]}" --out /missing/dir/x.png
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
[ "$ms" -lt 2000 ] && ok || bad "render --out missing folder took $ms ms (rendered first?)"
mkdir -p "$tmp/adir.png"
expect_fail "render --out a folder" "render: --out '$tmp/adir.png': cannot write: Is a directory" \
  render "${SMALL[@]}" --out "$tmp/adir.png"
expect_fail "render --hdr-out missing folder" "render: --hdr-out '/missing/dir/x.exr': cannot write: No such file or directory" \
  render "${SMALL[@]}" --out "$tmp/x.png" --hdr-out /missing/dir/x.exr
expect_fail "dump --out missing folder" "dump: --out '/missing/dir/p.txt': cannot write: No such file or directory" \
  dump --out /missing/dir/p.txt
expect_fail "compare --heatmap missing folder" "compare: --heatmap '/missing/dir/h.png': cannot write: No such file or directory" \
  compare "${SMALL[@]}" --heatmap /missing/dir/h.png
expect_fail "bench --out under a file" "bench: --out $tmp/passwd.json/b: cannot create $tmp/passwd.json/b: Not a directory" \
  bench --pipelines naive --lights 4 --size 32x18 --frames 1 --out "$tmp/passwd.json/b"

# ---- bench-merge: a row field of the wrong type ----
if timeout 120 "$PG" bench --pipelines naive --lights 4 --size 32x18 --frames 1 --warmup 0 --quiet --shard 1/1 \
     --out "$tmp/s1" >"$tmp/bench.log" 2>&1; then
  python3 - "$tmp/s1/results.json" <<'PY'
import json, sys
p = sys.argv[1]
d = json.load(open(p))
d["rows"][0]["gpu_ms"] = "fast"
json.dump(d, open(p, "w"))
PY
  expect_fail "bench-merge gpu_ms string" \
    "bench-merge: '$tmp/s1/results.json' rows[0].gpu_ms: expected an object of statistics, got string \"fast\"" \
    bench-merge --out "$tmp/m" "$tmp/s1"
  python3 - "$tmp/s1/results.json" <<'PY'
import json, sys
p = sys.argv[1]
d = json.load(open(p))
d["rows"][0]["gpu_ms"] = {"n": 1, "median": "fast"}
json.dump(d, open(p, "w"))
PY
  expect_fail "bench-merge gpu_ms.median string" \
    "rows[0].gpu_ms.median: expected a number, got string \"fast\"" bench-merge --out "$tmp/m" "$tmp/s1"
  python3 - "$tmp/s1/results.json" <<'PY'
import json, sys
p = sys.argv[1]
d = json.load(open(p))
d["rows"][0]["gpu_ms"] = {"n": 1, "median": 1.0}
d["rows"][0]["passes"][0].pop("name")
json.dump(d, open(p, "w"))
PY
  expect_fail "bench-merge pass without a name" \
    "rows[0].passes[0].name: expected a string, got nothing (missing)" bench-merge --out "$tmp/m" "$tmp/s1"
else
  bad "bench --shard 1/1 failed"; cat "$tmp/bench.log"
fi

# ---- a big --size: one line with the plan's estimate, before the work ----
timeout 60 "$PG" dump --size 16384x16384 --out "$tmp/big.txt" >"$tmp/out" 2>"$tmp/err"
if grep -qE "^dump: 16384x16384 needs about [0-9.]+ GiB of device memory \(plan estimate\); this can take minutes on a CPU device$" "$tmp/err"; then ok
else bad "dump --size 16384x16384: no estimate line"; cat "$tmp/err"; fi
timeout 20 "$PG" dump --size 640x360 --out "$tmp/small.txt" >"$tmp/out" 2>"$tmp/err"
grep -q "needs about" "$tmp/err" && bad "estimate printed for 640x360" || ok
# render goes through the same estimate (a lowered threshold keeps the frame small)
PASSGRAPH_SIZE_NOTE_MIB=0 timeout 60 "$PG" render "${SMALL[@]}" --out "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
grep -q "^passgraph render: 32x18 needs about .* of device memory (plan estimate)" "$tmp/err" && ok \
  || { bad "render: no estimate line with PASSGRAPH_SIZE_NOTE_MIB=0"; cat "$tmp/err"; }
# bench too, for every size of its sweep, before any row runs
PASSGRAPH_SIZE_NOTE_MIB=0 timeout 120 "$PG" bench --pipelines naive --lights 4 --size 32x18 --frames 1 --warmup 0 \
  --quiet --out "$tmp/bench" >"$tmp/out" 2>"$tmp/err"
grep -q "^passgraph bench: 32x18 needs about .* of device memory (plan estimate)" "$tmp/err" && ok \
  || { bad "bench: no estimate line with PASSGRAPH_SIZE_NOTE_MIB=0"; cat "$tmp/err"; }

check_finish input_paths_test
