#!/usr/bin/env bash
# incr_times.sh BINARY... - what the viewer waits for after a change, per binary (e.g. a build of
# the commit before the incremental plan signature, then this one), in one run on one machine.
# The viewer (under xvfb-run, 320x180, 2 frames in flight, the default scene) starts on
# forward_plus.json and at fixed frames: switches to deferred.json (5) and back (10), drags the
# ambient slider (0.05, 0.06, 0.07 at frames 13-15), the exposure slider (0.5, 0.6 at 18-19), and
# changes the shading model (blinn_phong at 22: a new shader variant). Printed per change: the time
# from the change to the first frame drawn with it (load, compile, plan set, first frame: the
# viewer's "ready in" line) and what the runtime re-created (when the binary reports it). Each
# binary runs twice with its own cache folder: the first run fills the SPIR-V and pipeline caches,
# the second is the one reported (warm caches); PG_NO_CACHE=1 adds --no-shader-cache instead.
set -u
[ $# -ge 1 ] || { echo "usage: incr_times.sh BINARY..." >&2; exit 2; }
command -v xvfb-run >/dev/null || { echo "incr_times: xvfb-run not installed" >&2; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
extra=()
[ "${PG_NO_CACHE:-0}" = 1 ] && extra=(--no-shader-cache)
n=0
for pg in "$@"; do
  n=$((n + 1))
  # the data folder next to the binary's build folder (its own pipelines and shaders)
  root=$(cd "$(dirname "$pg")/.." && pwd)
  [ -f "$root/pipelines/forward_plus.json" ] || root=$(cd "$(dirname "$0")/.." && pwd)
  for k in 1 2; do
    PASSGRAPH_CACHE_DIR=$tmp/cache$n xvfb-run -a -s "-screen 0 640x480x24" "$pg" view --size 320x180 --frames 26 \
      --pipeline "$root/pipelines/forward_plus.json" --at 5:pipeline=deferred.json --at 10:pipeline=forward_plus.json \
      --at 13:set=ambient=0.05 --at 14:set=ambient=0.06 --at 15:set=ambient=0.07 \
      --at 18:set=exposure=0.5 --at 19:set=exposure=0.6 --at 22:set=shading=blinn_phong \
      "${extra[@]}" >"$tmp/out" 2>"$tmp/err" || { echo "view failed: $pg" >&2; tail -5 "$tmp/err" >&2; }
  done
  rev="?"
  [ "$(git -C "$root" rev-parse --show-toplevel 2>/dev/null)" = "$root" ] && rev=$(git -C "$root" rev-parse --short HEAD)
  echo "== $pg (commit $rev${extra[*]:+, ${extra[*]}})"
  awk '/: set |: pipeline / {sub(/^view: /, ""); what = $0; next}
       /ready in/ {match($0, /ready in [0-9.]+ ms/); t = substr($0, RSTART + 9, RLENGTH - 12);
                   r = ""; if (match($0, /rebuilt: [a-z]+/)) r = substr($0, RSTART + 9, RLENGTH - 9);
                   printf "  %-36s %9.1f ms  %s\n", what, t, r}' "$tmp/out"
  grep -o 'host frame time median [0-9.]* ms' "$tmp/out" | sed 's/^/  /'
done
