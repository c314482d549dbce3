#!/bin/bash
# issue 13 items 1, 3 and 5 on the GPU (device tool: carry .bundle/final, .bundle/assets, the
# validation-layer deb and .gl). STEPS (default "valid bench sweep") picks the parts:
#   valid  the visibility pipeline (both resolve paths, and the path of devices without non-uniform
#          texture indexing) rendered with --validation at 1920x1080, 1000 lights
#   bench  every shipped pipeline (forward_plus with prepass=false,true; visibility with
#          resolve=shade,gbuffer) at 1000, 5000, 100000, 1000000 lights (naive to 100000),
#          1920x1080, Sponza cis565 (the tables of docs/performance.md)
#   batch  item 3: tile_batch 1/2/4 (final bundle) against the bundle before it (.bundle/old, the
#          same loop with the colour loaded for every light), visibility and deferred_oct16 at
#          100000 and 1000000 lights, alternated twice
#   refine item 3: the light_refine pass (refine=false,true; needs the code of
#          docs/results/issue13_gpu/refine/light_refine.patch, which was measured and not merged)
#   ab     the visibility pipeline of the final bundle against .bundle/old at 1000, 5000 and
#          100000 lights, alternated twice (before/after of a change to it)
#   model  item 3: the light model with one inversesqrt per light (final bundle) against the bundle
#          before it (.bundle/old: square root and three divisions), visibility and deferred_oct16
#          at 1000, 5000, 100000 and 1000000 lights, forward_plus at 1000 and 5000, alternated
#          twice; and the new model's image against naive (compare) at 1000 lights
#   var    item 3: variants of the light loop as data folders (.bundle/var/NAME: the final bundle's
#          shaders with experiment defines), visibility and deferred_oct16 at 5000, 100000 and
#          1000000 lights, alternated twice
#   ppt    item 3: tile_pixels=1,2 (final bundle) against the bundle before it (.bundle/old),
#          visibility and deferred_oct16 at 1000, 5000, 100000 and 1000000 lights, alternated twice
#   gridz  item 3: depth slices grid_z=24,32,48,64 (final bundle), visibility and deferred_oct16
#          at 5000, 100000 and 1000000 lights, forward_plus at 5000, alternated twice
#   sel    item 3: the branch-free light term in the tiled loop and grid_z=24,32 (final bundle)
#          against the bundle before it (.bundle/old), visibility and deferred_oct16 at 1000, 5000,
#          100000, 1000000 lights, forward_plus at 1000 and 5000, alternated twice; the tiled loop
#          against the per-pixel one (compare) at 100000 lights
#   orig   item 3 before/after: the final bundle's binary with the shaders and pipelines of commit
#          49cd181 (.bundle/orig, the light loop before issue 13's item 3 work) against the final
#          bundle, visibility and deferred_oct16 at 1000, 5000, 100000, 1000000 lights,
#          forward_plus at 1000 and 5000, alternated twice; the tiled loop against the per-pixel
#          loop (compare) and a --validation render at 100000 lights
#   pos    the visibility pass with its position-only vertex shader (final bundle) against the
#          bundle before it (.bundle/old), 1000 and 5000 lights, alternated twice
#   disp   display_ocio as a compute pass against the full-screen fragment pass
#          (display_stage=compute,fragment), visibility, deferred_oct16, forward_plus, 1000 lights,
#          alternated twice
#   tile   item 3: the tiled light loop against the per-pixel loop (tile_lights=true,false),
#          visibility and deferred_oct16 at 5000, 100000 and 1000000 lights
#   eq     item 2: forward_plus with prepass_test=less,equal and prepass=false at 1000, 5000 and
#          100000 lights, three rounds; prepass=false,true at 1000000 lights; equal and less
#          against prepass=false (compare) at 1000 and 5000 lights; a --validation render of equal
#   sweep  item 3: the light loop's knobs on the visibility and deferred_oct16 pipelines
#          (tile_size 8/16, cluster grid 16x9 / 32x18 / 64x36) at 100000 and 1000000 lights
# SIZE (default 1920x1080) sets the image size; off the device machine (no NVIDIA driver) the
# script runs on whatever Vulkan device is there, without installing anything (a dry run of a
# step, e.g. SIZE=64x36 OUT=/tmp/o STEPS=orig tools/gpu_issue13.sh on lavapipe).
set -u
if [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
fi
export PASSGRAPH_CACHE_DIR=/tmp/pgcache
STEPS=${STEPS:-valid bench sweep}
S=.bundle/assets/dabrovic-sponza/sponza.gltf
F=.bundle/final; SH=$F/share/passgraph; SC=$SH/assets/scenarios/cis565.json
echo "commit $(cat $F/COMMIT)"
mkdir -p $OUT/logs
summary() { # CSV -> one line per row
  python3 - "$1" <<'PY'
import csv,sys
for r in csv.DictReader(open(sys.argv[1])):
    ps={k[5:-10]:r[k] for k in r if k.startswith('pass_') and k.endswith('_ms_median') and r[k]}
    print(r['pipeline'], r['variant'], r['lights'], r['status'], 'gpu', r['gpu_ms_median'], 'rmse', r['rmse_linear'], ps,
          'refs', r.get('light_refs'), 'dropped', r.get('overflow_dropped'))
PY
}
B="--size ${SIZE:-1920x1080} --scene $S --scenario $SC --quiet"
# run_bench NAME SIDE PIPELINES ARGS...: `passgraph bench` of PIPELINES (comma-separated names) into
# $OUT/NAME, with one side's binary and data: old (.bundle/old, its own data), final, or a data
# folder (.bundle/orig, .bundle/var/X) that the final binary reads through PASSGRAPH_DATA_DIR;
# then the exit status and a line per row
run_bench() {
  local name=$1 side=$2 pipes=$3 bin=$F/passgraph data=$SH env=() list="" p
  shift 3
  case $side in
    old) bin=.bundle/old/passgraph; data=.bundle/old/share/passgraph ;;
    final) ;;
    *) data=$side; env=("PASSGRAPH_DATA_DIR=$side") ;;
  esac
  for p in ${pipes//,/ }; do list="$list,$data/pipelines/$p.json"; done
  env "${env[@]}" timeout 420 $bin bench $B --pipelines ${list#,} "$@" --out $OUT/$name > $OUT/logs/$name.log 2>&1
  echo "$name rc=$?"; summary $OUT/$name/results.csv
}
# run_compare NAME ARGS...: `passgraph compare` of the final bundle, its exit status and summary line
run_compare() {
  local name=$1
  shift
  timeout 120 $F/passgraph compare $B "$@" > $OUT/logs/$name.log 2>&1
  echo "$name rc=$?"; tail -1 $OUT/logs/$name.log | cut -c1-300
}
# run_validation NAME ARGS...: a --validation render of the final bundle, its exit status and output
run_validation() {
  local name=$1
  shift
  timeout 120 $F/passgraph render --validation $B "$@" --out /tmp/$name.png > $OUT/logs/$name.log 2>&1
  echo "$name rc=$?"; grep -v "^passgraph: device" $OUT/logs/$name.log | cut -c1-400
}
P=$SH/pipelines
HI="--reference-max-lights 0 --warmup 2 --frames 10"   # timing only, no reference image
case " $STEPS " in *" valid "*)
  for args in "--set resolve=shade" "--set resolve=gbuffer" "--set resolve=shade --set tile_lights=false"; do
    run_validation vis_valid --lights 1000 --pipeline $P/visibility.json $args --frames 3
  done
  PASSGRAPH_VIS_TEXTURE_LOOP=1 run_validation vis_valid_loop --lights 1000 --pipeline $P/visibility.json --frames 3
  run_compare vis_vs_naive --lights 1000 --pipeline $P/visibility.json --reference $P/naive.json --frames 3
  ;; esac
