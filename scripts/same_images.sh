#!/usr/bin/env bash
# same_images.sh OLD_DIR NEW_DIR [OUT_DIR] - renders every shipped pipeline (pipelines/*.json) on
# the built-in atrium and on the Sponza (with assets/scenarios/cis565.json) with two built
# checkouts (each run from its own folder: DIR/build/passgraph with its own pipelines and shaders)
# and checks that the PNGs are byte-identical. Prints one line per image and "N passed, M failed".
# For a change that must not change pixels (a refactoring): run it with the checkout before and
# after. PG_SPONZA: the Sponza glTF (default ../shared/assets/dabrovic-sponza/sponza.gltf beside
# NEW_DIR); PG_SI_SIZE (default 320x180), PG_SI_LIGHTS (default 1000).
set -uo pipefail
OLD=$(cd "$1" && pwd)
NEW=$(cd "$2" && pwd)
OUT=${3:-$(mktemp -d)}
mkdir -p "$OUT/old" "$OUT/new"
SPONZA=${PG_SPONZA:-$NEW/../shared/assets/dabrovic-sponza/sponza.gltf}
SIZE=${PG_SI_SIZE:-320x180}
LIGHTS=${PG_SI_LIGHTS:-1000}
pass=0 fail=0
for p in "$NEW"/pipelines/*.json; do
  name=$(basename "$p" .json)
  for scene in atrium sponza; do
    if [ $scene = atrium ]; then args=(--scene default)
    elif [ -f "$SPONZA" ]; then args=(--scene "$SPONZA" --scenario assets/scenarios/cis565.json)
    else echo "skip $name/$scene: no Sponza at $SPONZA"; continue; fi
    for side in old new; do
      dir=$OLD; [ $side = new ] && dir=$NEW
      (cd "$dir" && build/passgraph render --pipeline "pipelines/$name.json" "${args[@]}" --size "$SIZE" \
         --lights "$LIGHTS" --out "$OUT/$side/$name-$scene.png" >"$OUT/$side/$name-$scene.log" 2>&1) ||
        { echo "FAIL $name/$scene: $side render failed: $(tail -1 "$OUT/$side/$name-$scene.log")"; }
    done
    if cmp -s "$OUT/old/$name-$scene.png" "$OUT/new/$name-$scene.png"; then
      echo "same $name/$scene"; pass=$((pass + 1))
    else
      echo "DIFFERENT $name/$scene ($OUT/old/$name-$scene.png, $OUT/new/$name-$scene.png)"; fail=$((fail + 1))
    fi
  done
done
echo "same_images: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
