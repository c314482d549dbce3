#!/bin/bash
# device-run.sh: the GPU runs behind the tables of docs/performance.md, from a bundle made by
# scripts/bundle.sh (a self-contained folder: passgraph, its libraries, share/passgraph).
#
#   scripts/device-run.sh [STEP...]          (default: validate bench)
#
# Steps, each named by what it measures:
#   validate       visibility pipeline renders with --validation (both resolve paths, the per-pixel
#                  loop, the texture-array walk) and `compare` against naive at 1,000 lights
#   bench          visibility and the deferred pipelines, 1,000 to 1,000,000 lights
#   bench-forward  forward+ with and without the depth pre-pass, and naive (timing only)
#   prepass        forward+ pre-pass tests: validation, compare against no pre-pass, three rounds
#                  of less / equal / none, and 1,000,000 lights once
#   ab             the same bench with two bundles (OLD_BUNDLE against BUNDLE), two rounds
#   sweep          cluster grid and tile size of visibility and deferred_oct16
#   manylight      every pipeline, exact and approximate, 1,000 / 100,000 / 1,000,000 lights: time
#                  per pass, RMSE, FLIP, SSIM, flicker against the reference (naive at 1,000 only:
#                  it takes about 70 s a frame at 1,000,000)
#   tiling         the tiled shading loop with and without its back-face test (tile_backface) at
#                  1,000 / 100,000 / 1,000,000 lights (visibility, deferred_oct16; times only)
#   tile-size      the exact tiled loop with 8x8 and 16x16 tiles at 1,000 / 100,000 / 1,000,000
#                  lights (visibility; times only)
#   file-lights    1,000,000 cis565 lights frozen into the scene file (passgraph lights-table, a
#                  PASSGRAPH_lights_table) against the same count generated: time and error of
#                  visibility, deferred_oct16 and stochastic (threshold 3)
#   shading-cost   the light models at 100,000 lights: lambert, blinn_phong and pbr (the glTF BRDF) in
#                  every clustered exact pipeline (times only)
#   spot-cost      100,000 spot lights against the same 100,000 point lights (same positions, ranges,
#                  colours: scripts/spot_lights.py over `passgraph lights-table --json`) in every
#                  clustered exact pipeline (times only)
#   environment-cost  the environment light: one frame of visibility and reference with the neutral
#                  sky (the filter pass's one-time cost), and every exact pipeline with and without it
#                  at 1,000 lights, Lambert and pbr (times and error against the reference)
#   knob-stochastic  the stochastic_threshold x tile_size sweep of `knobs` alone
#   knobs          the approximation knobs at 1,000,000 lights (stochastic_threshold,
#                  ris_candidates, lightcut_error) and the accumulation curve of the stochastic
#                  pipeline (--accumulate 1, 4, 16, 64)
#   evals          light evaluations a pixel of the compute-shaded pipelines (exact and
#                  approximate) at 100,000 and 1,000,000 lights, with their shading time
#   animation      the animated character (models/walker.gltf): geometry_animate's cost in naive,
#                  forward+, deferred and visibility with the compute queue on and off, and the
#                  images of both queue plans (identical)
#   user-passes    the example user passes (`shader` passes, pipelines/examples/) against the built-in
#                  passes doing the same work: the tone mapper (fullscreen and compute) against display_tonemap
#                  (reinhard, fullscreen) and the OCIO display (compute) at 1,000 lights; the user lighting pass (a per-pixel
#                  loop over the cluster lists, and the tiled one) against deferred's lighting with the per-pixel loop
#                  (tile_lights=false) and tiled, with and without its back-face test, at 100,000
#                  lights (times only)
#   pipeline-stats the driver's statistics of every pipeline (PASSGRAPH_PIPELINE_STATS)
#                  of visibility, deferred_oct16 and forward+ with Lambert and pbr at 100,000 lights
#   raster         the visibility pass's two rasterizers (raster=hardware, compute) at 1,000 / 100,000 /
#                  1,000,000 lights (times; error against the reference at 1,000), every
#                  visibility-buffer pipeline with raster=compute as in manylight (time, RMSE, FLIP,
#                  flicker), and the built-in atrium (alpha-masked grille) at 1,000 lights
#   stress         radius 6 at 1,000,000 lights (exact? list memory), a dense clump of lights
#                  (assets/scenarios/clump.json), 3840x2160 at 100,000 lights
#
# Inputs (environment, with defaults):
#   BUNDLE=.bundle/final        the bundle to measure (its COMMIT file names the commit)
#   OLD_BUNDLE=.bundle/old      the other side of `ab`
#   SCENE=.bundle/assets/dabrovic-sponza/sponza.gltf
#   SCENARIO=$BUNDLE/share/passgraph/assets/scenarios/cis565.json
#   ICD=                        a Vulkan driver manifest (sets VK_DRIVER_FILES when given)
#   OUT=device-run-out          where the results.csv folders and logs go
#   SIZE=1920x1080
#   DRY_RUN=1                   print the commands instead of running them
# Each bench step writes OUT/NAME/results.csv; scripts/tables/results_table.py makes the tables.
set -u
BUNDLE=${BUNDLE:-.bundle/final}
OLD_BUNDLE=${OLD_BUNDLE:-.bundle/old}
SCENE=${SCENE:-.bundle/assets/dabrovic-sponza/sponza.gltf}
SCENARIO=${SCENARIO:-$BUNDLE/share/passgraph/assets/scenarios/cis565.json}
OUT=${OUT:-device-run-out}
SIZE=${SIZE:-1920x1080}
DRY_RUN=${DRY_RUN:-0}
HERE=$(cd "$(dirname "$0")" && pwd)
STEPS=("$@")
[ ${#STEPS[@]} -eq 0 ] && STEPS=(validate bench)
if [ -n "${ICD:-}" ]; then export VK_DRIVER_FILES=$ICD; fi
export PASSGRAPH_CACHE_DIR=${PASSGRAPH_CACHE_DIR:-/tmp/pgcache}
mkdir -p "$OUT/logs"
[ -f "$BUNDLE/COMMIT" ] && echo "commit $(cat "$BUNDLE/COMMIT")"
COMMON=(--size "$SIZE" --scene "$SCENE" --scenario "$SCENARIO" --quiet)

# run LOG CMD...: print or run CMD, its output in OUT/logs/LOG.log, then its exit status
run() {
  local log=$1
  shift
  if [ "$DRY_RUN" = 1 ]; then echo "$*"; return 0; fi
  timeout 420 "$@" > "$OUT/logs/$log.log" 2>&1
  echo "$log rc=$?"
}
# bench NAME BUNDLE PIPELINES ARGS...: `passgraph bench` of PIPELINES (comma-separated names)
bench() {
  local name=$1 bundle=$2 pipes=$3 list="" p
  shift 3
  for p in ${pipes//,/ }; do list="$list,$bundle/share/passgraph/pipelines/$p.json"; done
  run "$name" "$bundle/passgraph" bench "${COMMON[@]}" --pipelines "${list#,}" "$@" --out "$OUT/$name"
  if [ "$DRY_RUN" != 1 ] && [ -f "$OUT/$name/results.csv" ]; then
    python3 "$HERE/tables/bench_rows.py" "$OUT/$name/results.csv"
  fi
}
P=$BUNDLE/share/passgraph/pipelines
TIMING=(--reference-max-lights 0 --warmup 2 --frames 10)

for step in "${STEPS[@]}"; do
  case $step in
  validate)
    for args in "--set resolve=shade" "--set resolve=gbuffer" "--set resolve=shade --set tile_lights=false"; do
      # shellcheck disable=SC2086
      run vis_valid "$BUNDLE/passgraph" render --validation "${COMMON[@]}" --lights 1000 \
        --pipeline "$P/visibility.json" $args --frames 3 --out /tmp/vis_valid.png
    done
    PASSGRAPH_VIS_TEXTURE_LOOP=1 run vis_valid_loop "$BUNDLE/passgraph" render --validation "${COMMON[@]}" \
      --lights 1000 --pipeline "$P/visibility.json" --frames 3 --out /tmp/vis_valid_loop.png
    run vis_vs_naive "$BUNDLE/passgraph" compare "${COMMON[@]}" --lights 1000 --pipeline "$P/visibility.json" \
      --reference "$P/naive.json" --frames 3
    ;;
  bench)
    bench fast "$BUNDLE" visibility,deferred,deferred_oct16,deferred_packed --sweep resolve=shade,gbuffer \
      --lights 1000,5000,100000,1000000 --warmup 2 --frames 10
    ;;
  bench-forward)
    bench fplus "$BUNDLE" forward_plus --sweep prepass=false,true --lights 1000,5000,100000,1000000 \
      --reference-max-lights 0 --warmup 1 --frames 3
    bench naive "$BUNDLE" naive --lights 1000,5000,100000 --reference-max-lights 0 --warmup 0 --frames 1
    ;;
  prepass)
    run prepass_valid "$BUNDLE/passgraph" render --validation "${COMMON[@]}" --lights 1000 \
      --pipeline "$P/forward_plus.json" --set prepass_test=equal --frames 2 --out /tmp/prepass_valid.png
    for n in 1000 5000; do
      for t in less equal; do
        run "prepass_${t}_vs_none_$n" "$BUNDLE/passgraph" compare "${COMMON[@]}" --lights $n \
          --pipeline "$P/forward_plus.json" --reference "$P/forward_plus.json" \
          --pipeline-set prepass_test=$t --reference-set prepass=false --frames 3
      done
    done
    for round in 1 2 3; do
      bench eq_test_$round "$BUNDLE" forward_plus --sweep prepass_test=less,equal --lights 1000,5000,100000 \
        --reference-max-lights 0 --warmup 1 --frames 5
      bench eq_off_$round "$BUNDLE" forward_plus --set prepass=false --lights 1000,5000,100000 \
        --reference-max-lights 0 --warmup 1 --frames 5
    done
    bench eq_1m "$BUNDLE" forward_plus --sweep prepass=false,true --lights 1000000 --reference-max-lights 0 \
      --warmup 0 --frames 3
    ;;
  ab)
    for round in 1 2; do
      bench ab_old_$round "$OLD_BUNDLE" visibility --lights 1000,5000,100000 --reference-max-lights 0 --warmup 3 --frames 20
      bench ab_new_$round "$BUNDLE" visibility --lights 1000,5000,100000 --reference-max-lights 0 --warmup 3 --frames 20
    done
    ;;
  sweep)
    for g in "16 9" "32 18" "64 36"; do
      set -- $g
      bench "grid_$1x$2" "$BUNDLE" visibility,deferred_oct16 --set grid_x=$1 --set grid_y=$2 \
        --sweep tile_size=8,16 --lights 100000,1000000 "${TIMING[@]}"
    done
    ;;
  tiling)
    bench tiling "$BUNDLE" visibility,deferred_oct16 --lights 1000,100000,1000000 --sweep tile_backface=false,true \
      --reference-max-lights 0 --warmup 3 --warmup-ms 500 --frames 10
    ;;
  manylight)
    ERR=(--warmup 2 --warmup-ms 1000 --frames 5 --no-hdr-flip --flicker-frames 4)
    bench manylight "$BUNDLE" forward_plus,deferred,deferred_oct16,deferred_packed,visibility,stochastic,ris,lightcut \
      --lights 1000,100000,1000000 "${ERR[@]}"
    bench manylight_naive "$BUNDLE" naive --lights 1000 "${ERR[@]}"
    ;;
  file-lights)
    mkdir -p "$OUT/file_lights_scene"
    FL_SCENE="$OUT/file_lights_scene/sponza_1m.gltf"
    if [ "$DRY_RUN" = 1 ]; then echo "$BUNDLE/passgraph lights-table ... --out $FL_SCENE"; else
      t0=$(date +%s.%N)
      "$BUNDLE/passgraph" lights-table --scene "$SCENE" --scenario "$SCENARIO" --lights 1000000 --out "$FL_SCENE" \
        > "$OUT/logs/lights_table.log" 2>&1
      echo "lights-table rc=$? $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f s", b - a }')"
    fi
    FL=(--warmup 2 --warmup-ms 1000 --frames 5 --no-hdr-flip --flicker-frames 0 --set stochastic_threshold=3)
    SAVED=("${COMMON[@]}")
    COMMON=(--size "$SIZE" --scene "$FL_SCENE" --scenario "$SCENARIO" --quiet)
    bench file_lights "$BUNDLE" visibility,deferred_oct16,stochastic "${FL[@]}"
    COMMON=("${SAVED[@]}")
    bench generated_lights "$BUNDLE" visibility,deferred_oct16,stochastic --lights 1000000 "${FL[@]}"
    rm -rf "$OUT/file_lights_scene"
    ;;
  shading-cost)
    bench shading_cost "$BUNDLE" forward_plus,deferred,deferred_oct16,deferred_packed,visibility --lights 100000 \
      --sweep shading=lambert,blinn_phong,pbr --warmup 2 --warmup-ms 500 --frames 10 --reference-max-lights 0
    ;;
  spot-cost)
    mkdir -p "$OUT/spot_scene"
    SP_DIR="$OUT/spot_scene"
    if [ "$DRY_RUN" = 1 ]; then echo "$BUNDLE/passgraph lights-table --json ... ; spot_lights.py"; else
      "$BUNDLE/passgraph" lights-table --scene "$SCENE" --scenario "$SCENARIO" --lights 100000 --json \
        --out "$SP_DIR/points.gltf" > "$OUT/logs/spot_table.log" 2>&1
      python3 "$HERE/spot_lights.py" "$SP_DIR/points.gltf" "$SP_DIR/spots.gltf" >> "$OUT/logs/spot_table.log" 2>&1
      echo "spot scenes rc=$?"
    fi
    SAVED=("${COMMON[@]}")
    for kind in points spots; do
      COMMON=(--size "$SIZE" --scene "$SP_DIR/$kind.gltf" --scenario "$SCENARIO" --quiet)
      bench "spot_cost_$kind" "$BUNDLE" forward_plus,deferred,deferred_oct16,deferred_packed,visibility \
        --warmup 2 --warmup-ms 500 --frames 10 --reference-max-lights 0
    done
    COMMON=("${SAVED[@]}")
    rm -rf "$SP_DIR"
    ;;
  environment-cost)
    # the environment light's cost: the one-time filter (a rendered frame's passes) and every
    # pipeline with and without the neutral sky at 1,000 lights, with their error against the
    # reference (whose environment term is its Monte Carlo)
    for pipe in visibility reference; do
      run "env_frame_$pipe" "$BUNDLE/passgraph" render "${COMMON[@]}" --lights 1000 --environment default \
        --pipeline "$P/$pipe.json" --out "/tmp/env_$pipe.png"
    done
    for env in none default; do
      bench "environment_$env" "$BUNDLE" naive,forward_plus,deferred,deferred_oct16,deferred_packed,visibility \
        --lights 1000 --environment "$env" --sweep shading=lambert,pbr --warmup 2 --warmup-ms 500 --frames 10 \
        --no-hdr-flip
    done
    ;;
  tile-size)
    bench tile_size "$BUNDLE" visibility --lights 1000,100000,1000000 --sweep tile_size=8,16 \
      --reference-max-lights 0 --warmup 2 --warmup-ms 500 --frames 10
    ;;
  knobs | knob-stochastic)
    ERR=(--warmup 1 --warmup-ms 1000 --frames 5 --no-hdr-flip --flicker-frames 4 --lights 1000000)
    bench knob_stochastic "$BUNDLE" stochastic --sweep stochastic_threshold=0.005,0.02,0.08,0.3,1,3,10,30,100 \
      --sweep tile_size=8,16 "${ERR[@]}"
    [ "$step" = knob-stochastic ] && continue
    bench knob_ris "$BUNDLE" ris --sweep ris_candidates=4,16,64 "${ERR[@]}"
    bench knob_lightcut "$BUNDLE" lightcut --sweep lightcut_error=0.005,0.05,0.2 "${ERR[@]}"
    for n in 1 4 16 64; do
      bench "accumulate_$n" "$BUNDLE" stochastic,ris --accumulate $n --warmup 1 --warmup-ms 300 --frames 3 --no-hdr-flip \
        --flicker-frames 0 --lights 1000000
    done
    ;;
  evals)
    bench evals "$BUNDLE" visibility,deferred,stochastic,ris,lightcut --lights 100000,1000000 --warmup 2 \
      --warmup-ms 400 --frames 5 --no-hdr-flip --flicker-frames 0
    ;;
  pipeline-stats)
    # the driver's statistics (PASSGRAPH_PIPELINE_STATS) of the light loops, Lambert and pbr, at 100,000 lights
    for p in visibility deferred_oct16 forward_plus; do
      for sh in lambert pbr; do
        PASSGRAPH_PIPELINE_STATS=1 run "stats_${p}_$sh" "$BUNDLE/passgraph" render "${COMMON[@]}" --lights 100000 \
          --pipeline "$P/$p.json" --set shading=$sh --out /tmp/stats.png
        [ "$DRY_RUN" = 1 ] || grep "pipeline-stats" "$OUT/logs/stats_${p}_$sh.log" | cut -c1-400
      done
    done
    ;;
  raster)
    RT=(--warmup 2 --warmup-ms 500 --frames 20)
    bench raster "$BUNDLE" visibility --lights 1000,100000,1000000 --sweep raster=hardware,compute "${RT[@]}" \
      --reference-max-lights 1000
    bench raster_manylight "$BUNDLE" visibility,stochastic,ris,lightcut --lights 1000,100000,1000000 \
      --sweep raster=compute --warmup 2 --warmup-ms 1000 --frames 5 --no-hdr-flip --flicker-frames 4
    SAVED=("${COMMON[@]}")
    COMMON=(--size "$SIZE" --scene default --quiet)
    bench raster_atrium "$BUNDLE" visibility --lights 1000 --sweep raster=hardware,compute "${RT[@]}" --reference-max-lights 0
    COMMON=("${SAVED[@]}")
    ;;
  stress)
    ERR=(--warmup 2 --warmup-ms 300 --frames 5 --no-hdr-flip --flicker-frames 4)
    bench radius6 "$BUNDLE" visibility,stochastic --radius 6 --lights 1000000 "${ERR[@]}"
    SAVED=("${COMMON[@]}")
    COMMON=(--size "$SIZE" --scene "$SCENE" --scenario "$BUNDLE/share/passgraph/assets/scenarios/clump.json" --quiet)
    bench clump "$BUNDLE" visibility,stochastic,ris,lightcut --lights 100000 "${ERR[@]}"
    COMMON=(--size 3840x2160 --scene "$SCENE" --scenario "$SCENARIO" --quiet)
    bench uhd "$BUNDLE" visibility,stochastic,ris,lightcut --lights 100000 "${ERR[@]}"
    COMMON=("${SAVED[@]}")
    ;;
  user-passes)
    UT=(--warmup 2 --warmup-ms 500 --frames 20 --reference-max-lights 0)
    bench user_tonemap "$BUNDLE" examples/tonemap/tonemap --lights 1000 --sweep tonemap_stage=fullscreen,compute "${UT[@]}"
    bench builtin_display "$BUNDLE" forward_plus --lights 1000 --sweep tonemap=ocio,reinhard "${UT[@]}"
    bench user_lighting "$BUNDLE" examples/lighting/lighting --lights 100000 --sweep loop=pixel,tiled "${UT[@]}"
    bench builtin_lighting "$BUNDLE" deferred --lights 100000 --sweep tile_lights=false,true "${UT[@]}"
    bench builtin_lighting_box "$BUNDLE" deferred --lights 100000 --set tile_lights=true --sweep tile_backface=false "${UT[@]}"
    ;;
  animation)
    # the animated character (tests/corpus/gltf/models/walker.gltf, its walk cycle from t = 0.25,
    # the pose advancing with --time-step): geometry_animate's cost in each pipeline with the
    # compute queue on and off, and the image with the pass on either queue (must be identical)
    W=${WALKER:-tests/corpus/gltf/models/walker.gltf}
    for q in on off; do
      run "anim_bench_$q" "$BUNDLE/passgraph" bench --size "$SIZE" --scene "$W" --quiet --time 0.25 \
        --pipelines "$P/naive.json,$P/forward_plus.json,$P/deferred.json,$P/visibility.json" \
        "${TIMING[@]}" --async-compute $q --out "$OUT/anim_$q"
      [ -f "$OUT/anim_$q/results.csv" ] && python3 "$HERE/tables/bench_rows.py" "$OUT/anim_$q/results.csv"
      for p in visibility deferred; do
        run "anim_render_${p}_$q" "$BUNDLE/passgraph" render --size "$SIZE" --scene "$W" --pipeline "$P/$p.json" \
          --time 0.25 --frames 3 --async-compute $q --explain --out "$OUT/anim_${p}_$q.png"
      done
    done
    for p in visibility deferred; do
      if cmp -s "$OUT/anim_${p}_on.png" "$OUT/anim_${p}_off.png"; then echo "animation $p: compute queue on/off identical"
      else echo "animation $p: compute queue on/off DIFFER"; fi
    done
    ;;
  *)
    echo "device-run.sh: unknown step '$step' (validate, bench, bench-forward, prepass, ab, sweep, tiling, tile-size, file-lights, manylight, knobs, knob-stochastic," \
      "evals, stress, animation, user-passes)" >&2
    exit 2
    ;;
  esac
done
[ "$DRY_RUN" = 1 ] || [ -n "${KEEP_SVG:-}" ] || rm -f "$OUT"/*/*.svg
