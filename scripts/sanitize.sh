#!/usr/bin/env bash
# sanitize.sh - the test suite under AddressSanitizer + UndefinedBehaviorSanitizer (LeakSanitizer
# on): configures -DPG_SANITIZE=ON into $PG_ASAN_BUILD_DIR (default build-asan in the checkout), builds, and
# runs ctest there. tests/CMakeLists.txt sets ASAN_/LSAN_/UBSAN_OPTIONS for every test (leaks and
# UB fail it; driver-internal leaks are suppressed by tests/sanitizer/lsan.supp) and disables the
# memcheck_* tests (valgrind cannot run ASan binaries; ASan covers what they check).
# docs/robustness.md ("Sanitizers") lists what runs and how long it takes.
#
# Usage: scripts/sanitize.sh [extra ctest arguments]     (CI: .ci/run calls it with none)
#   PG_SANITIZE_EXCLUDE   ctest -E regex of tests left out (default: none; "" runs everything)
# Run scripts/setup.sh first (it installs the packages; gcc's libasan/libubsan come with it).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${PG_ASAN_BUILD_DIR:-build-asan} # inside the checkout (ignored): a /tmp cache from another checkout would clash
EXCLUDE=${PG_SANITIZE_EXCLUDE-}
start=$(date +%s)
# without libpassgraph.so (PG_LIBRARY=OFF): its check (install_test) builds a program without ASan,
# which cannot load an ASan-built library
cmake -S . -B "$BUILD" -DPG_SANITIZE=ON -DPG_LIBRARY=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j"$(nproc)"
args=(--test-dir "$BUILD" --output-on-failure)
[ -n "$EXCLUDE" ] && args+=(-E "$EXCLUDE")
status=0
ctest "${args[@]}" "$@" || status=$?
echo "sanitize: ASan+UBSan suite in $BUILD: $(( $(date +%s) - start )) s, ctest exit $status"
exit $status
