#!/usr/bin/env bash
# newer_layer_test.sh [--view PASSGRAPH] TEST... - the synchronization tests again under a newer Khronos validation
# layer than the installed one: Debian trixie's 1.4.309 (scripts/with_layer.sh: its loader and
# layer under trixie's dynamic loader, its shader-access checks on). It checks what bookworm's
# 1.3.239 does not: layout transitions against load ops when commands are recorded, and
# submissions across queues and frames with fewer false positives (docs/testing.md "The GPU tests
# on a real GPU"). Each TEST (a test executable) must pass there too; with --view, also
# tests/cli/view_test.sh on PASSGRAPH: the viewer, which ctest runs without the queue-submit checks
# because 1.3.239 crashes in them once a swapchain exists, gets them here. Skipped (exit 77) when
# deb.debian.org cannot be reached, and in a sanitizer build (scripts/sanitize.sh: the checks here
# are the layer's; that build checks memory in the regular tests, and its leak lists know only the
# installed layer).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
view=""
if [ "${1:-}" = --view ]; then
    view=$2
    shift 2
fi
[ $# -ge 1 ] || { echo "usage: $0 [--view PASSGRAPH] TEST..." >&2; exit 2; }
if [ ! -e /tmp/pg_layer_trixie/manifest/VkLayer_khronos_validation.json ] &&
    ! curl -fsS -o /dev/null --max-time 30 http://deb.debian.org/debian/dists/trixie/Release; then
    echo "newer_layer_test: skipped: deb.debian.org cannot be reached (the layer is downloaded)"
    exit 77
fi
# readelf reads the NEEDED entries without running anything (ldd once missed it in a clean-clone CI run)
if readelf -d "$1" 2>/dev/null | grep -q 'NEEDED.*libasan' || ldd "$1" 2>/dev/null | grep -q libasan; then
    echo "newer_layer_test: skipped: a sanitizer build"
    exit 77
fi
fail=0
for t in "$@"; do
    out=$("$root/scripts/with_layer.sh" trixie "$t" 2>&1)
    rc=$?
    echo "$out" | tail -1
    if [ $rc -ne 0 ]; then
        echo "FAIL: $(basename "$t") under layer 1.4.309: exit $rc"
        echo "$out" | grep -E "CHECK failed|validation (error|warning)" | cut -c1-400 | head -10
        fail=1
    fi
done
if [ -n "$view" ]; then
    w=$(mktemp -d)
    printf '#!/bin/sh\nexec "%s" trixie "%s" "$@"\n' "$root/scripts/with_layer.sh" "$view" > "$w/passgraph"
    chmod +x "$w/passgraph"
    out=$(bash "$root/tests/cli/view_test.sh" "$w/passgraph" 2>&1)
    rc=$?
    rm -rf "$w"
    echo "$out" | tail -1
    if [ $rc -ne 0 ]; then
        echo "FAIL: view_test under layer 1.4.309: exit $rc"
        echo "$out" | grep -E "FAIL|validation (error|warning)" | cut -c1-400 | head -10
        fail=1
    fi
fi
exit $fail
