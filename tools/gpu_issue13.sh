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
#   sweep  item 3: the light loop's knobs on the visibility and deferred_oct16 pipelines
#          (tile_size 8/16, cluster grid 16x9 / 32x18 / 64x36) at 100000 and 1000000 lights
set -u
for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
export PASSGRAPH_CACHE_DIR=/tmp/pgcache
STEPS=${STEPS:-valid bench sweep}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
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
B="--size 1920x1080 --scene $S --scenario $SC --quiet"
case " $STEPS " in *" valid "*)
  for args in "--set resolve=shade" "--set resolve=gbuffer" "--set resolve=shade --set tile_lights=false"; do
    timeout 120 $F/passgraph render --validation $B --lights 1000 --pipeline $SH/pipelines/visibility.json $args \
      --frames 3 --out $OUT/vis.png > $OUT/logs/v.log 2>&1
    echo "validation visibility $args rc=$?"; grep -v "^passgraph: device" $OUT/logs/v.log | cut -c1-400
  done
  PASSGRAPH_VIS_TEXTURE_LOOP=1 timeout 120 $F/passgraph render --validation $B --lights 1000 \
    --pipeline $SH/pipelines/visibility.json --frames 3 --out /tmp/vis_loop.png > $OUT/logs/v.log 2>&1
  echo "validation visibility, texture loop path rc=$?"; grep "^render:" $OUT/logs/v.log | cut -c1-400
  timeout 120 $F/passgraph compare $B --lights 1000 --pipeline $SH/pipelines/visibility.json \
    --reference $SH/pipelines/naive.json --frames 3 > $OUT/logs/c.log 2>&1; echo "compare vs naive rc=$?"; tail -1 $OUT/logs/c.log
  ;; esac
case " $STEPS " in *" bench "*)
  P=$SH/pipelines
  timeout 420 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred.json,$P/deferred_oct16.json,$P/deferred_packed.json \
    --sweep resolve=shade,gbuffer --lights 1000,5000,100000,1000000 --warmup 2 --frames 10 --out $OUT/fast > $OUT/logs/fast.log 2>&1
  echo "bench fast rc=$?"; summary $OUT/fast/results.csv
  ;; esac
case " $STEPS " in *" bench2 "*)
  P=$SH/pipelines
  timeout 420 $F/passgraph bench $B --pipelines $P/forward_plus.json --sweep prepass=false,true \
    --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 1 --frames 3 --out $OUT/fplus > $OUT/logs/fplus.log 2>&1
  echo "bench forward_plus rc=$?"; summary $OUT/fplus/results.csv
  timeout 200 $F/passgraph bench $B --pipelines $P/naive.json --lights 1000,5000,100000 --reference-max-lights 0 \
    --warmup 0 --frames 1 --out $OUT/naive > $OUT/logs/naive.log 2>&1
  echo "bench naive rc=$?"; summary $OUT/naive/results.csv
  ;; esac
case " $STEPS " in *" batch "*)
  P=$SH/pipelines; PO=.bundle/old/share/passgraph/pipelines
  for round in 1 2; do
    timeout 200 .bundle/old/passgraph bench $B --pipelines $PO/visibility.json,$PO/deferred_oct16.json --lights 100000,1000000 \
      --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/old_$round > $OUT/logs/old.log 2>&1
    echo "batch round $round old rc=$?"; summary $OUT/old_$round/results.csv
    timeout 200 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --sweep tile_batch=1,2,4 \
      --lights 100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/new_$round > $OUT/logs/new.log 2>&1
    echo "batch round $round new rc=$?"; summary $OUT/new_$round/results.csv
  done
  ;; esac
case " $STEPS " in *" refine "*)
  P=$SH/pipelines
  for pl in visibility deferred_oct16; do
    timeout 120 $F/passgraph render --validation $B --lights 100000 --pipeline $P/$pl.json --set refine=true \
      --frames 3 --out /tmp/r.png > $OUT/logs/r.log 2>&1; echo "validation $pl refine=true rc=$?"; grep "^render:" $OUT/logs/r.log | cut -c1-300
    timeout 120 $F/passgraph compare $B --lights 100000 --pipeline $P/$pl.json --reference $P/$pl.json --pipeline-set refine=true \
      --frames 1 > $OUT/logs/rc.log 2>&1; echo "compare $pl refine=true vs false rc=$?"; tail -1 $OUT/logs/rc.log | cut -c1-200
  done
  for round in 1 2; do
    timeout 300 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --sweep refine=false,true \
      --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/refine_$round > $OUT/logs/refine.log 2>&1
    echo "refine round $round rc=$?"; summary $OUT/refine_$round/results.csv
  done
  ;; esac
