#!/bin/bash
# forward+ pre-pass, prepass_test less vs equal (and prepass=false), on lavapipe at 640x360:
# the Sponza (cis565, no alpha-mask draws) and the built-in atrium (an alpha-masked grille),
# 1,000 and 5,000 lights, interleaved rounds (ROUNDS, default "1 2 3"; the CSVs here are of
# ROUNDS="1 2 3" then ROUNDS="4 5 6"). Writes r<round>_<scene>_{test,off}/ here.
set -e
cd "$(dirname "$0")/../../../.."
O=docs/results/issue13_lavapipe/prepass_equal
S=../shared/assets/dabrovic-sponza/sponza.gltf; SC=assets/scenarios/cis565.json
B="./build/passgraph bench --size 640x360 --quiet --reference-max-lights 0 --warmup 1 --frames 5 --pipelines pipelines/forward_plus.json --lights 1000,5000"
for round in ${ROUNDS:-1 2 3}; do
  for scene in sponza default; do
    if [ $scene = sponza ]; then A="--scene $S --scenario $SC"; else A="--scene default"; fi
    $B $A --sweep prepass_test=less,equal --out $O/r${round}_${scene}_test > /dev/null
    $B $A --set prepass=false --out $O/r${round}_${scene}_off > /dev/null
  done
done
