#!/usr/bin/env bash
# fault_test.sh PASSGRAPH_BINARY - device loss and driver errors: PASSGRAPH_FAULT_AT=k makes the
# k-th checked Vulkan call report VK_ERROR_DEVICE_LOST (core/vk/vk_context.h). For every k until a run
# no longer reaches k calls, `passgraph render` must exit 1 with a message naming the failed call
# and the error - never crash, hang or exit 0 with a broken image.
set -u
PG=$1
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$root/tests/corpus/gltf/ok_textured.gltf"
pass=0
fail=0
# deferred_packed+emulate: the two-queue plan (batches, timeline semaphores) on the one queue
for pe in naive forward_plus deferred_packed deferred_packed+emulate; do
  p=${pe%+emulate}
  extra=()
  [ "$pe" != "$p" ] && extra=(--async-compute emulate)
  k=1
  while :; do
    PASSGRAPH_FAULT_AT=$k timeout 60 "$PG" render --pipeline "$root/pipelines/$p.json" --scene "$scene" --size 32x18 \
      --lights 4 --frames 2 "${extra[@]}" --quiet --out "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if ! grep -q "fault injection" "$tmp/err"; then
      # the run made fewer than k checked calls: it must have succeeded
      [ $rc -eq 0 ] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: $p k=$k without fault: rc $rc"; cat "$tmp/err"; }
      echo "fault_test: $pe: $((k - 1)) checked Vulkan calls, each failed once"
      break
    fi
    call=$(sed -n 's/.*failing call #[0-9]*: \(vk[A-Za-z0-9]*\).*/\1/p' "$tmp/err" | head -1)
    if [ $rc -ne 1 ]; then
      fail=$((fail + 1)); echo "FAIL: $p k=$k ($call): exit $rc"; tail -3 "$tmp/err"
    elif ! grep -q "VK_ERROR_DEVICE_LOST" "$tmp/err" || ! grep -q -- "$call" "$tmp/err"; then
      fail=$((fail + 1)); echo "FAIL: $p k=$k: message does not name $call and the error"; tail -3 "$tmp/err"
    else
      pass=$((pass + 1))
    fi
    k=$((k + 1))
    [ $k -gt 400 ] && { fail=$((fail + 1)); echo "FAIL: $p: more than 400 checked calls?"; break; }
  done
done
echo "fault_test: $pass passed, $fail failed"
[ $fail -eq 0 ]
