#!/bin/bash
# fragment shader invocations per graphics pass (docs/results/issue13_gpu/fragment_stats/fragment_stats.patch)
for f in .gl/*.deb .bundle/vulkan-validationlayers_*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export PASSGRAPH_CACHE_DIR=/tmp/pgcache PASSGRAPH_DATA_DIR=.bundle/final/share/passgraph
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
PG="env LD_LIBRARY_PATH=.bundle/final/lib .bundle/fragstats/passgraph"  # built from fragment_stats.patch
P=.bundle/final/share/passgraph/pipelines
B="--size 1920x1080 --scene .bundle/assets/dabrovic-sponza/sponza.gltf --scenario .bundle/final/share/passgraph/assets/scenarios/cis565.json --lights 1000 --frames 3"
cmp() { echo "== $*"; $PG compare $B "$@" > /tmp/cmp.log 2>&1; grep -n "fragment_invocations" /tmp/cmp.log | cut -c1-600; tail -1 /tmp/cmp.log | tr ' ' '\n' | grep -E "gpu_ms|rmse_linear"; }
cmp --pipeline $P/forward_plus.json --reference $P/forward_plus.json --reference-set prepass=false
cmp --pipeline $P/forward_plus.json --reference $P/forward_plus.json --pipeline-set prepass_test=equal --reference-set prepass=false
cmp --pipeline $P/visibility.json --reference $P/deferred_oct16.json
cmp --pipeline $P/naive.json --reference $P/deferred.json