case " $STEPS " in *" ab "*)
  for round in 1 2; do
    for side in old final; do
      timeout 120 .bundle/$side/passgraph bench $B --pipelines .bundle/$side/share/passgraph/pipelines/visibility.json \
        --lights 1000,5000,100000 --reference-max-lights 0 --warmup 3 --frames 20 --out $OUT/ab_${side}_$round > $OUT/logs/ab.log 2>&1
      echo "ab round $round $side ($(cat .bundle/$side/COMMIT)) rc=$?"; summary $OUT/ab_${side}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" model "*)
  for side in old final; do
    timeout 120 .bundle/$side/passgraph compare $B --lights 1000 --pipeline .bundle/$side/share/passgraph/pipelines/visibility.json \
      --reference .bundle/$side/share/passgraph/pipelines/naive.json --frames 1 > $OUT/logs/mc.log 2>&1
    echo "model compare visibility vs naive, $side rc=$?"; tail -1 $OUT/logs/mc.log | cut -c1-300
  done
  for round in 1 2; do
    for side in old final; do
      P=.bundle/$side/share/passgraph/pipelines
      timeout 200 .bundle/$side/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json \
        --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/model_${side}_$round > $OUT/logs/model.log 2>&1
      echo "model round $round $side ($(cat .bundle/$side/COMMIT)) rc=$?"; summary $OUT/model_${side}_$round/results.csv
      timeout 100 .bundle/$side/passgraph bench $B --pipelines $P/forward_plus.json \
        --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5 --out $OUT/modelf_${side}_$round > $OUT/logs/modelf.log 2>&1
      echo "model fplus round $round $side rc=$?"; summary $OUT/modelf_${side}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" var "*)
  for round in 1 2; do
    for v in $(ls .bundle/var); do
      D=.bundle/var/$v
      PASSGRAPH_DATA_DIR=$D timeout 200 $F/passgraph bench $B --pipelines $D/pipelines/visibility.json,$D/pipelines/deferred_oct16.json \
        ${VAR_ARGS:-} --lights 5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/var_${v}_$round > $OUT/logs/var.log 2>&1
      echo "var round $round $v rc=$?"; summary $OUT/var_${v}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" ppt "*)
  for round in 1 2; do
    P=.bundle/old/share/passgraph/pipelines
    timeout 200 .bundle/old/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json \
      --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/ppt_old_$round > $OUT/logs/ppt.log 2>&1
    echo "ppt round $round old ($(cat .bundle/old/COMMIT)) rc=$?"; summary $OUT/ppt_old_$round/results.csv
    P=$SH/pipelines
    timeout 300 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --sweep tile_pixels=1,2 \
      --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/ppt_new_$round > $OUT/logs/ppt.log 2>&1
    echo "ppt round $round new ($(cat $F/COMMIT)) rc=$?"; summary $OUT/ppt_new_$round/results.csv
  done
  for pl in visibility deferred_oct16; do
    timeout 120 $F/passgraph compare $B --lights 100000 --pipeline $SH/pipelines/$pl.json --reference $SH/pipelines/$pl.json \
      --pipeline-set tile_pixels=2 --reference-set tile_pixels=1 --frames 1 > $OUT/logs/pc.log 2>&1
    echo "compare $pl tile_pixels 2 vs 1 rc=$?"; tail -1 $OUT/logs/pc.log | cut -c1-200
    timeout 120 $F/passgraph render --validation $B --lights 5000 --pipeline $SH/pipelines/$pl.json --frames 2 --out /tmp/v.png > $OUT/logs/pv.log 2>&1
    echo "validation $pl rc=$?"; grep "^render:" $OUT/logs/pv.log | cut -c1-200
  done
  ;; esac
case " $STEPS " in *" gridz "*)
  P=$SH/pipelines
  for round in 1 2; do
    timeout 300 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --sweep grid_z=24,32,48,64 \
      --lights 5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/gridz_$round > $OUT/logs/gz.log 2>&1
    echo "gridz round $round rc=$?"; summary $OUT/gridz_$round/results.csv
  done
  timeout 200 $F/passgraph bench $B --pipelines $P/forward_plus.json --sweep grid_z=24,32,48,64 \
    --lights 5000 --reference-max-lights 0 --warmup 1 --frames 5 --out $OUT/gridzf > $OUT/logs/gzf.log 2>&1
  echo "gridz forward_plus rc=$?"; summary $OUT/gridzf/results.csv
  ;; esac
