#!/usr/bin/env bash
# run.sh - builds the seed corpora and runs the libFuzzer targets one after another
# (tests/fuzz/README.md). Usage:
#   tests/fuzz/run.sh [BUILD_DIR [TARGET...]]      (defaults: /tmp/build-fuzz, every target)
# Environment: FUZZ_RUNS (executions per target, default 1000000), FUZZ_SECONDS (time cap per
# target, default 1800), FUZZ_WORK (corpora, artifacts and logs, default /tmp/pg-fuzz).
# Each target keeps its growing corpus in $FUZZ_WORK/corpus/TARGET (seeded on the first run) and
# writes crash-*/leak-*/timeout-*/oom-* inputs to $FUZZ_WORK/artifacts/TARGET/. The libFuzzer log
# is $FUZZ_WORK/logs/TARGET/fuzz-0.log.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD=${1:-/tmp/build-fuzz}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(fuzz_pipeline_json fuzz_gltf fuzz_hdr)
RUNS=${FUZZ_RUNS:-1000000}
SECONDS_MAX=${FUZZ_SECONDS:-1800}
WORK=${FUZZ_WORK:-/tmp/pg-fuzz}

seed_pipeline() { # $1 = directory
  local d=$1
  cp "$ROOT"/pipelines/*.json "$d"/
  for f in "$ROOT"/pipelines/fragments/*.json; do cp "$f" "$d/frag_$(basename "$f")"; done
  for f in "$ROOT"/tests/corpus/pipelines/*.json; do cp "$f" "$d/bad_$(basename "$f")"; done
  find "$ROOT"/tests/corpus/pipelines/good "$ROOT"/tests/corpus/pipelines/inc -name '*.json' |
    while read -r f; do cp "$f" "$d/sub_$(echo "${f#"$ROOT"/tests/corpus/pipelines/}" | tr / _)"; done
  for f in "$ROOT"/tests/corpus/graph/*.json; do cp "$f" "$d/graph_$(basename "$f")"; done
  # the examples' `shader` passes, their includes pointed at the target's fragments/ (their GLSL is
  # copied beside the input by the target itself)
  for f in "$ROOT"/pipelines/examples/*/*.json; do
    sed 's#"\.\./\.\./fragments/#"fragments/#g' "$f" >"$d/example_$(basename "$f")"
  done
}
seed_hdr() {
  cp "$ROOT"/tests/fuzz/seeds/hdr/* "$1"/
}
seed_gltf() {
  local d=$1
  cp "$ROOT"/tests/corpus/gltf/*.gltf "$ROOT"/tests/corpus/gltf/*.glb "$d"/
  for f in "$ROOT"/tests/corpus/gltf/animation/*.gltf; do cp "$f" "$d/anim_$(basename "$f")"; done
  cp "$ROOT"/tests/fuzz/seeds/gltf/* "$d"/
}

for t in "${TARGETS[@]}"; do
  bin="$BUILD/tests/fuzz/$t"
  [ -x "$bin" ] || { echo "run.sh: $bin not built (see tests/fuzz/README.md)" >&2; exit 1; }
  case $t in
    fuzz_pipeline_json) dict=pipeline.dict; seeder=seed_pipeline ;;
    fuzz_gltf) dict=gltf.dict; seeder=seed_gltf ;;
    fuzz_hdr) dict=hdr.dict; seeder=seed_hdr ;;
    *) echo "run.sh: unknown target $t" >&2; exit 1 ;;
  esac
  corpus="$WORK/corpus/$t"; art="$WORK/artifacts/$t"; logs="$WORK/logs/$t"
  mkdir -p "$corpus" "$art" "$logs" "$WORK/tmp"
  if [ -z "$(ls -A "$corpus")" ]; then $seeder "$corpus"; fi
  echo "run.sh: $t: $(ls "$corpus" | wc -l) corpus files, up to $RUNS runs / ${SECONDS_MAX}s"
  # the targets' private directories go under $WORK/tmp: a crash or an interrupt skips their
  # clean-up at exit, so they are removed here
  (cd "$logs" && TMPDIR="$WORK/tmp" "$bin" -jobs=1 -runs="$RUNS" -max_total_time="$SECONDS_MAX" -max_len=65536 \
     -timeout=10 -rss_limit_mb=2048 -dict="$ROOT/tests/fuzz/$dict" -artifact_prefix="$art/" \
     -print_final_stats=1 "$corpus") || true
  rm -rf "$WORK"/tmp/pg_fuzz_*
  tail -n 25 "$logs/fuzz-0.log"
  echo "run.sh: $t: corpus now $(ls "$corpus" | wc -l) files; findings: $(ls "$art" | wc -l)"
done
