#!/bin/bash
# with_layer.sh SUITE COMMAND [ARG...] - runs COMMAND (a passgraph binary or test) with a Debian
# suite's validation layer instead of the installed one, e.g.
#   scripts/with_layer.sh trixie build/tests/test_gpu_fif
# The layer and its runtimes (scripts/layer_debs.sh; or, offline, the packages it fetched, in the
# folder PG_LAYER_DEBS) are unpacked once into /tmp/pg_layer_SUITE; the
# command runs under that suite's dynamic loader with the layer's manifest on VK_LAYER_PATH, the
# layer's shader-access checks on, and queue-submit synchronization validation on (as in ctest).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 SUITE COMMAND [ARG...]" >&2; exit 2; }
suite=$1
shift
r=/tmp/pg_layer_$suite
lib=$r/usr/lib/x86_64-linux-gnu
# one unpacking at a time (the GPU bundle's run.sh starts several tests at once): the others wait
exec 9>"$r.lock"
flock 9
if [ ! -e "$r/manifest/VkLayer_khronos_validation.json" ]; then
    rm -rf "$r"
    debs=${PG_LAYER_DEBS:-$r/debs}
    [ -n "${PG_LAYER_DEBS:-}" ] || bash "$(dirname "$0")/layer_debs.sh" "$suite" "$debs"
    for f in "$debs"/*.deb; do dpkg -x "$f" "$r"; done
    mkdir -p "$r/manifest"
    sed "s#\"library_path\": *\"[^\"]*\"#\"library_path\": \"$lib/libVkLayer_khronos_validation.so\"#" \
        "$r/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json" > "$r/manifest/VkLayer_khronos_validation.json"
fi
flock -u 9
exec 9>&-
export VK_LAYER_PATH=$r/manifest VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC=true
export VK_LAYER_ENABLES=${VK_LAYER_ENABLES:-VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT}
exec "$lib/ld-linux-x86-64.so.2" --library-path "$lib:${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}/usr/lib/x86_64-linux-gnu" "$@"