case " $STEPS " in *" bench "*)
  run_bench fast final visibility,deferred,deferred_oct16,deferred_packed --sweep resolve=shade,gbuffer \
    --lights 1000,5000,100000,1000000 --warmup 2 --frames 10
  ;; esac
case " $STEPS " in *" bench2 "*)
  run_bench fplus final forward_plus --sweep prepass=false,true --lights 1000,5000,100000,1000000 \
    --reference-max-lights 0 --warmup 1 --frames 3
  run_bench naive final naive --lights 1000,5000,100000 --reference-max-lights 0 --warmup 0 --frames 1
  ;; esac
case " $STEPS " in *" batch "*)   # needs the tile_batch option, measured and reverted (docs/performance.md)
  for round in 1 2; do
    run_bench old_$round old visibility,deferred_oct16 --lights 100000,1000000 $HI
    run_bench new_$round final visibility,deferred_oct16 --sweep tile_batch=1,2,4 --lights 100000,1000000 $HI
  done
  ;; esac
case " $STEPS " in *" refine "*)  # needs docs/results/issue13_gpu/refine/light_refine.patch (not merged)
  for pl in visibility deferred_oct16; do
    run_validation refine_valid_$pl --lights 100000 --pipeline $P/$pl.json --set refine=true --frames 3
    run_compare refine_$pl --lights 100000 --pipeline $P/$pl.json --reference $P/$pl.json --pipeline-set refine=true --frames 1
  done
  for round in 1 2; do
    run_bench refine_$round final visibility,deferred_oct16 --sweep refine=false,true --lights 1000,5000,100000,1000000 $HI
  done
  ;; esac
case " $STEPS " in *" eq "*)
  run_validation eq_valid --lights 1000 --pipeline $P/forward_plus.json --set prepass_test=equal --frames 2
  for n in 1000 5000; do
    for t in less equal; do
      run_compare eq_${t}_vs_off_$n --lights $n --pipeline $P/forward_plus.json --reference $P/forward_plus.json \
        --pipeline-set prepass_test=$t --reference-set prepass=false --frames 3
    done
  done
  for round in 1 2 3; do
    run_bench eq_test_$round final forward_plus --sweep prepass_test=less,equal --lights 1000,5000,100000 \
      --reference-max-lights 0 --warmup 1 --frames 5
    run_bench eq_off_$round final forward_plus --set prepass=false --lights 1000,5000,100000 \
      --reference-max-lights 0 --warmup 1 --frames 5
  done
  run_bench eq_1m final forward_plus --sweep prepass=false,true --lights 1000000 --reference-max-lights 0 --warmup 0 \
    --frames 3
  ;; esac
