#!/bin/bash
# gpu_tests_bundle.sh BUILD OUT [TEST...] - the GPU tests, to run by hand on another machine (the
# lent GPU machine: docs/testing.md "The GPU tests on a real GPU"). Packs the named test executables
# of BUILD/tests (none named: every test there that loads libvulkan), stripped, with the shared
# libraries they load (from this machine) into one solid xz archive, OUT/tests.tar.xz (the tests
# share most of their code: the tests of 8 MB each pack into a few MB); beside it the Khronos
# validation layer's Debian package (apt-get download), the Sponza when ../shared holds it, the
# plug-ins of BUILD/plugins (put back at that path there: the tests' PG_PLUGIN_DIR), and
# OUT/run.sh. run.sh, run from a copy of this repository's tree on the other machine (its shaders
# and tests/ are read there), installs the layer, points the tests' compiled-in source and shared
# paths at that tree and the carried Sponza, and runs the tests with validation and synchronization
# validation on, $JOBS at a time (default 4), each under a 600 s timeout; each test's output is
# written to $OUT (or /tmp) as TEST.txt, a line per test (exit code, seconds, failed checks,
# validation counts) to stdout. Exit: non-zero when a step here fails.
# LAYER_SUITE=SUITE (e.g. trixie): carry that Debian suite's validation layer instead, with its loader
# and the C and C++ runtimes it needs (scripts/layer_debs.sh); run.sh runs every test through
# scripts/with_layer.sh with those packages (unpacked under /tmp, not /). Newer layers
# check more (1.4.309: layout transitions against load ops at record time); their shader-access
# checks are turned on (VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC, as in ctest).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 BUILD OUT [TEST...]" >&2; exit 2; }
build=$1 out=$2
shift 2
tests=("$@")
if [ ${#tests[@]} -eq 0 ]; then
    for f in "$build"/tests/test_*; do
        # the NEEDED entries (readelf runs nothing; ldd, which runs the loader, missed two tests once
        # while a CI run loaded the machine)
        [ -f "$f" ] && [ -x "$f" ] && readelf -d "$f" 2>/dev/null | grep -q 'NEEDED.*libvulkan' && tests+=("$(basename "$f")")
    done
fi
[ ${#tests[@]} -gt 0 ] || { echo "$0: no test in $build/tests loads libvulkan" >&2; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib"
for t in "${tests[@]}"; do
    [ -x "$build/tests/$t" ] || { echo "$0: $build/tests/$t is not built" >&2; exit 1; }
    strip -o "$stage/$t" "$build/tests/$t"
    ldd "$build/tests/$t" | awk '/=> \// {print $3}' | while read -r lib; do
        case "$(basename "$lib")" in
        libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;;
        *) cp -Lu "$lib" "$stage/lib/" ;;
        esac
    done
done
rm -rf "$out"
mkdir -p "$out"
# the plug-ins some tests load from the build folder (PG_PLUGIN_DIR, compiled in)
if [ -d "$build/plugins" ]; then
    mkdir -p "$stage/plugins"
    for so in "$build"/plugins/*.so; do [ -e "$so" ] && strip -o "$stage/plugins/$(basename "$so")" "$so"; done
fi
tar -C "$stage" -cf - . | xz -T1 -9 --lzma2=preset=9,dict=256MiB > "$out/tests.tar.xz"
suite=${LAYER_SUITE:-}
if [ -n "$suite" ]; then
    bash "$(dirname "$0")/layer_debs.sh" "$suite" "$out/layer"
else
    (cd "$out" && apt-get download -q vulkan-validationlayers >/dev/null) ||
        cp /var/cache/apt/archives/vulkan-validationlayers_*.deb "$out/"
fi
src=$(cd "$(dirname "$0")/.." && pwd)
build_abs=$(cd "$build" && pwd)
shared=$(cd "$src/.." && pwd)/shared
sponza=0
if [ -r "$shared/assets/dabrovic-sponza/sponza.gltf" ]; then
    mkdir -p "$out/assets"
    cp -r "$shared/assets/dabrovic-sponza" "$out/assets/"
    sponza=1
fi
cat > "$out/run.sh" <<EOF
#!/bin/bash
# Run from the root of a copy of the passgraph tree; the bundle is \$(dirname \$0). JOBS: tests at once.
b=\$(cd "\$(dirname "\$0")" && pwd)
t=/tmp/pg_gpu_tests_bin
rm -rf "\$t" && mkdir -p "\$t" && xz -dc "\$b/tests.tar.xz" | tar -C "\$t" -xf - || exit 1
for f in "\$b"/*.deb; do [ -e "\$f" ] && dpkg -x "\$f" /; done
ldconfig
run=""
if [ -d "\$b/layer" ]; then # scripts/with_layer.sh of the tree, with the carried packages
    rm -rf /tmp/pg_layer_$suite
    export PG_LAYER_DEBS="\$b/layer"
    run="\$PWD/scripts/with_layer.sh $suite"
    \$run /bin/true || { echo "\$0: the layer packages do not unpack" >&2; exit 1; } # once, before the tests start
fi
[ -e "$src/tests" ] || { mkdir -p "$(dirname "$src")" && ln -sfn "\$PWD" "$src"; }
if [ -d "\$t/plugins" ] && [ ! -e "$build_abs/plugins" ]; then # PG_PLUGIN_DIR of the tests
    mkdir -p "$build_abs/plugins" && cp "\$t"/plugins/*.so "$build_abs/plugins/"
fi
export LD_LIBRARY_PATH="\$t/lib" PASSGRAPH_DATA_DIR="\$PWD" PASSGRAPH_CACHE_DIR=/tmp/pg_gpu_tests
if [ $sponza = 1 ] && [ ! -e "$shared/assets/dabrovic-sponza" ]; then
    mkdir -p "$shared/assets" && ln -sfn "\$b/assets/dabrovic-sponza" "$shared/assets/dabrovic-sponza"
fi
[ -e "$shared/assets/dabrovic-sponza/sponza.gltf" ] || export PG_TEST_NO_SPONZA=1
export VK_LAYER_ENABLES=VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT
export VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC=true
export o=\${OUT:-/tmp} t run
one() {
    s=\$SECONDS
    timeout 600 \$run "\$t/\$1" > "\$o/\$1.txt" 2>&1
    rc=\$?
    v=\$(awk '/validation messages:/ {s += \$NF; n++} END {print n ? s : "none reported"}' "\$o/\$1.txt")
    echo "\$1 rc=\$rc \$((SECONDS - s)) s validation messages: \$v"
    grep -E "CHECK failed|passed, .* failed|SYNC-HAZARD|VUID" "\$o/\$1.txt" | cut -c1-300 | head -8
}
export -f one
printf '%s\n' ${tests[*]} | xargs -P "\${JOBS:-4}" -I{} bash -c 'one {}'
EOF
chmod +x "$out/run.sh"
du -sh "$out"
