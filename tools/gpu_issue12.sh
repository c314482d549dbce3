#!/bin/bash
# issue 12 final GPU run (device tool: carry .bundle/{old,final,assets}, the validation-layer deb
# and .gl): (1) the two-queue path with validation on every shipped pipeline, (2) async on/off
# frame time on deferred, (3) bench with the bundle of 3cf27cd (old, before issue 12) vs final.
# tools/bench_before_after.py docs/results/issue12_gpu makes the README table from the CSVs.
set -u
for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
export PASSGRAPH_CACHE_DIR=/tmp/pgcache
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
S=.bundle/assets/dabrovic-sponza/sponza.gltf
F=.bundle/final; SH=$F/share/passgraph; SC=$SH/assets/scenarios/cis565.json
echo "final commit $(cat $F/COMMIT)"
mkdir -p $OUT/logs
echo "== (1) validation, async on, 1920x1080, 100000 lights"
for p in deferred deferred_oct16 deferred_packed forward_plus reference naive; do
  L=100000; [ $p = naive ] && L=5000
  timeout 120 $F/passgraph render --validation --async-compute on --scene $S --scenario $SC --lights $L --size 1920x1080 \
     --pipeline $SH/pipelines/$p.json --frames 3 --out /tmp/v_$p.png > $OUT/logs/v_$p.log 2>&1
  echo "$p lights=$L rc=$? $(grep -ci 'validation error\|SYNC-HAZARD\|VUID' $OUT/logs/v_$p.log) error lines"
  grep "^queues:" $OUT/logs/v_$p.log | cut -c1-400
done
echo "== (2) async on/off, deferred, 60 frames, alternating twice"
for round in 1 2; do for m in on off; do
  $F/passgraph render --async-compute $m --scene $S --scenario $SC --lights 100000 --size 1920x1080 \
     --pipeline $SH/pipelines/deferred.json --frames 60 --out /tmp/t.png > $OUT/logs/t_${m}_$round.log 2>&1
  echo "round $round async=$m rc=$?"; grep "^render:" $OUT/logs/t_${m}_$round.log | cut -c1-300
done; done
echo "== (3) bench before vs after"
for round in 1 2; do
  for side in old final; do
    B=.bundle/$side
    timeout 100 $B/passgraph bench --pipelines naive --lights 1000 --size 1920x1080 --scene $S \
      --scenario $B/share/passgraph/assets/scenarios/cis565.json --frames 10 --warmup 2 \
      --out $OUT/naive_${side}_$round --quiet > $OUT/logs/naive_${side}_$round.log 2>&1
    echo "naive $side round $round: rc=$?"
    timeout 150 $B/passgraph bench --pipelines forward_plus,deferred,deferred_oct16,deferred_packed \
      --lights 1000,100000 --size 1920x1080 --scene $S \
      --scenario $B/share/passgraph/assets/scenarios/cis565.json --frames 20 --warmup 3 \
      --out $OUT/${side}_$round --quiet > $OUT/logs/${side}_$round.log 2>&1
    echo "$side round $round: rc=$?"; tail -1 $OUT/logs/${side}_$round.log | cut -c1-200
  done
done
rm -f $OUT/*/*.svg
