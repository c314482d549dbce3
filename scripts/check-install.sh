#!/usr/bin/env bash
# check-install.sh BUILD_DIR - passgraph as an installed library (docs/embedding.md): installs
# BUILD_DIR into a temporary prefix, builds examples/embed against it twice - with CMake's
# find_package(passgraph) and with pkg-config - and runs both with the validation layer on (each
# installed header is first compiled alone as C11 and as C++17). Each run
# must read its data from the prefix (not the source tree), render, read the frame into memory and
# into a VkImage of its own (the two must agree), print per-pass GPU times and the error against
# the reference pipeline. Then: the library exports only pg_* and passgraph_* symbols, and a
# program that finds it through a relative LD_LIBRARY_PATH, or sits next to another share/passgraph,
# still reads the prefix's data. ctest runs
# it as install_test.
set -euo pipefail
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
cmake --install "$build" --prefix "$prefix" >"$tmp/install.log"
for f in include/passgraph/passgraph.h include/passgraph/pass_api.h share/passgraph/shaders/common.glsl \
         share/passgraph/pipelines/forward_plus.json; do
  [ -f "$prefix/$f" ] || { echo "check-install: $f was not installed"; exit 1; }
done
pc=$(find "$prefix" -name passgraph.pc | head -1)
cfg=$(find "$prefix" -name passgraphConfig.cmake | head -1)
lib=$(find "$prefix" -name 'libpassgraph.so' | head -1)
[ -n "$pc" ] && [ -n "$cfg" ] && [ -n "$lib" ] || { echo "check-install: no pkg-config file, CMake package or library"; exit 1; }
libdir=$(dirname "$lib")
# every installed header alone, as C11 and as C++17 (a plug-in or host may be C++), warnings as errors
for h in "$prefix"/include/passgraph/*.h; do
  printf '#include "%s"\nint main(void) { return 0; }\n' "$(basename "$h")" >"$tmp/hdr.c"
  cp "$tmp/hdr.c" "$tmp/hdr.cpp"
  cc -std=c11 -Wall -Wextra -Werror -fsyntax-only -I"$prefix/include/passgraph" "$tmp/hdr.c" 2>"$tmp/hdr.log" &&
    c++ -std=c++17 -Wall -Wextra -Werror -fsyntax-only -I"$prefix/include/passgraph" "$tmp/hdr.cpp" 2>>"$tmp/hdr.log" ||
    { echo "check-install: $(basename "$h") does not compile alone as C and C++:"; cat "$tmp/hdr.log"; exit 1; }
done
# 1. CMake: find_package(passgraph) from the prefix
cmake -S "$root/examples/embed" -B "$tmp/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/cmake.log" \
  || { cat "$tmp/cmake.log"; exit 1; }
cmake --build "$tmp/cmake-build" >"$tmp/build.log" || { cat "$tmp/build.log"; exit 1; }
# 2. pkg-config
export PKG_CONFIG_PATH="$(dirname "$pc")"
# (with the rpath docs/embedding.md gives: the prefix is not where the dynamic loader looks)
cc -std=c11 -Wall -Wextra -Werror "$root/examples/embed/embed.c" -o "$tmp/embed-pkgconfig" \
  $(pkg-config --cflags --libs passgraph) -Wl,-rpath,"$libdir"
status=0
for exe in "$tmp/cmake-build/embed" "$tmp/embed-pkgconfig"; do
  out="$tmp/$(basename "$exe").ppm"
  # no LD_LIBRARY_PATH: each finds the library as a user's build would (the CMake target's rpath, -Wl,-rpath)
  if (cd "$tmp" && env -u PASSGRAPH_DATA_DIR -u LD_LIBRARY_PATH EMBED_VALIDATION=1 "$exe" "" "$out") >"$tmp/run.log" 2>&1 \
     && grep -qF "embed: data folder $prefix/" "$tmp/run.log" && grep -q "VkImage vs memory: 0 of" "$tmp/run.log" \
     && grep -q "against the reference: RMSE" "$tmp/run.log" && grep -q "validation messages: 0" "$tmp/run.log" \
     && [ -s "$out" ]; then
    echo "check-install: $(basename "$exe"): ok"
    cat "$tmp/run.log"
  else
    echo "check-install: $(basename "$exe"): FAILED"
    cat "$tmp/run.log"
    status=1
  fi
done
# the library exports the embedding and pass APIs only (cmake/libpassgraph.map): a host that links
# its own glslang, SPIRV-Tools or tinygltf gets no clashing definitions
others=$(nm -D --defined-only "$lib" | awk '{print $3}' | grep -vE '^(pg_|passgraph_)' || true)
if [ -n "$others" ]; then
  echo "check-install: libpassgraph.so exports $(echo "$others" | wc -l) symbols outside pg_* and passgraph_*:" \
    "$(echo "$others" | head -5 | tr '\n' ' ')"
  status=1
fi
# found through a relative LD_LIBRARY_PATH entry (the dynamic loader's name for it is relative):
# still the prefix's data, not the source tree the build came from
cc -std=c11 -Wall -Wextra -Werror "$root/examples/embed/embed.c" -o "$tmp/embed-norpath" $(pkg-config --cflags --libs passgraph)
if (cd "$prefix" && env -u PASSGRAPH_DATA_DIR LD_LIBRARY_PATH="${libdir#"$prefix"/}" "$tmp/embed-norpath" "" "$tmp/norpath.ppm") \
     >"$tmp/run.log" 2>&1 && grep -qF "embed: data folder $prefix/share/passgraph" "$tmp/run.log"; then
  echo "check-install: a relative LD_LIBRARY_PATH: ok"
else
  echo "check-install: a relative LD_LIBRARY_PATH: FAILED (the data folder must be the prefix's)"
  cat "$tmp/run.log"
  status=1
fi
# a program that sits next to another share/passgraph still gets the library's own data (the one
# next to the program won)
mkdir -p "$tmp/other/bin" "$tmp/other/share/passgraph/shaders"
: >"$tmp/other/share/passgraph/shaders/common.glsl"
cp "$tmp/embed-pkgconfig" "$tmp/other/bin/embed"
if (cd "$tmp" && env -u PASSGRAPH_DATA_DIR -u LD_LIBRARY_PATH "$tmp/other/bin/embed" "" "$tmp/other.ppm") >"$tmp/run.log" 2>&1 \
     && grep -qF "embed: data folder $prefix/share/passgraph" "$tmp/run.log"; then
  echo "check-install: a share/passgraph next to the program: ok"
else
  echo "check-install: a share/passgraph next to the program: FAILED (the data folder must be the library's)"
  cat "$tmp/run.log"
  status=1
fi
# a plug-in built from the installed headers only (docs/plugins.md), loaded by the installed tool
cc -std=c11 -Wall -Wextra -Werror -shared -fPIC "$root/examples/plugins/tint/tint.c" $(pkg-config --cflags passgraph) \
  -o "$tmp/libpg_tint.so"
frag="$prefix/share/passgraph/pipelines/fragments"
sed -e "s#\"\.\./\.\./\.\./pipelines/fragments/#\"$frag/#g" -e 's#^  "include"#  "plugins": ["libpg_tint.so"],\n  "include"#' \
  "$root/examples/plugins/tint/tint.json" >"$tmp/tint.json"
if (cd "$tmp" && env -u PASSGRAPH_DATA_DIR "$prefix/bin/passgraph" render --pipeline "$tmp/tint.json" --size 32x18 \
      --lights 4 --validation --out "$tmp/tint.png") >"$tmp/run.log" 2>&1 && grep -q "tint" "$tmp/run.log"; then
  echo "check-install: a plug-in built against the installed headers: ok"
else
  echo "check-install: a plug-in built against the installed headers: FAILED"
  cat "$tmp/run.log"
  status=1
fi
exit $status
