#!/usr/bin/env bash
# fault_test.sh PASSGRAPH_BINARY - device loss and driver errors: PASSGRAPH_FAULT_AT=k makes the
# k-th checked Vulkan call report VK_ERROR_DEVICE_LOST (core/vk/vk_context.h). For every k until a run
# no longer reaches k calls, `passgraph render` must exit 1 with a message naming the failed call
# and the error - never crash, hang or exit 0 with a broken image.
set -u
PG=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$root/tests/corpus/gltf/ok_textured.gltf"
# one configuration: walks k until a run no longer reaches k checked calls; prints its counts as
# the last line "counts PASS FAIL". The four configurations run in two workers (ctest runs the
# tests one after the other, so this uses the second core).
run_config() {
  local pe=$1 dir=$2 p=${1%+emulate} pass=0 fail=0 k=1 rc call
  local extra=()
  [ "$pe" != "$p" ] && extra=(--async-compute emulate)
  # a 4 x 2 x 8 cluster grid where the pipeline has one: the same Vulkan calls as the default
  # 16 x 9 x 32 (only buffer sizes differ), whose light assignment took a quarter of each run on lavapipe
  [ "$p" != naive ] && extra+=(--set grid_x=4 --set grid_y=2 --set grid_z=8)
  # the scene has no lights, so it is lit by the default environment, whose filter pass took half
  # of a run that reaches it on lavapipe: naive and deferred_packed fail its calls, forward_plus and
  # the emulated compute queue render without it
  [ "$pe" = forward_plus ] || [ "$pe" = deferred_packed+emulate ] && extra+=(--environment none)
  while :; do
    PASSGRAPH_FAULT_AT=$k timeout 60 "$PG" render --pipeline "$root/pipelines/$p.json" --scene "$scene" --size 32x18 \
      --lights 4 --frames 2 "${extra[@]}" --quiet --out "$dir/x.png" >"$dir/out" 2>"$dir/err"
    rc=$?
    if ! grep -q "fault injection" "$dir/err"; then
      # the run made fewer than k checked calls: it must have succeeded
      [ $rc -eq 0 ] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: $p k=$k without fault: rc $rc"; cat "$dir/err"; }
      echo "fault_test: $pe: $((k - 1)) checked Vulkan calls, each failed once"
      break
    fi
    call=$(sed -n 's/.*failing call #[0-9]*: \(vk[A-Za-z0-9]*\).*/\1/p' "$dir/err" | head -1)
    if [ $rc -ne 1 ]; then
      fail=$((fail + 1)); echo "FAIL: $p k=$k ($call): exit $rc"; tail -3 "$dir/err"
    elif ! grep -q "VK_ERROR_DEVICE_LOST" "$dir/err" || ! grep -q -- "$call" "$dir/err"; then
      fail=$((fail + 1)); echo "FAIL: $p k=$k: message does not name $call and the error"; tail -3 "$dir/err"
    else
      pass=$((pass + 1))
    fi
    k=$((k + 1))
    [ $k -gt 400 ] && { fail=$((fail + 1)); echo "FAIL: $p: more than 400 checked calls?"; break; }
  done
  echo "counts $pass $fail"
}
# two workers of about the same time (106 + 146 and 116 + 143 checked calls with the options above;
# 133 and 172 for forward_plus and the emulated queue with the environment)
configs=(naive deferred_packed+emulate forward_plus deferred_packed)
for w in 0 2; do
  (for j in $w $((w + 1)); do
     mkdir -p "$tmp/$j"
     run_config "${configs[$j]}" "$tmp/$j" >"$tmp/$j.log" 2>&1
   done) &
done
wait
pass=0
fail=0
for j in 0 1 2 3; do
  grep -v '^counts ' "$tmp/$j.log"
  read -r _ p f < <(grep '^counts ' "$tmp/$j.log" || echo "counts 0 1")
  pass=$((pass + p))
  fail=$((fail + f))
done
echo "fault_test: $pass passed, $fail failed"
[ $fail -eq 0 ]
