#!/usr/bin/env bash
# cache_times.sh PASSGRAPH_BINARY [RUNS] - what the shader and pipeline caches save (pg_cache.h):
#  1. `passgraph render` of the default scene at 320x180 ($PG_SIZE) for each shipped pipeline, wall time,
#     median of RUNS (default 3): --no-shader-cache (every variant through glslang, no pipeline
#     cache: what passgraph did before the caches), cold (empty cache folder; compiles and writes)
#     and warm (the same folder again; glslang runs for nothing).
#  2. the viewer (under xvfb-run) switching forward_plus -> deferred (frame 5) -> forward_plus
#     (frame 10), then the sliders: ambient 0.05 (frame 12), exposure 0.5 (frame 15), ambient 0.05
#     again (frame 18): the time from the change to the first frame drawn with it, without and with
#     the caches. PG_PART=render or PG_PART=view runs one of the two.
set -u
PG=$1
RUNS=${2:-3}
SIZE=${PG_SIZE:-320x180}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
t_render() { # cache-dir extra-args... -> "wall_s glslang_ms"
  local dir=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  PASSGRAPH_CACHE_STATS=1 PASSGRAPH_CACHE_DIR=$dir "$PG" render --size "$SIZE" --out "$tmp/o.png" "$@" >/dev/null \
    2>"$tmp/err" || { echo "render failed: $*" >&2; cat "$tmp/err" >&2; }
  t1=$(date +%s.%N)
  echo "$(awk "BEGIN {print $t1 - $t0}") $(sed -n 's/.*variants compiled (\([0-9.]*\) ms).*/\1/p' "$tmp/err") $(sed -n 's/.*pipeline cache \([0-9]*\) bytes loaded.*/\1/p' "$tmp/err")"
}
col() { awk "{print \$$1}" | median; }
PART=${PG_PART:-all}
[ "$PART" != view ] && printf '%-16s %9s %9s %9s | %9s %9s %9s | %s\n' "" "wall s" "" "" "glslang" "ms" "" "warm: pipeline cache"
[ "$PART" != view ] && printf '%-16s %9s %9s %9s | %9s %9s %9s | %9s   (render --size %s, median of %d)\n' pipeline no-cache cold warm \
  no-cache cold warm "bytes" "$SIZE" "$RUNS"
for p in naive forward_plus deferred deferred_oct16 deferred_packed reference; do
  [ "$PART" = view ] && break
  pj=$root/pipelines/$p.json
  for i in $(seq "$RUNS"); do t_render "$tmp/none" --pipeline "$pj" --no-shader-cache; done >"$tmp/nc"
  for i in $(seq "$RUNS"); do rm -rf "$tmp/c"; t_render "$tmp/c" --pipeline "$pj"; done >"$tmp/cold"
  for i in $(seq "$RUNS"); do t_render "$tmp/c" --pipeline "$pj"; done >"$tmp/warm"
  printf '%-16s %9.3f %9.3f %9.3f | %9.1f %9.1f %9.1f | %9s\n' "$p" "$(col 1 <"$tmp/nc")" "$(col 1 <"$tmp/cold")" \
    "$(col 1 <"$tmp/warm")" "$(col 2 <"$tmp/nc")" "$(col 2 <"$tmp/cold")" "$(col 2 <"$tmp/warm")" "$(col 3 <"$tmp/warm")"
done
if [ "$PART" != render ] && command -v xvfb-run >/dev/null; then
  for mode in no-cache cached; do
    extra=()
    [ "$mode" = no-cache ] && extra=(--no-shader-cache)
    rm -rf "$tmp/v"
    # the first run fills the on-disk cache; the second is the one reported (for cached, warm)
    for k in 1 2; do
      PASSGRAPH_CACHE_STATS=1 PASSGRAPH_CACHE_DIR=$tmp/v xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 320x180 --frames 20 \
        --pipeline "$root/pipelines/forward_plus.json" --at 5:pipeline=deferred.json --at 10:pipeline=forward_plus.json \
        --at 12:set=ambient=0.05 --at 15:set=exposure=0.5 --at 18:set=ambient=0.05 \
        "${extra[@]}" >"$tmp/vout" 2>"$tmp/verr" || { echo "view failed" >&2; tail -5 "$tmp/verr" >&2; }
    done
    echo "viewer $mode: $(grep 'ready in' "$tmp/vout" | sed 's/^view: //; s/ (load.*//' | tr '\n' ';')" \
      "$(grep -o '[0-9]* shader variants compiled ([0-9.]* ms)' "$tmp/verr")"
  done
fi
