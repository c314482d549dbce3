#!/usr/bin/env bash
# lightcut_bound_test.sh PASSGRAPH PYTHON - scripts/lightcut_bound.py, the check of the lightcut's
# per-pixel bound on rendered images (accuracy.md): on lavapipe, the exact visibility image and the
# lightcut's at eps 0.02 of the atrium (96x54, rgba32f; lightcut_bucket 1, the plain walk: with the
# default's exact buckets this small scene is nearly exact) are within the bound (exit 0), the same
# lightcut is not within eps 0.0001 (exit 1: the check can fail; a misread file would fail the first
# check), an image against itself uses 0 of the bound, its OpenEXR reader reads passgraph's FLOAT and
# HALF files (shape, finite, lit), and a file that is not OpenEXR exits 2.
set -u
PG=$1 PY=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
. "$root/tests/cli/check_lib.sh"
C=(--scene default --size 96x54 --lights 64 --set hdr_format=rgba32f)
"$PG" render "${C[@]}" --pipeline "$root/pipelines/visibility.json" --out "$tmp/v.png" --hdr-out "$tmp/v.exr" \
  >/dev/null 2>"$tmp/err" && ok || { bad "visibility render"; cat "$tmp/err"; }
"$PG" render "${C[@]}" --pipeline "$root/pipelines/lightcut.json" --set lightcut_error=0.02 --set lightcut_bucket=1 --out "$tmp/l.png" \
  --hdr-out "$tmp/l.exr" >/dev/null 2>"$tmp/err" && ok || { bad "lightcut render"; cat "$tmp/err"; }
"$PY" "$root/scripts/lightcut_bound.py" "$tmp/v.exr" "$tmp/l.exr" 0.02 >"$tmp/out" 2>&1
rc=$?
[ $rc = 0 ] && grep -q " 0 of 15552 channels over the bound" "$tmp/out" && ok || { bad "eps 0.02: exit $rc"; cat "$tmp/out"; }
"$PY" "$root/scripts/lightcut_bound.py" "$tmp/v.exr" "$tmp/l.exr" 0.0001 >"$tmp/out" 2>&1
rc=$?
[ $rc = 1 ] && ok || { bad "eps 0.0001: exit $rc (the lightcut at 0.02 should be outside it)"; cat "$tmp/out"; }
"$PY" "$root/scripts/lightcut_bound.py" "$tmp/v.exr" "$tmp/v.exr" 0.02 | grep -q "worst bound usage 0.0000" \
  && ok || bad "an image against itself is not at usage 0"
"$PY" - "$root/scripts" "$tmp/v.exr" <<'PYEOF' && ok || bad "the reader on a FLOAT image"
import sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import lightcut_bound as lb
img = lb.read(sys.argv[2])
assert img.shape == (54, 96, 3), img.shape
assert np.isfinite(img).all() and img.max() > 0 and img.min() >= 0, (img.min(), img.max())
PYEOF
"$PG" render --scene default --size 37x13 --lights 8 --out "$tmp/h.png" --hdr-out "$tmp/h.exr" >/dev/null 2>&1
"$PY" - "$root/scripts" "$tmp/h.exr" <<'PYEOF' && ok || bad "the reader on a HALF image of odd size"
import sys
sys.path.insert(0, sys.argv[1])
import lightcut_bound as lb
img = lb.read(sys.argv[2])
assert img.shape == (13, 37, 3), img.shape
PYEOF
printf 'not an exr' >"$tmp/bad.exr"
"$PY" "$root/scripts/lightcut_bound.py" "$tmp/bad.exr" "$tmp/l.exr" 0.02 >/dev/null 2>"$tmp/err"
[ $? = 2 ] && grep -q "bad.exr: not a single-part scanline OpenEXR file" "$tmp/err" && ok || bad "a bad file: not exit 2"
check_finish lightcut_bound_test
