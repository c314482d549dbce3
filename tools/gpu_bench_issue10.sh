#!/usr/bin/env bash
# gpu_bench_issue10.sh PART OUT - the GPU benchmark of docs/results/<gpu>/ (issue 10), run on the
# device machine from the repository root with the bundle in .bundle/after (tools/bundle.sh) and
# the Sponza in .bundle/assets. PART sponza: every shipped pipeline on the Sponza (cis565
# scenario) at 1920x1080, 1,000 .. 1,000,000 lights (naive with one timed frame: it takes ~85 s a
# frame at 1M lights), plus the deferred_oct16 frame at 1M lights and its error heatmap; PART
# default: the same on the built-in atrium, a max_lights sweep on the Sponza, and the 1M-light
# frame (reference and oct16) at a low exposure. Everything goes
# to OUT (bench folders tarred into one file, to fit the device tool's file limits).
set -u
part=$1
out=$2
B=.bundle/after
PG=$B/passgraph
S=.bundle/assets/dabrovic-sponza/sponza.gltf
SC=$B/share/passgraph/assets/scenarios/cis565.json
L=1000,5000,20000,100000,1000000
mkdir -p "$out/w"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$out/w/gpu.txt"
$PG devices | tee -a "$out/w/gpu.txt"
common="--size 1920x1080 --lights $L"
if [ "$part" = sponza ]; then
  timeout -s INT 300 $PG bench --pipelines forward_plus,deferred,deferred_oct16,deferred_packed,reference \
    --scene $S --scenario $SC $common --warmup 1 --frames 5 --out "$out/w/sponza" 2>&1 | grep -v '%' | tail -30
  timeout -s INT 230 $PG bench --pipelines naive --scene $S --scenario $SC $common --warmup 0 --frames 1 \
    --out "$out/w/sponza_naive" 2>&1 | grep -v '%' | tail -8
  $PG render --pipeline $B/share/passgraph/pipelines/deferred_oct16.json --scene $S --scenario $SC --size 1920x1080 \
    --lights 1000000 --frames 3 --out "$out/oct16_1m.png" 2>&1 | tail -2
  timeout 60 $PG compare --pipeline $B/share/passgraph/pipelines/deferred_oct16.json --scene $S --scenario $SC \
    --size 1920x1080 --lights 1000000 --heatmap "$out/oct16_1m_heat.png" 2>&1 | tail -3
else
  timeout -s INT 330 $PG bench --pipelines forward_plus,deferred,deferred_oct16,deferred_packed,reference \
    --scene default $common --warmup 1 --frames 5 --out "$out/w/default" 2>&1 | grep -v '%' | tail -30
  timeout -s INT 100 $PG bench --pipelines naive --scene default --size 1920x1080 --lights 1000,5000,20000 \
    --warmup 0 --frames 1 --out "$out/w/default_naive" 2>&1 | grep -v '%' | tail -6
  timeout -s INT 120 $PG bench --pipelines deferred_oct16 --scene $S --scenario $SC --size 1920x1080 \
    --lights 20000,100000 --sweep max_lights=0,32,128,512,2048 --warmup 1 --frames 5 --out "$out/w/sweep_max_lights" \
    2>&1 | grep -v '%' | tail -12
  # the 1,000,000-light frame at an exposure that shows it (the default saturates), exact and oct16
  for p in reference deferred_oct16; do
    $PG render --pipeline $B/share/passgraph/pipelines/$p.json --scene $S --scenario $SC --size 1920x1080 \
      --lights 1000000 --set exposure=0.002 --out "$out/${p}_1m_exposure.png" 2>&1 | tail -1
  done
fi
tar -C "$out/w" -czf "$out/$part.tar.gz" . && rm -rf "$out/w"