case " $STEPS " in *" ab "*)
  for round in 1 2; do
    for side in old final; do
      run_bench ab_${side}_$round $side visibility --lights 1000,5000,100000 --reference-max-lights 0 --warmup 3 --frames 20
    done
  done
  ;; esac
case " $STEPS " in *" model "*)
  run_compare model_vis_vs_naive --lights 1000 --pipeline $P/visibility.json --reference $P/naive.json --frames 1
  for round in 1 2; do
    for side in old final; do
      run_bench model_${side}_$round $side visibility,deferred_oct16 --lights 1000,5000,100000,1000000 $HI
      run_bench modelf_${side}_$round $side forward_plus --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5
    done
  done
  ;; esac
case " $STEPS " in *" var "*)
  for round in 1 2; do
    for v in $(ls .bundle/var); do
      run_bench var_${v}_$round .bundle/var/$v visibility,deferred_oct16 ${VAR_ARGS:-} --lights 5000,100000,1000000 $HI
    done
  done
  ;; esac
case " $STEPS " in *" ppt "*)   # needs docs/results/issue13_gpu/tile_pixels/tile_pixels.patch (not merged)
  for round in 1 2; do
    run_bench ppt_old_$round old visibility,deferred_oct16 --lights 1000,5000,100000,1000000 $HI
    run_bench ppt_new_$round final visibility,deferred_oct16 --sweep tile_pixels=1,2 --lights 1000,5000,100000,1000000 $HI
  done
  for pl in visibility deferred_oct16; do
    run_compare ppt_$pl --lights 100000 --pipeline $P/$pl.json --reference $P/$pl.json \
      --pipeline-set tile_pixels=2 --reference-set tile_pixels=1 --frames 1
    run_validation ppt_valid_$pl --lights 5000 --pipeline $P/$pl.json --frames 2
  done
  ;; esac
case " $STEPS " in *" gridz "*)
  for round in 1 2; do
    run_bench gridz_$round final visibility,deferred_oct16 --sweep grid_z=24,32,48,64 --lights 5000,100000,1000000 $HI
  done
  run_bench gridzf final forward_plus --sweep grid_z=24,32,48,64 --lights 5000 --reference-max-lights 0 --warmup 1 --frames 5
  ;; esac
case " $STEPS " in *" sel "*)
  for pl in visibility deferred_oct16; do
    run_compare sel_tiled_$pl --lights 100000 --pipeline $P/$pl.json --reference $P/$pl.json --reference-set tile_lights=false --frames 1
  done
  for round in 1 2; do
    for side in old final; do
      SW=""; [ $side = final ] && SW="--sweep grid_z=24,32"
      run_bench sel_${side}_$round $side visibility,deferred_oct16 $SW --lights 1000,5000,100000,1000000 $HI
      run_bench self_${side}_$round $side forward_plus $SW --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5
    done
  done
  ;; esac
case " $STEPS " in *" orig "*)
  for pl in visibility deferred_oct16; do
    run_compare orig_tiled_$pl --lights 100000 --pipeline $P/$pl.json --reference $P/$pl.json --reference-set tile_lights=false --frames 1
    run_validation orig_valid_$pl --lights 100000 --pipeline $P/$pl.json --frames 2
  done
  for round in 1 2; do
    for side in .bundle/orig final; do
      n=$(basename $side)
      run_bench orig_${n}_$round $side visibility,deferred_oct16 --lights 1000,5000,100000,1000000 $HI
      run_bench origf_${n}_$round $side forward_plus --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5
    done
  done
  ;; esac
case " $STEPS " in *" pos "*)
  for round in 1 2; do
    for side in old final; do
      run_bench pos_${side}_$round $side visibility --lights 1000,5000 --reference-max-lights 0 --warmup 3 --frames 20
    done
  done
  ;; esac
case " $STEPS " in *" disp "*)
  for round in 1 2; do
    run_bench disp_$round final visibility,deferred_oct16,forward_plus --sweep display_stage=compute,fragment --lights 1000 \
      --reference-max-lights 0 --warmup 3 --frames 20
  done
  ;; esac
case " $STEPS " in *" tile "*)
  run_bench tile final visibility,deferred_oct16 --sweep tile_lights=true,false --lights 5000,100000,1000000 \
    --reference-max-lights 0 --warmup 1 --frames 3
  ;; esac
case " $STEPS " in *" sweep "*)
  for g in "16 9" "32 18" "64 36"; do set -- $g
    run_bench grid_$1x$2 final visibility,deferred_oct16 --set grid_x=$1 --set grid_y=$2 --sweep tile_size=8,16 \
      --lights 100000,1000000 $HI
  done
  ;; esac
rm -f $OUT/*/*.svg