case " $STEPS " in *" sel "*)
  for pl in visibility deferred_oct16; do
    timeout 120 $F/passgraph compare $B --lights 100000 --pipeline $SH/pipelines/$pl.json --reference $SH/pipelines/$pl.json \
      --reference-set tile_lights=false --frames 1 > $OUT/logs/sc.log 2>&1
    echo "compare $pl tiled vs per-pixel rc=$?"; tail -1 $OUT/logs/sc.log | cut -c1-200
  done
  for round in 1 2; do
    for side in old final; do
      P=.bundle/$side/share/passgraph/pipelines; SW=""; [ $side = final ] && SW="--sweep grid_z=24,32"
      timeout 250 .bundle/$side/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json $SW \
        --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/sel_${side}_$round > $OUT/logs/sel.log 2>&1
      echo "sel round $round $side ($(cat .bundle/$side/COMMIT)) rc=$?"; summary $OUT/sel_${side}_$round/results.csv
      timeout 150 .bundle/$side/passgraph bench $B --pipelines $P/forward_plus.json $SW \
        --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5 --out $OUT/self_${side}_$round > $OUT/logs/self.log 2>&1
      echo "sel fplus round $round $side rc=$?"; summary $OUT/self_${side}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" orig "*)
  for pl in visibility deferred_oct16; do
    timeout 120 $F/passgraph compare $B --lights 100000 --pipeline $SH/pipelines/$pl.json --reference $SH/pipelines/$pl.json \
      --reference-set tile_lights=false --frames 1 > $OUT/logs/oc.log 2>&1
    echo "compare $pl tiled vs per-pixel rc=$?"; tail -1 $OUT/logs/oc.log | cut -c1-200
    timeout 120 $F/passgraph render --validation $B --lights 100000 --pipeline $SH/pipelines/$pl.json --frames 2 --out /tmp/v.png > $OUT/logs/ov.log 2>&1
    echo "validation $pl rc=$?"; grep -v "^passgraph: device" $OUT/logs/ov.log | cut -c1-300
  done
  for round in 1 2; do
    for side in orig final; do
      if [ $side = orig ]; then D=.bundle/orig; else D=$SH; fi
      PASSGRAPH_DATA_DIR=$D timeout 250 $F/passgraph bench $B --pipelines $D/pipelines/visibility.json,$D/pipelines/deferred_oct16.json \
        --lights 1000,5000,100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 --out $OUT/orig_${side}_$round > $OUT/logs/orig.log 2>&1
      echo "orig round $round $side rc=$?"; summary $OUT/orig_${side}_$round/results.csv
      PASSGRAPH_DATA_DIR=$D timeout 150 $F/passgraph bench $B --pipelines $D/pipelines/forward_plus.json \
        --lights 1000,5000 --reference-max-lights 0 --warmup 1 --frames 5 --out $OUT/origf_${side}_$round > $OUT/logs/origf.log 2>&1
      echo "orig fplus round $round $side rc=$?"; summary $OUT/origf_${side}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" pos "*)
  for round in 1 2; do
    for side in old final; do
      timeout 120 .bundle/$side/passgraph bench $B --pipelines .bundle/$side/share/passgraph/pipelines/visibility.json \
        --lights 1000,5000 --reference-max-lights 0 --warmup 3 --frames 20 --out $OUT/pos_${side}_$round > $OUT/logs/pos.log 2>&1
      echo "pos round $round $side ($(cat .bundle/$side/COMMIT)) rc=$?"; summary $OUT/pos_${side}_$round/results.csv
    done
  done
  ;; esac
case " $STEPS " in *" disp "*)
  P=$SH/pipelines
  for round in 1 2; do
    timeout 200 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json,$P/forward_plus.json \
      --sweep display_stage=compute,fragment --lights 1000 --reference-max-lights 0 --warmup 3 --frames 20 \
      --out $OUT/disp_$round > $OUT/logs/disp.log 2>&1
    echo "disp round $round rc=$?"; summary $OUT/disp_$round/results.csv
  done
  ;; esac
case " $STEPS " in *" tile "*)
  P=$SH/pipelines
  timeout 400 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --sweep tile_lights=true,false \
    --lights 5000,100000,1000000 --reference-max-lights 0 --warmup 1 --frames 3 --out $OUT/tile > $OUT/logs/tile.log 2>&1
  echo "tile rc=$?"; summary $OUT/tile/results.csv
  ;; esac
case " $STEPS " in *" sweep "*)
  P=$SH/pipelines
  for g in "16 9" "32 18" "64 36"; do set -- $g
    timeout 300 $F/passgraph bench $B --pipelines $P/visibility.json,$P/deferred_oct16.json --set grid_x=$1 --set grid_y=$2 \
      --sweep tile_size=8,16 --lights 100000,1000000 --reference-max-lights 0 --warmup 2 --frames 10 \
      --out $OUT/grid_$1x$2 > $OUT/logs/grid_$1.log 2>&1
    echo "sweep grid $1x$2 rc=$?"; summary $OUT/grid_$1x$2/results.csv
  done
  ;; esac
rm -f $OUT/*/*.svg
