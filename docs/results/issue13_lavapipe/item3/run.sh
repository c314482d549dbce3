#!/bin/bash
# lavapipe, item 3 changes each on its own: A 49cd181 (before), B 2cb4ecb (+ one-inversesqrt model),
# C HEAD with grid_z=24 (+ branch-free tiled sum), D HEAD (grid_z=32); same binary, interleaved rounds
cd /work/main
S=../shared/assets/dabrovic-sponza/sponza.gltf; SC=assets/scenarios/cis565.json
B="--size 640x360 --scene $S --scenario $SC --quiet --reference-max-lights 0 --warmup 1 --frames 5"
O=/tmp/lvp3; rm -rf $O; mkdir -p $O
for round in 1 2 3 4 5; do
  for side in A B C D; do
    case $side in A) D=.bundle/orig; X="";; B) D=.bundle/m1; X="";; C) D=.; X="--set grid_z=24";; D) D=.; X="";; esac
    PASSGRAPH_DATA_DIR=$D ./build/passgraph bench $B $X --pipelines $D/pipelines/visibility.json,$D/pipelines/deferred_oct16.json,$D/pipelines/forward_plus.json --lights 1000,5000 --out $O/${side}_$round > $O/${side}_$round.log 2>&1
  done
done
echo done > $O/DONE
