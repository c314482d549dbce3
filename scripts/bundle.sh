#!/usr/bin/env bash
# bundle.sh [BUILD_DIR] [OUT_DIR] - a self-contained passgraph for a Linux machine that has only
# glibc and a Vulkan driver (e.g. the GPU benchmark machine): `cmake --install` into OUT_DIR
# (bin/passgraph, share/passgraph/{shaders,pipelines,assets}), every non-glibc shared library the
# binary loads into OUT_DIR/lib (the Vulkan loader included), and OUT_DIR/passgraph, a wrapper that
# sets LD_LIBRARY_PATH. Headless use needs no window system (the X11 libraries GLFW links are
# bundled but only used by `view`).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=${2:-bundle}
rm -rf "$OUT"
cmake --install "$BUILD" --prefix "$OUT" >/dev/null
mkdir -p "$OUT/lib"
ldd "$OUT/bin/passgraph" | awk '/=> \// {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;; # glibc: the target's own
    *) cp -L "$lib" "$OUT/lib/" ;;
  esac
done
cat >"$OUT/passgraph" <<'WRAP'
#!/bin/sh
here=$(cd "$(dirname "$0")" && pwd)
LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/bin/passgraph" "$@"
WRAP
chmod +x "$OUT/passgraph"
echo "bundle: $OUT ($(du -sh "$OUT" | cut -f1)); run $OUT/passgraph"
