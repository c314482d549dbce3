#!/bin/bash
# cross_device_renders.sh PASSGRAPH OUT - the glossy pbr scenes on which the raster pipelines and the
# visibility pipeline part between lavapipe and NVIDIA GPUs (docs/accuracy.md "One image, two
# devices"): pbr/spheres.gltf and models/desk_lamp, mug, snowman of tests/corpus/gltf, each with
# naive.json, visibility.json, reference.json and reference.json with surface=ray (as
# SCENE_reference_ray), 160x90, the file's lights plus 48 generated, rgba32f HDR, written to
# OUT/SCENE_PIPELINE.exr (and the command's line to .log), and naive's and visibility's shading
# normals (the debug view `normal`) to OUT/SCENE_PIPELINE_normal.exr. Run it from the repository
# root on each device with the same commit; scripts/tables/cross_device_table.py compares two such
# folders. PASSGRAPH: the binary (build/passgraph, or a bundle's wrapper). Exit: non-zero
# when a render fails.
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 PASSGRAPH OUT" >&2; exit 2; }
pg=$1 out=$2
mkdir -p "$out"
rc=0
for s in pbr/spheres.gltf models/desk_lamp.gltf models/mug.gltf models/snowman.gltf; do
    b=$(basename "$s" .gltf)
    for p in naive visibility reference reference_ray; do
        set_ray=()
        [ "$p" = reference_ray ] && set_ray=(--set surface=ray)
        if ! "$pg" render --quiet --scene "tests/corpus/gltf/$s" --pipeline "pipelines/${p%_ray}.json" --size 160x90 \
            --set hdr_format=rgba32f --lights 48 "${set_ray[@]}" --out "$out/${b}_$p.exr" > "$out/${b}_$p.log" 2>&1; then
            echo "$0: $s with $p failed: $(tail -1 "$out/${b}_$p.log")" >&2
            rc=1
        fi
        rm -f "$out/${b}_$p.png"
    done
    for p in naive visibility; do # the shading normal each lights with (debug view, n/2 + 1/2)
        if ! "$pg" render --quiet --scene "tests/corpus/gltf/$s" --pipeline "pipelines/$p.json" --size 160x90 \
            --set hdr_format=rgba32f --lights 48 --debug-view normal --out "$out/${b}_${p}_normal.exr" \
            > "$out/${b}_${p}_normal.log" 2>&1; then
            echo "$0: $s with $p (normal) failed: $(tail -1 "$out/${b}_${p}_normal.log")" >&2
            rc=1
        fi
        rm -f "$out/${b}_${p}_normal.png"
    done
done
exit $rc
