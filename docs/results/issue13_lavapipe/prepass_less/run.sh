#!/bin/bash
cd /work/main
S=../shared/assets/dabrovic-sponza/sponza.gltf; SC=assets/scenarios/cis565.json
O=/tmp/lvp4; rm -rf $O; mkdir -p $O
for round in 1 2 3; do
  ./build/passgraph bench --size 640x360 --scene $S --scenario $SC --quiet --reference-max-lights 0 --warmup 1 --frames 5 --pipelines pipelines/forward_plus.json --sweep prepass=false,true --lights 1000,5000 --out $O/r$round > $O/r$round.log 2>&1
done
echo done > $O/DONE
