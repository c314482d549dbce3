#!/bin/bash
# layer_debs.sh SUITE DIR - downloads a Debian suite's Khronos validation layer (e.g. trixie: 1.4.309)
# with its Vulkan loader (libvulkan1: bookworm's 1.3.239 loader asks a device for an instance-level
# function that the newer layer warns about) and the C and C++ runtimes it needs (libc6, libstdc++6,
# libgcc-s1), from deb.debian.org into DIR.
# Newer layers check more than bookworm's 1.3.239; they need a newer libc than bookworm's, so they
# run under that suite's dynamic loader (scripts/with_layer.sh here, scripts/gpu_tests_bundle.sh's
# LAYER_SUITE on the GPU machine), never unpacked into /.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 SUITE DIR" >&2; exit 2; }
suite=$1 dir=$2
mkdir -p "$dir"
index=$(mktemp)
trap 'rm -f "$index"' EXIT
curl -fsS "http://deb.debian.org/debian/dists/$suite/main/binary-amd64/Packages.xz" | xz -d > "$index"
for p in vulkan-validationlayers libvulkan1 libc6 libstdc++6 libgcc-s1; do
    f=$(awk -v P="$p" '$0 == "Package: " P {p = 1} p && /^Filename:/ {print $2; exit}' "$index")
    [ -n "$f" ] || { echo "$0: no package $p in $suite" >&2; exit 1; }
    (cd "$dir" && curl -fsS -O "http://deb.debian.org/debian/$f")
done
