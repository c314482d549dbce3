#!/bin/bash
# gpu_tests_bundle.sh BUILD OUT TEST... - GPU tests to run by hand on another machine (the lent GPU
# machine: docs/testing.md "The GPU tests on a real GPU"). Copies the named test executables of
# BUILD/tests, stripped, into OUT with the shared libraries they load (from this machine), the
# Khronos validation layer's Debian package (apt-get download) and OUT/run.sh, which, run from a
# copy of this repository's tree on the other machine (its shaders and tests/ are read there),
# installs the layer, points the tests' compiled-in source path at that tree and runs each test
# with validation and synchronization validation on, the Sponza left out; each test's output is
# written to $OUT (or /tmp) as TEST.txt. Exit: non-zero when a step here fails.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 BUILD OUT TEST..." >&2; exit 2; }
build=$1 out=$2
shift 2
rm -rf "$out"
mkdir -p "$out/lib"
for t in "$@"; do
    [ -x "$build/tests/$t" ] || { echo "$0: $build/tests/$t is not built" >&2; exit 1; }
    strip -o "$out/$t" "$build/tests/$t"
    ldd "$build/tests/$t" | awk '/=> \// {print $3}' | while read -r lib; do
        case "$(basename "$lib")" in
        libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;;
        *) cp -Lu "$lib" "$out/lib/" ;;
        esac
    done
done
(cd "$out" && apt-get download -q vulkan-validationlayers >/dev/null) ||
    cp /var/cache/apt/archives/vulkan-validationlayers_*.deb "$out/"
src=$(cd "$(dirname "$0")/.." && pwd)
cat > "$out/run.sh" <<EOF
#!/bin/bash
# Run from the root of a copy of the passgraph tree; the bundle is \$(dirname \$0).
b=\$(cd "\$(dirname "\$0")" && pwd)
for f in "\$b"/*.deb; do dpkg -x "\$f" /; done
ldconfig
[ -e "$src/tests" ] || { mkdir -p "$(dirname "$src")" && ln -sfn "\$PWD" "$src"; }
export LD_LIBRARY_PATH="\$b/lib" PASSGRAPH_DATA_DIR="\$PWD" PASSGRAPH_CACHE_DIR=/tmp/pg_gpu_tests PG_TEST_NO_SPONZA=1
export VK_LAYER_ENABLES=VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT
o=\${OUT:-/tmp}
for t in $*; do
    s=\$SECONDS
    timeout 600 "\$b/\$t" > "\$o/\$t.txt" 2>&1
    echo "\$t rc=\$? \$((SECONDS - s)) s"
    grep -E "CHECK failed|passed, .* failed|validation messages" "\$o/\$t.txt" | cut -c1-300 | head -20
done
EOF
chmod +x "$out/run.sh"
du -sh "$out"
