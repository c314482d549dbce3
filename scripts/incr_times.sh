#!/usr/bin/env bash
# incr_times.sh BINARY... - what the viewer waits for after a change, per binary (e.g. a build of
# the commit before the incremental plan signature, then this one), in one run on one machine.
# The viewer (under xvfb-run, 320x180, 2 frames in flight, the default scene) starts on
# forward_plus.json and at fixed frames: switches to deferred.json (5) and back (10), drags the
# ambient slider (0.05, 0.06, 0.07 at frames 13-15), the exposure slider (0.5, 0.6 at 18-19), and
# changes the shading model (blinn_phong at 22: a new shader variant). Printed per change: the time
# from the change to the first frame drawn with it (load, compile, plan set, first frame: the
# viewer's "ready in" line) and what the runtime re-created (when the binary reports it). Each
# binary runs RUNS + 1 times with its own cache folder: the first run fills the SPIR-V and pipeline caches,
# the others (RUNS, default 3: medians) are reported with warm caches; PG_NO_CACHE=1 adds
# --no-shader-cache instead.
set -u
[ $# -ge 1 ] || { echo "usage: incr_times.sh BINARY..." >&2; exit 2; }
command -v xvfb-run >/dev/null || { echo "incr_times: xvfb-run not installed" >&2; exit 77; }
RUNS=${RUNS:-3}
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
  : >"$tmp/all"
  for k in $(seq 0 "$RUNS"); do # run 0 fills the caches; runs 1..RUNS are reported
    PASSGRAPH_CACHE_DIR=$tmp/cache$n xvfb-run -a -s "-screen 0 640x480x24" "$pg" view --size 320x180 --frames 26 \
      --pipeline "$root/pipelines/forward_plus.json" --at 5:pipeline=deferred.json --at 10:pipeline=forward_plus.json \
      --at 13:set=ambient=0.05 --at 14:set=ambient=0.06 --at 15:set=ambient=0.07 \
      --at 18:set=exposure=0.5 --at 19:set=exposure=0.6 --at 22:set=shading=blinn_phong \
      "${extra[@]}" >"$tmp/out" 2>"$tmp/err" || { echo "view failed: $pg" >&2; tail -5 "$tmp/err" >&2; }
    [ "$k" = 0 ] && continue
    awk '/: set |: pipeline / {sub(/^view: /, ""); what = $0; next}
         /ready in/ {match($0, /ready in [0-9.]+ ms/); t = substr($0, RSTART + 9, RLENGTH - 12);
                     r = "-"; if (match($0, /rebuilt: [a-z]+/)) r = substr($0, RSTART + 9, RLENGTH - 9);
                     gsub(/ /, "~", what); print what, t, r}
         /host frame time median/ {match($0, /median [0-9.]+/); print "host~frame~time~median", substr($0, RSTART + 7, RLENGTH - 7), "-"}' \
      "$tmp/out" >>"$tmp/all"
  done
  rev="?"
  [ "$(git -C "$root" rev-parse --show-toplevel 2>/dev/null)" = "$root" ] && rev=$(git -C "$root" rev-parse --short HEAD)
  echo "== $pg (commit $rev${extra[*]:+, ${extra[*]}}; ms, median of $RUNS runs, then min..max)"
  awk '{k = $1; if (!(k in n)) order[++m] = k; v[k, ++n[k]] = $2; r[k] = $3}
       END {for (i = 1; i <= m; i++) {k = order[i]; c = n[k];
              for (a = 1; a <= c; a++) for (b = a + 1; b <= c; b++) if (v[k, b] < v[k, a]) {t = v[k, a]; v[k, a] = v[k, b]; v[k, b] = t}
              med = c % 2 ? v[k, (c + 1) / 2] : (v[k, c / 2] + v[k, c / 2 + 1]) / 2; name = k; gsub(/~/, " ", name);
              printf "  %-36s %8.1f  (%.1f..%.1f)  %s\n", name, med, v[k, 1], v[k, c], r[k] == "-" ? "" : "rebuilt: " r[k]}}' "$tmp/all"
done
