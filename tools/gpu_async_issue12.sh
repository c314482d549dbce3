#!/bin/bash
# issue 12 item 6 (async compute) on the GPU machine (device tool; bundle + Sponza copied into
# .bundle/async12, see README "Async compute"): validation of the real two-queue path, then async
# on vs off at 1920x1080, 100,000 lights, Sponza + cis565 (frame GPU time medians, per-pass times
# per queue, overlap of light assignment with the G-buffer pass); all logs in $OUT/async_logs.tgz
set -u
D=${D:-.bundle/async12}
if [ -z "${LOCAL:-}" ]; then
  for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  export VK_LAYER_PATH=/usr/share/vulkan/explicit_layer.d
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
fi
export PASSGRAPH_CACHE_DIR=/tmp/pgcache
PG=$D/after/passgraph
SH=$D/after/share/passgraph
S=$D/sponza/sponza.gltf
SC=$SH/assets/scenarios/cis565.json
SIZE=${SIZE:-1920x1080}; LIGHTS=${LIGHTS:-100000}; FRAMES=${FRAMES:-60}
RES=$OUT; OUT=/tmp/async_logs; mkdir -p $OUT
$PG devices 2>&1 | head -5
echo "== validation (Khronos layer + sync validation), async on, $SIZE, $LIGHTS lights"
for p in deferred deferred_oct16 deferred_packed forward_plus naive reference; do
  $PG render --validation --async-compute on --scene $S --scenario $SC --lights $LIGHTS --size $SIZE \
     --pipeline $SH/pipelines/$p.json --frames 3 --out $OUT/v_${p}_on.png > $OUT/v_$p.log 2>&1
  echo "$p rc=$? $(grep -c 'validation' $OUT/v_$p.log) validation lines; $(grep -m1 'compute queue' $OUT/v_$p.log)"
  grep -m3 "validation error\|validation warning" $OUT/v_$p.log | cut -c1-400
  tail -2 $OUT/v_$p.log | cut -c1-600
done
$PG render --validation --async-compute emulate --scene $S --scenario $SC --lights $LIGHTS --size $SIZE \
   --pipeline $SH/pipelines/deferred.json --frames 3 --out $OUT/v_deferred_emul.png > $OUT/v_emul.log 2>&1
echo "deferred emulate rc=$?"; tail -1 $OUT/v_emul.log | cut -c1-300
echo "== images async on vs off (no validation)"
for p in deferred forward_plus; do
  $PG render --async-compute off --scene $S --scenario $SC --lights $LIGHTS --size $SIZE \
     --pipeline $SH/pipelines/$p.json --frames 3 --out $OUT/i_${p}_off.png > /dev/null 2>&1
  cmp -s $OUT/v_${p}_on.png $OUT/i_${p}_off.png && echo "$p: on/off PNG identical" || echo "$p: on/off PNG differ"
done
echo "== timing: $FRAMES frames each, alternating on/off twice"
for round in 1 2; do
  for p in deferred forward_plus; do
    for m in on off; do
      $PG render --async-compute $m --scene $S --scenario $SC --lights $LIGHTS --size $SIZE \
         --pipeline $SH/pipelines/$p.json --frames $FRAMES --out /tmp/t.png > $OUT/t_${p}_${m}_$round.log 2>&1
      echo "round $round $p async=$m rc=$?"; grep "^render:\|^queues:" $OUT/t_${p}_${m}_$round.log | cut -c1-900
    done
  done
done
echo "== 2 frames in flight, two queues, validation: bench"
$PG bench --validation --async-compute on --pipelines deferred,forward_plus --lights $LIGHTS --size $SIZE --scene $S \
   --scenario $SC --frames 10 --warmup 2 --reference-max-lights 1 --out $OUT/bench_val --quiet > $OUT/bench_val.log 2>&1
echo "bench validation rc=$? $(grep -c 'validation error' $OUT/bench_val.log) validation errors"; tail -3 $OUT/bench_val.log | cut -c1-400
rm -f $OUT/*.png
tar czf $RES/async_logs.tgz -C /tmp async_logs
