#!/bin/bash
# issue 13 items 2 and 4 on the GPU (device tool: carry .bundle/final, .bundle/assets, the
# validation-layer deb and .gl): forward+ with and without the depth pre-pass (validation, then
# bench, two rounds), and two bench shards on one GPU merged vs the unsharded run
set -u
for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
export PASSGRAPH_CACHE_DIR=/tmp/pgcache
S=.bundle/assets/dabrovic-sponza/sponza.gltf
F=.bundle/final; SH=$F/share/passgraph; SC=$SH/assets/scenarios/cis565.json
echo "commit $(cat $F/COMMIT)"
mkdir -p $OUT/logs
for pp in true false; do
  $F/passgraph render --validation --scene $S --scenario $SC --lights 5000 --size 1920x1080 \
     --pipeline $SH/pipelines/forward_plus.json --set prepass=$pp --frames 3 --out /tmp/p.png > $OUT/logs/v_$pp.log 2>&1
  echo "validation prepass=$pp rc=$?"; grep "^render:" $OUT/logs/v_$pp.log | cut -c1-300
done
for round in 1 2; do
  $F/passgraph bench --pipelines forward_plus --sweep prepass=false,true --lights 1000,5000,100000 --size 1920x1080 \
    --scene $S --scenario $SC --frames 20 --warmup 3 --out $OUT/prepass_$round --quiet > $OUT/logs/b_$round.log 2>&1
  echo "bench round $round rc=$?"
  python3 - "$OUT/prepass_$round/results.csv" <<'PY'
import csv,sys
for r in csv.DictReader(open(sys.argv[1])):
    ps={k[5:-10]:r[k] for k in r if k.startswith('pass_') and k.endswith('_ms_median') and r[k]}
    print(r['pipeline'], r['variant'], r['lights'], r['status'], 'gpu', r['gpu_ms_median'], 'rmse', r['rmse_linear'], ps)
PY
done
rm -f $OUT/*/*.svg
echo "== shards on the GPU: 2 shards one after the other, merged, vs unsharded"
A="--pipelines forward_plus,deferred_oct16 --lights 1000,5000 --size 1920x1080 --scene $S --scenario $SC --frames 10 --warmup 2 --quiet"
$F/passgraph bench $A --out $OUT/sh_full > $OUT/logs/sh_full.log 2>&1; echo "full rc=$?"
$F/passgraph bench $A --shard 1/2 --out $OUT/sh_1 > $OUT/logs/sh_1.log 2>&1; echo "shard 1 rc=$?"
$F/passgraph bench $A --shard 2/2 --out $OUT/sh_2 > $OUT/logs/sh_2.log 2>&1; echo "shard 2 rc=$?"
$F/passgraph bench-merge --out $OUT/sh_merged $OUT/sh_1 $OUT/sh_2 > $OUT/logs/sh_merge.log 2>&1; echo "merge rc=$?"; tail -2 $OUT/logs/sh_merge.log
wc -l $OUT/sh_full/results.csv $OUT/sh_merged/results.csv
rm -f $OUT/*/*.svg
