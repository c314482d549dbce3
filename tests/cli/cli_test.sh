#!/usr/bin/env bash
# cli_test.sh PASSGRAPH_BINARY - the command line as a user meets it: help texts, refusals of bad
# input (non-zero exit, message naming the cause, no crash), and a validated render whose summary
# line has the documented shape.
set -u
PG=$1
. "$(dirname "$0")/check_lib.sh"


# expect_fail "description" "substring of stderr" args...
expect_fail() {
  local what=$1 needle=$2
  shift 2
  "$PG" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [ $rc -eq 0 ]; then bad "$what: exit 0"; return; fi
  if [ $rc -ge 128 ]; then bad "$what: crashed (rc $rc)"; return; fi
  if ! grep -qF -- "$needle" "$tmp/err"; then bad "$what: stderr lacks '$needle':"; cat "$tmp/err"; return; fi
  ok
}

"$PG" --help >"$tmp/h" && grep -q "render" "$tmp/h" && ok || bad "passgraph --help"
"$PG" render --help >"$tmp/h" || bad "render --help exit"
for o in --pipeline --scene --scenario --camera --lights --size --time --seed --out --set --device --validation \
         --no-aliasing --immediate --explain --frames --radius --intensity --view --debug-view --ocio-config --display \
         --ocio-view --hdr-out; do
  grep -qF -- "$o" "$tmp/h" && ok || bad "render --help does not document $o"
done

expect_fail "no command" "usage" 
expect_fail "unknown command" "unknown command" frobnicate
expect_fail "unknown option" "unknown option" render --bogus --out "$tmp/x.png"
expect_fail "missing --out" "--out" render
expect_fail "negative lights" "--lights -1" render --lights -1 --out "$tmp/x.png"
expect_fail "an option where a value belongs" "--lights: missing value (followed by the option --out)" render --lights --out "$tmp/x.png"
expect_fail "lights > 2^32" "--lights 4294967296" render --lights 4294967296 --out "$tmp/x.png"
expect_fail "size 0x0" "--size width 0" render --size 0x0 --out "$tmp/x.png"
expect_fail "huge size" "--size width 100000" render --size 100000x100000 --out "$tmp/x.png"
# a full disk (/dev/full): the encoders' write errors reach the exit code (stb ignored them: exit 0)
if [ -w /dev/full ]; then
  ln -sf /dev/full "$tmp/full.png" && ln -sf /dev/full "$tmp/full.jpg"
  expect_fail "PNG on a full disk" "full.png: cannot write PNG: No space left on device" render --size 16x9 --lights 4 \
    --out "$tmp/full.png"
  expect_fail "JPEG on a full disk" "full.jpg: cannot write JPEG: No space left on device" render --size 16x9 --lights 4 \
    --out "$tmp/full.jpg"
  expect_fail "heat map on a full disk" "full.png: cannot write PNG: No space left" compare --size 16x9 --lights 4 \
    --frames 1 --flicker-frames 0 --heatmap "$tmp/full.png"
fi
expect_fail "size garbage" "expected WxH" render --size big --out "$tmp/x.png"
expect_fail "time NaN" "--time nan" render --time nan --out "$tmp/x.png"
# a float of seconds: past 1e5 a fraction of a second is lost (9999999.5 played the pose of a whole second)
expect_fail "time past 1e5" "--time 9999999.5: expected a finite number in [-100000, 100000]" render --time 9999999.5 --out "$tmp/x.png"
expect_fail "set without =" "KEY=VALUE" render --set foo --out "$tmp/x.png"
expect_fail "missing pipeline" "nope.json" render --pipeline "$tmp/nope.json" --out "$tmp/x.png"
expect_fail "missing scene" "missing.gltf" render --scene "$tmp/missing.gltf" --out "$tmp/x.png"
for o in --scene --scenario --pipeline --out; do # named as the option, not as an internal function
  expect_fail "empty $o" "$o: empty path" render "$o" "" --size 16x9
done
expect_fail "unknown parameter" "no_such_param" render --set no_such_param=1 --size 32x18 --out "$tmp/x.png"
# a --set key or value, or a debug view, the pipeline refuses is a bad option (exit 2, as in compare
# and bench) naming the option that gave it, found before a device is made
for bad_set in "--set no_such_param=1|--set no_such_param=1: the pipeline naive" \
               "--set shading=wat|--set shading=wat: pipeline" "--debug-view cluster_heat|--debug-view cluster_heat: pipeline" \
               "--view Nope|--view Nope: pipeline" \
               "--pipeline $(dirname "$0")/../../pipelines/lightcut.json --set lightcut_bucket=3|--set lightcut_bucket=3: pipeline"; do
  # shellcheck disable=SC2086
  "$PG" render ${bad_set%%|*} --size 32x18 --out "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc = 2 ] && grep -qF -- "${bad_set#*|}" "$tmp/err" && ! grep -q "^passgraph: device" "$tmp/err" \
    && { [ "${bad_set%% *}" != --view ] || grep -qF "nor is it a view of the OCIO config" "$tmp/err"; } && ok \
    || { bad "render ${bad_set%%|*}: want exit 2 naming the option (exit $rc)"; cat "$tmp/err"; }
  # dump the same (it exited 1 for a --set the pipeline refuses)
  [ "${bad_set%% *}" = --view ] && continue
  # shellcheck disable=SC2086
  "$PG" dump ${bad_set%%|*} >"$tmp/out" 2>"$tmp/err"
  rc=$?
  [ $rc = 2 ] && grep -qF -- "${bad_set#*|}" "$tmp/err" && ok \
    || { bad "dump ${bad_set%%|*}: want exit 2 naming the option (exit $rc)"; cat "$tmp/err"; }
done
printf '{"name":"x","resources":[{"name":"o","type":"image","format":"rgba8"}],"passes":[{"name":"p","type":"warp_drive","writes":["o"]}],"output":"o"}' >"$tmp/unknown_type.json"
expect_fail "unknown pass type" "passes[0].type" render --pipeline "$tmp/unknown_type.json" --size 32x18 --out "$tmp/x.png"
expect_fail "unwritable out" "cannot write" render --size 32x18 --lights 4 --out "$tmp/no/such/dir/x.png"
# --device: a whole number is an index (said against the count), any other text part of a name, also
# one that starts with a digit ("256 bits" of lavapipe's name)
expect_fail "device index out of range" "no usable Vulkan device matches (device index 15 of " render --device 15 --size 16x9 --out "$tmp/x.png"
"$PG" render --device 16 --size 16x9 --out "$tmp/x.png" >/dev/null 2>&1; [ $? = 1 ] && ok || bad "--device 16: want exit 1 as for 15 (no such device)"
expect_fail "device name" "no usable Vulkan device matches (a name containing 'no such gpu' among " render --device "no such gpu" --size 16x9 --out "$tmp/x.png"
dev=$("$PG" devices 2>/dev/null | grep -o '[0-9][0-9]* bits' | head -1)
[ -z "$dev" ] || { "$PG" render --device "$dev" --size 16x9 --lights 4 --out "$tmp/x.png" >/dev/null 2>"$tmp/err" && ok || { bad "--device '$dev' (a name starting with a digit)"; cat "$tmp/err"; }; }

# --explain gives the values --radius / --intensity put in place of the set-up's
"$PG" render --size 16x9 --lights 4 --radius 100 --intensity 5 --out "$tmp/r.png" --explain >"$tmp/out" 2>"$tmp/err" \
  && grep -q "; instead: radius 100 (--radius), intensity 5 (--intensity)" "$tmp/out" && ok \
  || { bad "render --radius/--intensity: the explain line lacks their values"; grep "lights:" "$tmp/out"; cat "$tmp/err"; }
"$PG" render --validation --size 160x90 --lights 32 --time 2 --out "$tmp/r.png" --explain >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "validated render exit $rc"; cat "$tmp/err"; else ok; fi
grep -Eq '^render: naive 160x90 lights=32 gpu=[0-9.]+ ms \[animate_lights [0-9.]+, shade [0-9.]+, display [0-9.]+\] nonfinite=0 frames=1 -> ' "$tmp/out" \
  && ok || { bad "summary line shape"; cat "$tmp/out"; }
grep -q "explain:" "$tmp/out" && ok || bad "--explain printed nothing"
[ -s "$tmp/r.png" ] && ok || bad "PNG not written"
grep -q "validation" "$tmp/err" && grep -q "validation message" "$tmp/err" && bad "validation messages" || ok

# ---- passgraph compare: image error against a reference pipeline ----
root=$(cd "$(dirname "$0")/../.." && pwd)
naive="$root/pipelines/naive.json"
"$PG" --help | grep -q "compare" && ok || bad "passgraph --help does not list compare"
"$PG" compare --help >"$tmp/h" || bad "compare --help exit"
for o in --pipeline --reference --reference-set --pipeline-set --scene --scenario --lights --size --time --seed --set \
         --device --validation --frames --heatmap --heatmap-scale --threshold --json pipelines/reference.json \
         --flip-map --no-hdr-flip --accumulate --flicker-frames; do
  grep -qF -- "$o" "$tmp/h" && ok || bad "compare --help does not document $o"
done
# compare_value KEY: the value of KEY= on the 'compare:' line of $tmp/out
compare_value() { grep '^compare: ' "$tmp/out" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
"$PG" compare --pipeline "$naive" --reference "$naive" --size 64x36 --lights 8 --validation --json "$tmp/c.json" \
  >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "compare same pipeline: exit $rc"; cat "$tmp/err"; else ok; fi
grep -Eq '^compare: pipeline=naive reference=naive lights=8 size=64x36 rmse_linear=' "$tmp/out" \
  && ok || { bad "compare line shape"; cat "$tmp/out"; }
[ "$(compare_value rmse_linear)" = 0 ] && ok || bad "same pipeline twice: rmse_linear=$(compare_value rmse_linear), want 0"
[ "$(compare_value max_abs_display)" = 0 ] && ok || bad "same pipeline twice: max_abs_display=$(compare_value max_abs_display), want 0"
[ "$(compare_value psnr_linear)" = inf ] && ok || bad "same pipeline twice: psnr_linear=$(compare_value psnr_linear), want inf"
[ "$(compare_value over_threshold)" = 0 ] && ok || bad "same pipeline twice: over_threshold not 0"
grep -q "validation message" "$tmp/err" && bad "compare: validation messages" || ok
grep -Eq '"rmse_linear":[[:space:]]*0,' "$tmp/c.json" && grep -q '"psnr_linear":[[:space:]]*"inf"' "$tmp/c.json" \
  && ok || { bad "compare --json content"; cat "$tmp/c.json"; }
# the perceptual and temporal numbers: printed on the compare: line and in --json (HDR-FLIP with its exposures)
for k in flip hdr_flip ssim flicker accumulate; do
  [ -n "$(compare_value $k)" ] && ok || { bad "compare: line lacks $k="; grep '^compare:' "$tmp/out"; }
done
[ "$(compare_value flip)" = 0 ] && [ "$(compare_value hdr_flip)" = 0 ] && [ "$(compare_value ssim)" = 1 ] \
  && [ "$(compare_value flicker)" = 0 ] && ok || { bad "same pipeline twice: want flip=0 hdr_flip=0 ssim=1 flicker=0"; grep '^compare:' "$tmp/out"; }
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["flip"] == 0 and d["hdr_flip"] == 0 and d["ssim"] == 1 and d["flicker"] == 0, d
assert d["hdr_flip_exposures"] >= 2 and d["hdr_flip_start_exposure"] <= d["hdr_flip_stop_exposure"] and d["accumulate"] == 1 and d["flicker_frames"] == 4, d' \
  "$tmp/c.json" && ok || bad "compare --json: flip / hdr_flip (exposures) / ssim / flicker"
# forward_plus and naive give bit-identical images: every perceptual and temporal number is exact
"$PG" compare --pipeline "$root/pipelines/forward_plus.json" --reference "$naive" --size 64x36 --lights 64 --quiet \
  --flip-map "$tmp/flip0.png" >"$tmp/out" 2>"$tmp/err" && ok || { bad "compare forward_plus: exit"; cat "$tmp/err"; }
[ "$(compare_value rmse_linear)" = 0 ] && [ "$(compare_value flip)" = 0 ] && [ "$(compare_value ssim)" = 1 ] \
  && [ "$(compare_value flicker)" = 0 ] && [ "$(compare_value hdr_flip)" = 0 ] && ok \
  || { bad "forward_plus vs naive: want rmse 0, flip 0, hdr_flip 0, ssim 1, flicker 0"; grep '^compare:' "$tmp/out"; }
# stochastic_threshold over its whole range (1e-6 .. 1e6): the threshold reaches the shaders in
# millionths, past a GLSL int literal above 2147.48 (it failed to compile there, or wrapped)
"$PG" dump --pipeline "$root/pipelines/stochastic.json" --set stochastic_threshold=3000 --lights 8 >"$tmp/out" 2>"$tmp/err" \
  && [ "$(grep -c "PG_SC_TAU_MICRO=3000000000.0" "$tmp/out")" = 2 ] && ok \
  || { bad "dump stochastic_threshold=3000: want the threshold in millionths in both passes"; grep TAU "$tmp/out"; cat "$tmp/err"; }
"$PG" render --pipeline "$root/pipelines/stochastic.json" --set stochastic_threshold=1000000 --size 16x9 --lights 8 \
  --out "$tmp/st.png" >"$tmp/out" 2>"$tmp/err" && ok || { bad "render stochastic_threshold=1000000 (its maximum)"; cat "$tmp/err"; }
# ris is stochastic: its image differs from the exact one (flip > 0) and changes with the sample (flicker > 0);
# the mean of 16 frames is closer to the reference than one frame; --flip-map is a PNG of the image's size
"$PG" compare --pipeline "$root/pipelines/ris.json" --reference "$naive" --size 64x36 --lights 64 --quiet --validation \
  --flip-map "$tmp/flip.png" --json "$tmp/ris.json" >"$tmp/out" 2>"$tmp/err" && ok || { bad "compare ris: exit"; cat "$tmp/err"; }
grep -q "validation message" "$tmp/err" && bad "compare ris: validation messages" || ok
ris_rmse1=$(compare_value rmse_linear)
awk -v f="$(compare_value flip)" -v k="$(compare_value flicker)" -v h="$(compare_value hdr_flip)" -v s="$(compare_value ssim)" \
  'BEGIN { exit !(f > 0 && f < 1 && k > 0 && h > 0 && s < 1) }' && ok \
  || { bad "ris vs naive: want flip > 0, hdr_flip > 0, ssim < 1, flicker > 0"; grep '^compare:' "$tmp/out"; }
python3 "$root/tests/cli/png_stats.py" "$tmp/flip.png" | grep -q '^64 36 ' && ok || bad "compare --flip-map: not a 64x36 PNG"
"$PG" compare --pipeline "$root/pipelines/ris.json" --reference "$naive" --size 64x36 --lights 64 --quiet --accumulate 16 \
  --flicker-frames 0 >"$tmp/out" 2>"$tmp/err" && ok || { bad "compare ris --accumulate 16: exit"; cat "$tmp/err"; }
awk -v a="$(compare_value rmse_linear)" -v b="$ris_rmse1" 'BEGIN { exit !(a > 0 && a < 0.7 * b) }' && ok \
  || bad "ris: --accumulate 16 must cut the RMSE: rmse_linear=$(compare_value rmse_linear) against $ris_rmse1 for one frame"
[ "$(compare_value accumulate)" = 16 ] && [ "$(compare_value flicker)" = nan ] && ok || { bad "compare --accumulate 16 --flicker-frames 0: line"; grep '^compare:' "$tmp/out"; }
"$PG" compare --pipeline "$root/pipelines/ris.json" --reference "$naive" --size 64x36 --lights 64 --quiet --no-hdr-flip \
  >"$tmp/out" 2>"$tmp/err" && [ "$(compare_value hdr_flip)" = nan ] && ok || { bad "compare --no-hdr-flip"; cat "$tmp/out" "$tmp/err"; }
for v in 0 x -1 1.5 4097; do
  expect_fail "compare --accumulate $v" "--accumulate $v: expected a whole number of frames in [1, 4096]" compare --accumulate "$v"
  "$PG" compare --accumulate "$v" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "compare --accumulate $v: want exit 2"
done
expect_fail "compare --flicker-frames 1" "--flicker-frames 1: flicker compares consecutive frames" compare --flicker-frames 1
expect_fail "compare --flicker-frames y" "--flicker-frames y: expected 0 (off)" compare --flicker-frames y
expect_fail "compare --flip-map .bmp" "--flip-map: $tmp/f.bmp: unsupported image extension" compare --flip-map "$tmp/f.bmp"
expect_fail "compare: unwritable flip map" "cannot write" compare --reference "$naive" --size 32x18 --lights 4 --flip-map "$tmp/no/such/dir/f.png"
# --pipeline-set: the reference declares hdr_format too, so --set would give both sides rgba32f
"$PG" compare --pipeline "$naive" --reference "$naive" --pipeline-set hdr_format=rgba32f --size 64x36 --lights 8 --validation \
  --heatmap "$tmp/heat.png" >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "compare rgba32f vs rgba16f: exit $rc"; cat "$tmp/err"; else ok; fi
awk -v r="$(compare_value rmse_linear)" -v m="$(compare_value max_abs_linear)" 'BEGIN { exit !(r > 0 && r < 0.01 && m > 0 && m < 1) }' \
  && ok || bad "rgba32f vs rgba16f: want a small nonzero linear error: rmse_linear=$(compare_value rmse_linear) max_abs_linear=$(compare_value max_abs_linear)"
[ "$(head -c 4 "$tmp/heat.png" 2>/dev/null | tail -c 3)" = PNG ] && ok || bad "compare --heatmap did not write a PNG"
expect_fail "compare: missing reference" "nope_ref.json" compare --reference "$tmp/nope_ref.json" --size 32x18 --lights 4
expect_fail "compare: missing pipeline" "nope_a.json" compare --pipeline "$tmp/nope_a.json" --size 32x18 --lights 4
printf '{"name":"nohdr","include":["%s/pipelines/fragments/lights.json","%s/pipelines/fragments/display.json"],
 "resources":[{"name":"hdr","type":"image","format":"rgba16f"},{"name":"depth","type":"image","format":"d32f"}],
 "passes":[{"name":"shade","type":"forward_naive","reads":["lights"],"writes":["hdr","depth"]}],"output":"ldr"}' \
  "$root" "$root" >"$tmp/nohdr.json"
expect_fail "compare: no hdr_output" "hdr_output" compare --pipeline "$tmp/nohdr.json" --size 32x18 --lights 4
expect_fail "compare: unknown option" "unknown option" compare --bogus
expect_fail "compare: --out is not an option" "unknown option '--out'" compare --out "$tmp/x.png"
expect_fail "compare: negative threshold" "--threshold -1" compare --threshold -1
expect_fail "compare: heatmap-scale garbage" "--heatmap-scale big" compare --heatmap-scale big
expect_fail "compare: reference-set without =" "KEY=VALUE" compare --reference-set foo
expect_fail "compare: unknown reference parameter" "--reference-set no_such_param=1: the reference naive" \
  compare --reference "$naive" --reference-set no_such_param=1 --size 32x18 --lights 4
expect_fail "compare: unwritable heatmap" "cannot write" compare --reference "$naive" --size 32x18 --lights 4 --heatmap "$tmp/no/such/dir/h.png"
expect_fail "compare: unwritable json" "cannot write" compare --reference "$naive" --size 32x18 --lights 4 --json "$tmp/no/such/dir/c.json"

# --json -: the JSON alone on stdout (it wrote a file named '-'), the report on stderr
(cd "$tmp" && "$PG" compare --pipeline "$naive" --reference "$naive" --size 16x9 --lights 4 --heatmap "$tmp/same.png" \
   --flicker-frames 0 --json - >"$tmp/stdout.json" 2>"$tmp/err") \
  && python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["rmse_linear"] == 0 and d["heatmap_scale"] == 0, d' \
     "$tmp/stdout.json" && [ ! -e "$tmp/-" ] && grep -q '^compare: ' "$tmp/err" \
  && grep -qF "over [0, 0]: no pixel differs: the map is black" "$tmp/err" \
  && grep -qF "flicker=nan (not measured: --flicker-frames 0)" "$tmp/err" && ok \
  || { bad "compare --json -: JSON on stdout, report on stderr, heatmap scale 0 for identical images"; head -5 "$tmp/stdout.json" "$tmp/err"; }
# a folder the permission bits allow but the file system refuses (/proc, as root): refused before
# rendering, exit 2 (it rendered both sides, then failed with exit 1)
if [ -d /proc/self ] && [ "$(id -u)" = 0 ]; then
  "$PG" compare --reference "$naive" --size 16x9 --lights 4 --json /proc/pg.json >"$tmp/out" 2>"$tmp/err"
  [ $? -eq 2 ] && ! grep -q '^sides:' "$tmp/out" && grep -qF -- "--json '/proc/pg.json': cannot write" "$tmp/err" && ok \
    || { bad "compare --json /proc/pg.json: exit 2 before rendering"; cat "$tmp/out" "$tmp/err"; }
  "$PG" bench --pipelines naive --lights 4 --size 16x9 --frames 1 --warmup 0 --quiet --out /proc/pg >"$tmp/out" 2>"$tmp/err"
  [ $? -eq 2 ] && grep -qF -- "--out /proc/pg: cannot create /proc/pg" "$tmp/err" && ok \
    || { bad "bench --out /proc/pg: exit 2"; cat "$tmp/err"; }
fi
# --set reaches the reference when it declares the key; --pipeline-set / --reference-set one side only;
# the debug view stays the pipeline's. The 'sides:' line says what each side used.
fplus="$root/pipelines/forward_plus.json"
# compare_sides [args...]: runs forward_plus against naive at 64x36 (64 lights: no cluster overflows, so
# forward+ equals naive when both shade alike); output in $tmp/out
compare_sides() {
  "$PG" compare --pipeline "$fplus" --reference "$naive" --size 64x36 --lights 64 --quiet "$@" >"$tmp/out" 2>"$tmp/err"
}
sides_value() { grep '^sides: ' "$tmp/out" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
# exact KEY: compare_value KEY is within 1e-6 of 0; large: rmse_linear > 1e-3 and > 5% of the pixels differ
near_zero() { awk -v r="$(compare_value rmse_linear)" -v o="$(compare_value over_threshold)" 'BEGIN { exit !(r != "" && r + 0 < 1e-6 && o == 0) }'; }
large_error() { awk -v r="$(compare_value rmse_linear)" -v o="$(compare_value over_threshold)" 'BEGIN { exit !(r + 0 > 1e-3 && o + 0 > 0.05) }'; }
compare_sides --set shading=blinn_phong --json "$tmp/sides.json"
rc=$?
if [ $rc -ne 0 ]; then bad "compare --set shading=blinn_phong: exit $rc"; cat "$tmp/err"; else ok; fi
near_zero && ok || bad "compare --set shading=blinn_phong: the reference must shade Blinn-Phong too: rmse_linear=$(compare_value rmse_linear) over_threshold=$(compare_value over_threshold)"
[ "$(head -n 1 "$tmp/out" | cut -d' ' -f1)" = "sides:" ] && ok || { bad "compare: the sides line is not the first line"; cat "$tmp/out"; }
[ "$(sides_value pipeline)" = forward_plus ] && [ "$(sides_value pipeline_path)" = "$fplus" ] \
  && [ "$(sides_value pipeline_sets)" = shading=blinn_phong ] && [ "$(sides_value reference)" = naive ] \
  && [ "$(sides_value reference_path)" = "$naive" ] && [ "$(sides_value reference_sets)" = shading=blinn_phong ] \
  && ok || { bad "compare --set: sides line"; grep '^sides:' "$tmp/out"; }
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["pipeline_sets"] == {"shading": "blinn_phong"} and d["reference_sets"] == {"shading": "blinn_phong"}, d' \
  "$tmp/sides.json" && ok || bad "compare --json: pipeline_sets / reference_sets"
compare_sides --pipeline-set shading=blinn_phong
large_error && ok || bad "compare --pipeline-set shading=blinn_phong: want a large error against a Lambert reference: rmse_linear=$(compare_value rmse_linear) over_threshold=$(compare_value over_threshold)"
[ "$(sides_value pipeline_sets)" = shading=blinn_phong ] && [ "$(sides_value reference_sets)" = none ] \
  && ok || { bad "compare --pipeline-set: sides line"; grep '^sides:' "$tmp/out"; }
compare_sides --set shading=blinn_phong --reference-set shading=lambert
large_error && ok || bad "compare --reference-set wins over --set: rmse_linear=$(compare_value rmse_linear)"
[ "$(sides_value pipeline_sets)" = shading=blinn_phong ] && [ "$(sides_value reference_sets)" = shading=lambert ] \
  && ok || { bad "compare --set + --reference-set: sides line"; grep '^sides:' "$tmp/out"; }
compare_sides --reference-set shading=blinn_phong --pipeline-set shading=blinn_phong
near_zero && [ "$(sides_value reference_sets)" = shading=blinn_phong ] && ok || bad "compare: --pipeline-set and --reference-set together"
compare_sides --set shading=blinn_phong --debug-view albedo
rc=$?
[ $rc -eq 0 ] && [ "$(sides_value pipeline_sets)" = "shading=blinn_phong;view=albedo" ] && [ "$(sides_value reference_sets)" = shading=blinn_phong ] \
  && ok || { bad "compare --debug-view: pipeline only (rc $rc)"; grep '^sides:' "$tmp/out"; cat "$tmp/err"; }
large_error && ok || bad "compare --debug-view albedo against lit naive: want a large error"
expect_fail "compare: --pipeline-set without =" "--pipeline-set shading: expected KEY=VALUE" compare --pipeline-set shading
expect_fail "compare: --pipeline-set of an undeclared key" "--pipeline-set gbuffer=packed: the pipeline forward_plus" \
  compare --pipeline "$fplus" --reference "$naive" --pipeline-set gbuffer=packed
expect_fail "compare: a --set value the reference refuses" "--reference-set view=VALUE" \
  compare --pipeline "$fplus" --reference "$naive" --set view=cluster_heat
expect_fail "compare: a --reference-set value refused" "--reference-set shading=toon: reference" \
  compare --reference "$naive" --reference-set shading=toon
"$PG" compare --reference "$naive" --reference-set shading=toon >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && ok || bad "compare: a refused --reference-set value must exit 2 (bad option)"
# the default reference is pipelines/reference.json of the data folder
if [ -f "$root/pipelines/reference.json" ]; then
  "$PG" compare --size 32x18 --lights 4 --quiet >"$tmp/out" 2>"$tmp/err" && [ "$(sides_value reference_path)" = "$root/pipelines/reference.json" ] \
    && ok || { bad "compare: default reference"; cat "$tmp/out" "$tmp/err"; }
else
  expect_fail "compare: default reference (pipelines/reference.json, not in this checkout)" "pipelines/reference.json" compare --size 32x18 --lights 4
fi

# debug views: every view of a clustered pipeline renders; a cluster view on naive is refused
for v in cluster_heat cluster_x cluster_y cluster_z overflow albedo normal depth; do
  "$PG" render --pipeline "$root/pipelines/forward_plus.json" --view $v --size 64x36 --lights 16 --out "$tmp/v.png" >"$tmp/out" 2>"$tmp/err" \
    && [ -s "$tmp/v.png" ] && ok || { bad "--view $v"; cat "$tmp/err"; }
done
expect_fail "cluster view on naive" "not one of" render --pipeline "$root/pipelines/naive.json" --view cluster_heat --size 64x36 --out "$tmp/v.png"
# colour: OCIO views and displays by name (spaces and parentheses), EXR output, clear refusals
# a display given to a pipeline without display_ocio (tonemap=clamp): said, not silently ignored
"$PG" render --size 64x36 --lights 8 --set tonemap=clamp --display Rec.1886 --out "$tmp/c.png" >/dev/null 2>"$tmp/err" \
  && grep -q "warning: --display Rec.1886: no effect, the pipeline runs no display_ocio pass" "$tmp/err" \
  && "$PG" render --size 64x36 --lights 8 --display Rec.1886 --out "$tmp/c.png" >/dev/null 2>"$tmp/err" && ! grep -q "no effect" "$tmp/err" \
  && ok || { bad "--display with tonemap=clamp: no warning"; cat "$tmp/err"; }
"$PG" render --validation --size 64x36 --lights 8 --view "Filmic (ACES)" --display Rec.1886 --out "$tmp/c.exr" \
  >"$tmp/out" 2>"$tmp/err" && [ "$(head -c 4 "$tmp/c.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] \
  && [ "$(head -c 4 "$tmp/c.png" | tail -c 3)" = PNG ] && ok || { bad "render --view 'Filmic (ACES)' --out x.exr"; cat "$tmp/err"; }
grep -q "validation message" "$tmp/err" && bad "OCIO render: validation messages" || ok
"$PG" render --size 64x36 --lights 8 --ocio-view Raw --debug-view albedo --out "$tmp/c2.png" --hdr-out "$tmp/c2.exr" \
  >"$tmp/out" 2>"$tmp/err" && [ -s "$tmp/c2.png" ] && [ -s "$tmp/c2.exr" ] && ok || { bad "--ocio-view --debug-view --hdr-out"; cat "$tmp/err"; }
expect_fail "unknown OCIO display" "displays: sRGB, Rec.1886" render --display Nope --size 32x18 --out "$tmp/x.png"
expect_fail "unknown OCIO view" "views: Standard, Filmic (ACES), Raw" render --ocio-view Nope --size 32x18 --out "$tmp/x.png"
expect_fail "missing OCIO config" "nope.ocio" render --ocio-config "$tmp/nope.ocio" --size 32x18 --out "$tmp/x.png"
printf 'ocio_profile_version: 2\nroles: [\n' >"$tmp/broken.ocio"
expect_fail "broken OCIO config" "broken.ocio" render --ocio-config "$tmp/broken.ocio" --size 32x18 --out "$tmp/x.png"
OCIO="$tmp/broken.ocio" "$PG" render --size 32x18 --lights 4 --out "$tmp/x.png" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "broken.ocio" "$tmp/err" && ok || { bad "\$OCIO broken config not reported"; cat "$tmp/err"; }
expect_fail "--hdr-out not .exr" "expected a .exr" render --hdr-out "$tmp/x.png" --out "$tmp/x.png"

# the tiled deferred light loop is bit-identical to the per-pixel one (both tile sizes)
for t in 8 16; do
  "$PG" compare --pipeline "$root/pipelines/deferred_packed.json" --reference "$root/pipelines/deferred_packed.json" \
    --pipeline-set tile_size=$t --reference-set tile_lights=false --lights 2000 --radius 4 --size 64x36 >"$tmp/out" 2>&1
  grep -q '^compare: .* rmse_linear=0 .*max_abs_linear=0 ' "$tmp/out" && ok || { bad "tile_size=$t differs from the per-pixel loop"; tail -2 "$tmp/out"; }
done
# the dump marks grow buffers (own memory, never aliased)
"$PG" dump --pipeline "$root/pipelines/forward_plus.json" --format json 2>/dev/null | python3 -c '
import json, sys
d = json.load(sys.stdin)
g = {r["name"]: r for r in d["resources"]}
sys.exit(0 if g["cluster_lights"]["grow"] and g["cluster_lights"]["block"] is None and not g["cluster_counts"]["grow"] else 1)' \
  && ok || bad "dump json: cluster_lights not marked grow"
"$PG" dump --pipeline "$root/pipelines/forward_plus.json" 2>/dev/null | grep -Eq '^  cluster_lights .* own \(grow\)$' && ok || bad "dump text: no 'own (grow)'"
# exact by default: the light lists grow to what the frame needs (frame rendered again) and drop nothing
"$PG" render --pipeline "$root/pipelines/forward_plus.json" --lights 3000 --radius 6 --size 64x36 --out "$tmp/o.png" >"$tmp/out" 2>&1
grep -Eq 'overflow=0 clusters \(0 light refs dropped\) refs=[0-9]+ lists=[0-9.]+ MiB grew cluster_lights [0-9.]+->[0-9.]+ MiB \(1 re-render\)' "$tmp/out" \
  && ok || { bad "list growth not reported"; cat "$tmp/out"; }
# past the list budget: the overflow is counted and a note says why
"$PG" render --pipeline "$root/pipelines/deferred.json" --lights 20000 --radius 6 --set list_budget_mb=1 --size 64x36 --out "$tmp/o.png" >"$tmp/out" 2>&1
grep -Eq 'overflow=[1-9][0-9]* clusters \([1-9][0-9]* light refs dropped\)' "$tmp/out" && grep -q '^note: light lists need .* over the 1.0 MiB budget' "$tmp/out" \
  && ok || { bad "budget overflow not reported"; cat "$tmp/out"; }
# a budget under 256 bytes is still a budget (it rounded to 0, which means "auto": the lists grew)
"$PG" render --pipeline "$root/pipelines/forward_plus.json" --lights 2000 --set list_budget_mb=1e-9 --size 64x36 \
  --out "$tmp/o.png" >"$tmp/out_tiny" 2>&1
grep -q 'render: warning: the image is not exact: [1-9][0-9]* light references dropped' "$tmp/out_tiny" \
  && ok || { bad "list_budget_mb=1e-9 read as auto"; cat "$tmp/out_tiny"; }
# a frame that dropped references is not exact: a warning line (exit 0), --require-exact fails,
# the bench row reads status=inexact (a failure with --require-exact)
grep -q 'render: warning: the image is not exact: [1-9][0-9]* light references dropped' "$tmp/out" \
  && ok || { bad "render: no inexact warning"; cat "$tmp/out"; }
"$PG" render --pipeline "$root/pipelines/deferred.json" --lights 20000 --radius 6 --set list_budget_mb=1 --size 64x36 --require-exact --out "$tmp/o.png" >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q 'error: the image is not exact.*(--require-exact)' "$tmp/out" \
  && ok || { bad "render --require-exact: exit $rc"; cat "$tmp/out"; }
"$PG" render --pipeline "$root/pipelines/deferred.json" --lights 64 --size 64x36 --require-exact --out "$tmp/o.png" >"$tmp/out" 2>&1 \
  && ! grep -q 'not exact' "$tmp/out" && ok || { bad "render --require-exact on an exact frame"; cat "$tmp/out"; }
"$PG" compare --pipeline "$root/pipelines/deferred.json" --lights 20000 --radius 6 --set list_budget_mb=1 --size 64x36 --require-exact >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "compare: error: the pipeline's image is not exact" "$tmp/out" \
  && ok || { bad "compare --require-exact: exit $rc"; cat "$tmp/out"; }
for re in "" --require-exact; do
  "$PG" bench --pipelines "$root/pipelines/deferred.json" --lights 20000 --radius 6 --set list_budget_mb=1 --size 64x36 \
    --frames 1 --warmup 0 --reference-max-lights 0 $re --out "$tmp/bi" >"$tmp/out" 2>&1
  rc=$?
  want=0; [ -n "$re" ] && want=1
  [ $rc -eq $want ] && grep -q '^bench: deferred .* inexact' "$tmp/out" && grep -q ',deferred,.*,inexact,not exact: [1-9]' "$tmp/bi/results.csv" \
    && ok || { bad "bench $re: inexact row (exit $rc, want $want)"; cat "$tmp/out"; }
done
# an allocation the device refuses while the lists grow: a note, the overflow reported, exit 0, no crash
PASSGRAPH_FAULT_CALL="(grow)" "$PG" render --pipeline "$root/pipelines/forward_plus.json" --lights 3000 --radius 6 --size 64x36 \
  --out "$tmp/o.png" >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 0 ] && grep -q "^note: buffer 'cluster_lights' could not grow from .* (VK_ERROR_OUT_OF_DEVICE_MEMORY): kept" "$tmp/out" \
  && grep -Eq 'overflow=[1-9][0-9]* clusters \([1-9][0-9]* light refs dropped\)' "$tmp/out" \
  && ok || { bad "refused list growth not reported (rc $rc)"; cat "$tmp/out"; }
# a driver error after a buffer's or image's memory was allocated (bind, map, view): the error
# named, nothing leaked (the buffer and its memory outlived the device: the validation layer's
# "has not been destroyed" at exit)
for call in vkMapMemory vkBindBufferMemory vkBindImageMemory vkCreateImageView; do
  PASSGRAPH_FAULT_CALL=$call "$PG" render --validation --size 32x18 --lights 4 --out "$tmp/o.png" >"$tmp/out" 2>&1
  rc=$?
  [ $rc = 1 ] && grep -q "$call(.*failed: VK_ERROR_DEVICE_LOST" "$tmp/out" && ! grep -q "has not been destroyed" "$tmp/out" \
    && ok || { bad "a failed $call: want its error and nothing leaked (rc $rc)"; grep -m3 "failed\|destroyed" "$tmp/out"; }
done
# clustered summary reports overflow (all lights at one point, 2 per cluster)
"$PG" render --pipeline "$root/pipelines/forward_plus.json" --set max_lights=2 --lights 64 --radius 100 --size 64x36 --out "$tmp/o.png" >"$tmp/out" 2>&1
grep -Eq 'overflow=[1-9][0-9]* clusters \([0-9]+ light refs dropped\)' "$tmp/out" && ok || { bad "overflow not reported"; cat "$tmp/out"; }

# ---- passgraph dump: the compiled graph without rendering (text, JSON, DOT, memory timeline) ----
deferred="$root/pipelines/deferred.json"
"$PG" --help | grep -q "dump" && ok || bad "passgraph --help does not list dump"
"$PG" dump --help >"$tmp/h" || bad "dump --help exit"
for o in --pipeline --scene --lights --size --set --no-aliasing --immediate --view --format --out text json dot timeline graphviz \
         --scenario --debug-view --gltf-scene --variant --animation --environment --include-dir --plugin --async-compute \
         --time --seed --radius --intensity --ambient --environment-intensity --environment-rotation --frames --device \
         --validation --explain --quiet --camera --ocio-config --display --ocio-view; do
  grep -qF -- "$o" "$tmp/h" && ok || bad "dump --help does not document $o"
done
for fmt in text json dot timeline; do
  "$PG" dump --pipeline "$deferred" --lights 1000 --format $fmt >"$tmp/dump.$fmt" 2>"$tmp/err" && [ -s "$tmp/dump.$fmt" ] \
    && ok || { bad "dump --format $fmt"; cat "$tmp/err"; }
done
grep -q "^totals: 5 passes run, 4 culled; 14 barriers" "$tmp/dump.text" && grep -q "^memory timeline" "$tmp/dump.text" \
  && ok || { bad "dump text: totals or timeline missing"; cat "$tmp/dump.text"; }
python3 -c 'import json,sys; json.load(sys.stdin)' <"$tmp/dump.json" && ok || bad "dump --format json does not parse"
python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["format_version"] == 1 and d["order"][-1] == "display" and d["totals"]["passes_run"] == 5' \
  <"$tmp/dump.json" && ok || bad "dump json content"
head -n 1 "$tmp/dump.dot" | grep -q "^digraph" && ok || bad "dump --format dot is not a digraph"
head -c 4 "$tmp/dump.timeline" | grep -q "<svg" && tail -n 1 "$tmp/dump.timeline" | grep -q "</svg>" && ok || bad "dump --format timeline is not an SVG"
"$PG" dump --pipeline "$deferred" --format timeline --out "$tmp/tl.svg" >"$tmp/out" 2>"$tmp/err" && grep -q "^dump: deferred 1920x1080" "$tmp/out" \
  && grep -q "class=\"bar\"" "$tmp/tl.svg" && ok || { bad "dump timeline --out"; cat "$tmp/err"; }
"$PG" dump --pipeline "$deferred" --lights 0 --format json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert [p["name"] for p in d["culled_passes"]] == ["filter_environment", "animate_geometry", "animate_lights", "assign_lights", "background", "transparent"]' \
  && ok || bad "dump --lights 0 does not cull light animation and assignment (and the filter without an environment, the geometry pass without animation)"
# the transparent pass: culled with its reason without BLEND materials, run with them
grep -q "culled pass 'transparent': no BLEND materials: no transparent pass" "$tmp/dump.text" \
  && ok || bad "dump text: transparent pass not culled with its reason"
"$PG" dump --pipeline "$deferred" --scene "$root/tests/corpus/gltf/blend/blend_lit.gltf" --format json 2>/dev/null \
  | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["order"][-2:] == ["transparent", "display"]' \
  && ok || bad "dump with a BLEND scene does not run the transparent pass before the display"
if command -v dot >/dev/null 2>&1; then
  "$PG" dump --pipeline "$deferred" --format dot --out "$tmp/graph.svg" >"$tmp/out" 2>"$tmp/err" && grep -q "<svg" "$tmp/graph.svg" \
    && ok || { bad "dump --format dot --out x.svg"; cat "$tmp/err"; }
  dot -Tsvg "$tmp/dump.dot" -o "$tmp/graph2.svg" 2>"$tmp/err" && ok || { bad "dot rejects the DOT dump"; cat "$tmp/err"; }
else
  echo "cli_test: Graphviz 'dot' not installed: skipping dump --out x.svg"
fi
PATH=/nonexistent-passgraph "$PG" dump --pipeline "$deferred" --format dot --out "$tmp/nodot.svg" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "graphviz" "$tmp/err" && ok || { bad "dump without dot: rc $rc, no message naming graphviz"; cat "$tmp/err"; }
# --immediate: the dump says so (text and JSON), with no aliasing and full barriers
"$PG" dump --pipeline "$deferred" --immediate >"$tmp/imm.txt" 2>"$tmp/err" \
  && grep -qF "mode: immediate (declaration order, no aliasing, before every pass a full barrier all_commands/memory_write -> all_commands/memory_read|memory_write)" "$tmp/imm.txt" \
  && grep -q "^memory blocks (aliasing disabled):" "$tmp/imm.txt" \
  && ! grep -E "^      barrier " "$tmp/imm.txt" | grep -vq "all_commands/memory_write -> all_commands/memory_read|memory_write" \
  && ok || { bad "dump --immediate text"; cat "$tmp/err"; }
"$PG" dump --pipeline "$deferred" --format json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["immediate"] is False and d["aliasing"] is True' \
  && "$PG" dump --pipeline "$deferred" --immediate --format json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["immediate"] is True and d["aliasing"] is False' \
  && ok || bad "dump --format json: immediate / aliasing fields"
"$PG" dump --pipeline "$root/pipelines/reference.json" --lights 100000 | grep -qF "accum_diffuse (storage_rw, initialized by the pass)" \
  && "$PG" dump --pipeline "$deferred" | grep -qF "cluster_lights (storage_write, partial)" \
  && ok || bad "dump text: initialized / partial slots"
"$PG" render --immediate --validation --pipeline "$deferred" --size 64x36 --lights 8 --out "$tmp/imm.png" >"$tmp/out" 2>"$tmp/err" \
  && "$PG" render --validation --pipeline "$deferred" --size 64x36 --lights 8 --out "$tmp/nimm.png" >/dev/null 2>&1 \
  && cmp -s "$tmp/imm.png" "$tmp/nimm.png" && ok || { bad "render --immediate: failed or a different image"; cat "$tmp/err"; }
# PASSGRAPH_PIPELINE_STATS on a device without VK_KHR_pipeline_executable_properties (lavapipe):
# one line naming the device and the extension, exit 0, the same image
PASSGRAPH_PIPELINE_STATS=1 "$PG" render --validation --pipeline "$deferred" --size 64x36 --lights 8 --out "$tmp/pstats.png" >/dev/null 2>"$tmp/err" \
  && [ "$(grep -c 'pipeline-stats: .* lacks VK_KHR_pipeline_executable_properties: no statistics' "$tmp/err")" = 1 ] \
  && cmp -s "$tmp/pstats.png" "$tmp/nimm.png" && ok || { bad "render with PASSGRAPH_PIPELINE_STATS"; cat "$tmp/err"; }
expect_fail "dump: bad pipeline" "passes[0].type" dump --pipeline "$tmp/unknown_type.json"
expect_fail "dump: missing pipeline" "nope_dump.json" dump --pipeline "$tmp/nope_dump.json"
expect_fail "dump: bad format" "--format xml" dump --pipeline "$deferred" --format xml
expect_fail "dump: timeline as png" "writes SVG" dump --pipeline "$deferred" --format timeline --out "$tmp/tl.png"
expect_fail "dump: unknown option" "unknown option" dump --bogus
expect_fail "dump: unwritable out" "cannot write" dump --pipeline "$deferred" --out "$tmp/no/such/dir/d.txt"

# ---- passgraph bench: every pipeline over light counts; CSV, JSON and SVG charts ----
"$PG" --help | grep -q "bench" && ok || bad "passgraph --help does not list bench"
"$PG" bench --help >"$tmp/h" || bad "bench --help exit"
for o in --pipelines --lights --size --warmup --frames --seed --out --set --sweep --reference --reference-max-lights \
         --pipeline-set --reference-set --naive-max-lights --time-step --validation pipelines/reference.json \
         --accumulate --flicker-frames --no-hdr-flip flip_vs_time.svg; do
  grep -qF -- "$o" "$tmp/h" && ok || bad "bench --help does not document $o"
done
n_pipes=$(ls "$root"/pipelines/*.json | wc -l)
n_gbuf=$(grep -lE '"gbuffer": *\{' "$root"/pipelines/*.json | wc -l) # pipelines declaring the parameter
"$PG" bench --pipelines all --lights 0,16 --size 64x36 --frames 2 --warmup 1 --validation --out "$tmp/bench" \
  >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "bench --pipelines all: exit $rc"; cat "$tmp/err"; else ok; fi
rows=$(($(wc -l <"$tmp/bench/results.csv" 2>/dev/null || echo 0) - 1))
[ "$rows" -eq $((n_pipes * 2)) ] && ok || bad "bench results.csv: $rows rows, want $((n_pipes * 2)) ($n_pipes pipelines x 2 light counts)"
head -1 "$tmp/bench/results.csv" | grep -q '^scene,pipeline,variant,.*gpu_ms_median,.*rmse_linear,.*error_note' \
  && ok || bad "bench results.csv header"
[ "$(grep -c ',ok,' "$tmp/bench/results.csv")" -eq $((n_pipes * 2)) ] && ok || bad "bench: not every row has status ok"
python3 -c 'import json,sys;d=json.load(open(sys.argv[1]));assert len(d["rows"])==int(sys.argv[2])' \
  "$tmp/bench/results.json" $((n_pipes * 2)) && ok || bad "bench results.json does not parse or has the wrong row count"
for f in gpu_time_vs_lights passes_stacked error_vs_time flip_vs_time; do
  [ "$(head -c 5 "$tmp/bench/$f.svg" 2>/dev/null)" = "<svg " ] && tail -1 "$tmp/bench/$f.svg" | grep -q '</svg>' \
    && ok || bad "bench did not write $f.svg"
done
# every pass in the stacked chart has one colour of its own (15 passes shared 10 colours: display
# and assign_lights one red in deferred's bar)
python3 - "$tmp/bench/passes_stacked.svg" <<'PYEOF' && ok || bad "passes_stacked.svg: passes share a colour"
import re, sys
m = {}
for fill, name in re.findall(r'fill="(#[0-9a-f]{6})" stroke="#fff" stroke-width="0.5"><title>([^:<]+):', open(sys.argv[1]).read()):
    m.setdefault(name, set()).add(fill)
assert len(m) >= 12 and all(len(f) == 1 for f in m.values()), m
assert len({next(iter(f)) for f in m.values()}) == len(m), m
PYEOF
# every row carries flip, hdr_flip, ssim, flicker, accumulate; deterministic pipelines (lightcut
# too) flicker exactly 0, the stochastic ones (ris, stochastic) do not
python3 - "$tmp/bench/results.csv" "$tmp/bench/results.json" <<'PYEOF' && ok || bad "bench: perceptual / temporal columns"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for x in rows:
    for c in ("flip", "hdr_flip", "ssim", "flicker"):
        assert x[c] != "", (x["pipeline"], x["lights"], c)
    assert x["accumulate"] == "1" and x["flicker_frames"] == "4" and float(x["accumulated_ms_median"]) == float(x["gpu_ms_median"]), x
    if x["pipeline"] in ("ris", "stochastic"):
        assert float(x["flicker"]) > 0 or x["lights"] == "0", x
    else:
        assert float(x["flicker"]) == 0, (x["pipeline"], x["lights"], x["flicker"])
    assert 0 <= float(x["flip"]) <= 1 and float(x["ssim"]) <= 1, x
assert any(x["pipeline"] == "ris" for x in rows)
# the light-list columns: empty for the pipelines without cluster lists (lightcut counts
# evaluations only: its row read 0s), filled for the clustered ones with lights (0 lights: culled)
lists = ("overflow_clusters", "overflow_dropped", "overflow_clusters_max", "light_refs", "list_bytes")
for x in rows:
    empty = x["pipeline"] in ("naive", "reference", "lightcut") or x["lights"] == "0"
    assert all((x[c] == "") == empty for c in lists), (x["pipeline"], x["lights"], [x[c] for c in lists])
assert any(x["pipeline"] == "lightcut" and x["light_evals"] != "" for x in rows)
d = json.load(open(sys.argv[2]))
for r in d["rows"]:
    e = r["error"]
    assert r["accumulate"] == 1 and all(k in e for k in ("flip", "hdr_flip", "hdr_flip_start_exposure", "hdr_flip_stop_exposure", "ssim", "flicker")), r
assert d["meta"]["accumulate"] == 1 and d["meta"]["flicker_frames"] == 4 and d["meta"]["hdr_flip"] is True
PYEOF
grep -Eq '^bench: ris .* flip=[0-9.e-]+ hdr_flip=.* ssim=.* flicker=' "$tmp/out" && ok || { bad "bench: row line lacks flip / flicker"; grep '^bench: ris' "$tmp/out"; }
# --accumulate in bench: the mean of 8 frames of ris is closer to the reference than one frame
"$PG" bench --pipelines ris --reference "$naive" --lights 64 --size 64x36 --frames 1 --warmup 0 --quiet --accumulate 8 \
  --flicker-frames 0 --no-hdr-flip --out "$tmp/bench_acc" >"$tmp/out" 2>"$tmp/err" && ok || { bad "bench --accumulate 8: exit"; cat "$tmp/err"; }
"$PG" bench --pipelines ris --reference "$naive" --lights 64 --size 64x36 --frames 1 --warmup 0 --quiet \
  --out "$tmp/bench_acc1" >"$tmp/out" 2>"$tmp/err" && ok || { bad "bench ris: exit"; cat "$tmp/err"; }
python3 - "$tmp/bench_acc/results.csv" "$tmp/bench_acc1/results.csv" <<'PYEOF' && ok || bad "bench --accumulate 8: columns or error"
import csv, sys
a = list(csv.DictReader(open(sys.argv[1])))[0]; b = list(csv.DictReader(open(sys.argv[2])))[0]
assert a["accumulate"] == "8" and abs(float(a["accumulated_ms_median"]) - 8 * float(a["gpu_ms_median"])) < 1e-3 * float(a["accumulated_ms_median"]), a
assert a["flicker"] == "" and a["hdr_flip"] == "" and a["flip"] != "", a
assert float(a["rmse_linear"]) < 0.7 * float(b["rmse_linear"]) and float(a["flip"]) < float(b["flip"]), (a["rmse_linear"], b["rmse_linear"], a["flip"], b["flip"])
PYEOF
for v in 0 x; do
  expect_fail "bench --accumulate $v" "--accumulate $v: expected a whole number" bench --accumulate "$v" --out "$tmp/bx"
  "$PG" bench --accumulate "$v" --out "$tmp/bx" >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "bench --accumulate $v: want exit 2"
done
expect_fail "bench --flicker-frames 1" "--flicker-frames 1:" bench --flicker-frames 1 --out "$tmp/bx"
expect_fail "bench --warmup-ms x" "--warmup-ms" bench --warmup-ms x --out "$tmp/bx"
# light evaluations: RIS evaluates candidates x samples a lit pixel (doubling the samples doubles
# the count exactly); visibility's tiled loop evaluates fewer lights than its per-pixel loop
evals() { "$PG" render --size 64x36 --lights 64 --out "$tmp/ev.png" "$@" 2>/dev/null | grep -o 'light_evals=[0-9]*' | cut -d= -f2; }
e1=$(evals --pipeline "$root/pipelines/ris.json" --set ris_candidates=8 --set ris_samples=1)
e2=$(evals --pipeline "$root/pipelines/ris.json" --set ris_candidates=8 --set ris_samples=2)
[ -n "$e1" ] && [ "$e1" -gt 0 ] && [ $((e1 % 8)) -eq 0 ] && [ "$e2" -eq $((2 * e1)) ] && [ "$e1" -le $((8 * 64 * 36)) ] \
  && ok || bad "ris light_evals: $e1, $e2"
t1=$(evals --pipeline "$root/pipelines/visibility.json")
t0=$(evals --pipeline "$root/pipelines/visibility.json" --set tile_lights=false)
[ -n "$t1" ] && [ -n "$t0" ] && [ "$t1" -gt 0 ] && [ "$t1" -lt "$t0" ] && ok || bad "visibility light_evals: tiled $t1, per pixel $t0"
# lightcut with one bucket over every light, each in reach of every pixel: every pixel evaluates
# each of its 65 lights once (the tree's 63 padding leaves up to 128 were evaluated and counted too)
l1=$(evals --pipeline "$root/pipelines/lightcut.json" --lights 65 --radius 100 --set lightcut_bucket=256)
[ "$l1" = $((65 * 64 * 36)) ] && ok || bad "lightcut light_evals: $l1, want $((65 * 64 * 36))"
"$PG" bench --pipelines all --lights 16 --size 64x36 --frames 1 --warmup 0 --sweep gbuffer=float,packed \
  --out "$tmp/bench2" >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "bench --sweep: exit $rc"; cat "$tmp/err"; else ok; fi
rows=$(($(wc -l <"$tmp/bench2/results.csv" 2>/dev/null || echo 0) - 1))
[ "$rows" -eq $((n_pipes + n_gbuf)) ] && ok || bad "bench --sweep: $rows rows, want $((n_pipes + n_gbuf))"
for v in gbuffer=float gbuffer=packed; do
  [ "$(grep -c ",$v," "$tmp/bench2/results.csv")" -eq "$n_gbuf" ] && ok || bad "bench --sweep: want $n_gbuf rows of variant $v"
done
# above --reference-max-lights the error columns are empty and say why; the reference's own row is skipped
"$PG" bench --pipelines naive,forward_plus --reference "$naive" --lights 4,8 --reference-max-lights 4 --size 32x18 \
  --frames 1 --warmup 0 --out "$tmp/bench3" >"$tmp/out" 2>"$tmp/err" && ok || { bad "bench --reference-max-lights: exit"; cat "$tmp/err"; }
grep -q '^default,forward_plus,,,8,.*,ok,.*,naive skipped above 4 lights (--reference-max-lights 4),' "$tmp/bench3/results.csv" \
  && grep -q '^default,naive,,,8,.*,skipped,' "$tmp/bench3/results.csv" && ok || { bad "bench: reference skip not reported"; cat "$tmp/bench3/results.csv"; }
# a row that did not run counts no grow events in results.json either (null, as the CSV's empty cell)
python3 -c "import json,sys; rows=json.load(open(sys.argv[1]))['rows']; sys.exit(0 if all((r['grow_events'] is None) == (r['status'] == 'skipped') for r in rows) else 1)" \
  "$tmp/bench3/results.json" && ok || bad "bench: grow_events of a skipped row is not null in results.json"
python3 -c 'import csv,sys; r=[x for x in csv.DictReader(open(sys.argv[1])) if x["lights"] == "4"]; assert len(r) == 2 and all(x["status"] == "ok" and x["rmse_linear"] != "" and x["error_note"] == "" for x in r), r' \
  "$tmp/bench3/results.csv" && ok || bad "bench: rows at the limit must have their error measured"
grep -q 'deprecated' "$tmp/err" && bad "bench: a deprecation warning without --naive-max-lights" || ok
python3 -c 'import json,sys; m=json.load(open(sys.argv[1]))["meta"]["reference_max_lights"]; assert m["source"] == "--reference-max-lights" and m["by_size"] == {"32x18": 4}, m' \
  "$tmp/bench3/results.json" && ok || bad "bench results.json: meta reference_max_lights"
# --naive-max-lights: the old name still works, with one warning line
"$PG" bench --pipelines naive,forward_plus --reference "$naive" --lights 8 --naive-max-lights 4 --naive-max-lights 4 --size 32x18 \
  --frames 1 --warmup 0 --quiet --out "$tmp/bench3b" >"$tmp/out" 2>"$tmp/err" && ok || { bad "bench --naive-max-lights: exit"; cat "$tmp/err"; }
grep -q '^default,forward_plus,.*,ok,.*naive skipped above 4 lights' "$tmp/bench3b/results.csv" \
  && grep -q '^default,naive,.*,skipped,' "$tmp/bench3b/results.csv" && ok || { bad "bench: --naive-max-lights skip not reported"; cat "$tmp/bench3b/results.csv"; }
[ "$(grep -c 'warning: --naive-max-lights is deprecated; use --reference-max-lights' "$tmp/err")" -eq 1 ] \
  && ok || { bad "bench --naive-max-lights: want exactly one deprecation warning"; cat "$tmp/err"; }
# the default limit: 1,000,000 lights on a GPU; on a CPU device a light x pixel budget (555 lights at 1920x1080)
"$PG" bench --pipelines deferred_packed --reference "$naive" --lights 556 --size 1920x1080 --frames 1 --warmup 0 --quiet \
  --out "$tmp/bench3c" >"$tmp/out" 2>"$tmp/err" && ok || { bad "bench default reference limit: exit"; cat "$tmp/err"; }
if "$PG" devices 2>/dev/null | head -n 1 | grep -q '(cpu,'; then
  python3 -c 'import csv,sys,re; r=list(csv.DictReader(open(sys.argv[1]))); assert len(r) == 1 and r[0]["status"] == "ok" and r[0]["rmse_linear"] == "" and re.fullmatch(r"naive skipped above 555 lights on a CPU device \(.+\) at 1920x1080, the default budget .*: set --reference-max-lights", r[0]["error_note"]), r' \
    "$tmp/bench3c/results.csv" && ok || { bad "bench on a CPU device: default reference limit note"; cat "$tmp/bench3c/results.csv"; }
  grep -q 'no error measured: naive skipped above 555 lights on a CPU device' "$tmp/bench3c/error_vs_time.svg" \
    && ok || bad "bench: the error chart does not say why no error was measured"
else
  python3 -c 'import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); assert r[0]["rmse_linear"] != "", r' "$tmp/bench3c/results.csv" \
    && ok || bad "bench on a GPU: 556 lights are under the default reference limit (1000000)"
fi
# bench follows the same rule as compare: --set and swept values reach the reference when it declares the key
bench_sides() { # bench_sides DIR args...: forward_plus against naive at 64x36, 64 lights
  local d=$1
  shift
  "$PG" bench --pipelines forward_plus --reference "$naive" --lights 64 --size 64x36 --frames 1 --warmup 0 --quiet \
    --out "$d" "$@" >"$tmp/out" 2>"$tmp/err"
}
# bench_rows FILE 'python condition on row x': every row of results.csv satisfies it (and there is one)
bench_rows() { python3 -c 'import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); x=None; assert r and all(eval(sys.argv[2]) for x in r), r' "$1" "$2"; }
bench_sides "$tmp/bench6" --set shading=blinn_phong && ok || { bad "bench --set shading: exit"; cat "$tmp/err"; }
bench_rows "$tmp/bench6/results.csv" 'x["sets"] == "shading=blinn_phong" and x["reference_sets"] == "shading=blinn_phong" and float(x["rmse_linear"]) < 1e-6 and float(x["share_over_1"]) == 0' \
  && ok || { bad "bench --set shading=blinn_phong: the reference must take it (error ~0)"; cat "$tmp/bench6/results.csv"; }
grep -q "^bench: sides: pipeline=forward_plus pipeline_path=$fplus pipeline_sets=shading=blinn_phong sweeps=none reference=naive reference_path=$naive reference_sets=shading=blinn_phong\$" "$tmp/out" \
  && ok || { bad "bench: sides header line"; cat "$tmp/out"; }
python3 -c 'import json,sys; m=json.load(open(sys.argv[1]))["meta"]; s=m["sides"]; assert m["sets"] == {"shading": "blinn_phong"} and s == [{"pipeline": "forward_plus", "pipeline_path": sys.argv[2], "pipeline_sets": "shading=blinn_phong", "reference_sets": ["shading=blinn_phong"], "reference": "naive", "reference_path": sys.argv[3]}], m' \
  "$tmp/bench6/results.json" "$fplus" "$naive" && ok || bad "bench results.json: meta sides"
bench_sides "$tmp/bench7" --pipeline-set shading=blinn_phong && ok || { bad "bench --pipeline-set: exit"; cat "$tmp/err"; }
bench_rows "$tmp/bench7/results.csv" 'x["sets"] == "shading=blinn_phong" and x["reference_sets"] == "" and float(x["rmse_linear"]) > 1e-3 and float(x["share_over_1"]) > 0.05' \
  && ok || { bad "bench --pipeline-set shading=blinn_phong: want a large error against a Lambert reference"; cat "$tmp/bench7/results.csv"; }
bench_sides "$tmp/bench8" --sweep shading=lambert,blinn_phong && ok || { bad "bench --sweep shading: exit"; cat "$tmp/err"; }
bench_rows "$tmp/bench8/results.csv" 'x["reference_sets"] == x["variant"] and float(x["rmse_linear"]) < 1e-6' \
  && [ "$(grep -c ',shading=blinn_phong,' "$tmp/bench8/results.csv")" -ge 1 ] \
  && ok || { bad "bench --sweep shading: the reference must follow the swept value"; cat "$tmp/bench8/results.csv"; }
grep -q "sweeps=shading .*reference_sets=shading=lambert|shading=blinn_phong\$" "$tmp/out" && ok || { bad "bench --sweep: sides header"; cat "$tmp/out"; }
bench_sides "$tmp/bench9" --sweep shading=lambert,blinn_phong --reference-set shading=lambert && ok || { bad "bench --sweep + --reference-set: exit"; cat "$tmp/err"; }
bench_rows "$tmp/bench9/results.csv" 'x["reference_sets"] == "shading=lambert" and (float(x["rmse_linear"]) < 1e-6) == (x["variant"] == "shading=lambert")' \
  && ok || { bad "bench: --reference-set pins the reference under a sweep"; cat "$tmp/bench9/results.csv"; }
bench_sides "$tmp/bench10" --set shading=blinn_phong --debug-view albedo && ok || { bad "bench --debug-view: exit"; cat "$tmp/err"; }
bench_rows "$tmp/bench10/results.csv" 'x["sets"] == "shading=blinn_phong;view=albedo" and x["reference_sets"] == "shading=blinn_phong"' \
  && ok || { bad "bench --debug-view: the pipeline's only"; cat "$tmp/bench10/results.csv"; }
expect_fail "bench: --reference-set of an undeclared key" "--reference-set gbuffer=packed: the reference naive" \
  bench --pipelines forward_plus --reference "$naive" --reference-set gbuffer=packed --out "$tmp/b5"
expect_fail "bench: --pipeline-set no pipeline declares" "--pipeline-set gbuffer=packed: no selected pipeline" \
  bench --pipelines forward_plus --reference "$naive" --pipeline-set gbuffer=packed --out "$tmp/b5"
# a reference that does not load is an option error (every row's error was empty, exit 0); a bare
# name is a shipped pipeline, as in --pipelines
"$PG" bench --pipelines naive --reference "$tmp/no_such_ref.json" --lights 4 --size 64x36 --frames 1 --warmup 0 \
  --out "$tmp/b6" >/dev/null 2>"$tmp/err"
[ $? = 2 ] && grep -qF -- "--reference: pipeline '$tmp/no_such_ref.json': cannot open" "$tmp/err" && ok \
  || { bad "bench: a reference that does not load: want exit 2"; cat "$tmp/err"; }
"$PG" bench --pipelines visibility --reference naive --lights 4 --size 64x36 --frames 1 --warmup 0 --quiet \
  --out "$tmp/b6" >/dev/null 2>"$tmp/err" && python3 -c '
import csv, json, sys
assert json.load(open(sys.argv[1]))["meta"]["reference_path"].endswith("pipelines/naive.json")
assert list(csv.DictReader(open(sys.argv[2])))[0]["rmse_linear"] != ""' "$tmp/b6/results.json" "$tmp/b6/results.csv" \
  && ok || { bad "bench --reference naive: not the shipped naive.json"; cat "$tmp/err"; }
expect_fail "bench: a swept value the reference refuses" "--sweep view=cluster_heat: reference" \
  bench --pipelines forward_plus --reference "$naive" --sweep view=none,cluster_heat --out "$tmp/b5"
# a value the pipeline refuses is an option error naming the option (it ran, failed the row and said --set)
expect_fail "bench: a swept value the pipeline refuses" "--sweep tile_size=12: pipeline $root/pipelines/visibility.json: int parameter 'tile_size': 12 is not one of: 8, 16" \
  bench --pipelines visibility --sweep tile_size=8,12 --out "$tmp/b5"
"$PG" bench --pipelines visibility --pipeline-set tile_size=9 --out "$tmp/b5" >/dev/null 2>&1
[ $? -eq 2 ] && ok || bad "bench --pipeline-set tile_size=9: not exit 2"
expect_fail "bench: --sweep and --pipeline-set of one key" "the same key is given with --pipeline-set" \
  bench --pipelines forward_plus --sweep shading=lambert --pipeline-set shading=lambert --out "$tmp/b5"
expect_fail "bench: bad --reference-max-lights" "--reference-max-lights x" bench --reference-max-lights x --out "$tmp/b5"
# a pipeline that does not load is reported in its row; the others still run; exit 1
echo '{"name": "broken", "passes": [' >"$tmp/broken.json"
"$PG" bench --pipelines "$tmp/broken.json",naive --lights 4 --size 32x18 --frames 1 --warmup 0 --out "$tmp/bench4" \
  >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q '^default,broken,.*,error,' "$tmp/bench4/results.csv" && grep -q '^default,naive,.*,ok,' "$tmp/bench4/results.csv" \
  && ok || { bad "bench: broken pipeline not reported in its row"; cat "$tmp/err"; }
expect_fail "bench: size 0x0" "--size width 0" bench --size 0x0 --out "$tmp/b5"
# a pipeline or scene listed twice (by name and by path) runs once, as a repeated light count does;
# a missing pipeline's row names the file tried
"$PG" bench --pipelines naive,"$root/pipelines/naive.json",nosuch --scene default,default --lights 4,4 --size 16x9 \
  --frames 1 --warmup 0 --flicker-frames 0 --out "$tmp/bdup" >"$tmp/out" 2>"$tmp/err"
[ "$(grep -c '^default,naive,' "$tmp/bdup/results.csv")" = 1 ] && grep -q "'$root/pipelines/naive.json' is listed twice: run once" "$tmp/err" \
  && grep -q "'default' is listed twice: run once" "$tmp/err" \
  && grep -q "^default,nosuch,.*,error,pipeline '$root/pipelines/nosuch.json': cannot open" "$tmp/bdup/results.csv" && ok \
  || { bad "bench: duplicates not run once, or a missing pipeline's row without its path"; cat "$tmp/err" "$tmp/bdup/results.csv"; }
# a scene that does not load fails its rows, counted, exit 1 (it said "0 failed" and exited 0); the
# other scenes still run
"$PG" bench --pipelines naive --scene default,"$tmp/no_scene.gltf" --lights 4 --size 16x9 --frames 1 --warmup 0 \
  --flicker-frames 0 --out "$tmp/bscene" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc = 1 ] && grep -q "2 rows (1 failed)" "$tmp/out" \
  && grep -q "^default,naive,.*,ok," "$tmp/bscene/results.csv" && grep -q "no_scene.gltf,naive,.*,error," "$tmp/bscene/results.csv" && ok \
  || { bad "bench: a scene that does not load: want its row failed, counted and exit 1 (exit $rc)"; cat "$tmp/out" "$tmp/err"; }
expect_fail "bench: --frames-in-flight 0" "--frames-in-flight 0: expected a whole number in [1, 2]" bench --frames-in-flight 0 --out "$tmp/b5"
expect_fail "bench: bad light list" "--lights -5" bench --lights 100,-5 --out "$tmp/b5"
expect_fail "bench: no --out" "--out DIR" bench --lights 4
expect_fail "bench: sweep of an undeclared key" "no_such_key" bench --sweep no_such_key=1,2 --out "$tmp/b5"
expect_fail "bench: sweep without values" "KEY=VALUE1" bench --sweep gbuffer --out "$tmp/b5"
expect_fail "bench: a swept value twice" "value 'float' given twice" bench --sweep gbuffer=float,float --out "$tmp/b5"
expect_fail "bench: a swept number twice in two forms" "--sweep exposure: value '1.0' given twice (as '1')" \
  bench --sweep exposure=1,1.0 --out "$tmp/b5"
expect_fail "bench: unknown option" "unknown option" bench --bogus --out "$tmp/b5"
[ ! -e "$tmp/b5" ] && ok || bad "bench: bad options created the output folder"

# ---- default framing, lights and glTF cameras (tests/corpus/gltf/objects) ----
objs="$root/tests/corpus/gltf/objects"
# a scenario that moves the camera without near/far: the planes are fitted again from the new position
# (the default view's, fitted at its own distance, cut the cube off: a black frame)
printf '{"camera": {"position": [0, 0, 12], "target": [0, 0, 0]}}\n' >"$tmp/sc_far.json"
"$PG" render --scene "$objs/cube.gltf" --scenario "$tmp/sc_far.json" --size 64x36 --environment none --ambient 0.5 \
  --out "$tmp/sc_far.png" >"$tmp/out" 2>"$tmp/err" \
  && python3 "$root/tests/cli/png_stats.py" "$tmp/sc_far.png" | awk '{ exit !($3 > 0.002) }' && ok \
  || { bad "a scenario camera without near/far: the object is cut off"; cat "$tmp/err"; }
camline() { "$PG" render --size 64x36 --lights 8 --explain --out "$tmp/c.png" "$@" 2>"$tmp/cerr" | grep -E '^explain: (camera|lights):'; }
camline >"$tmp/cl" && grep -q "^explain: camera: interior view of the built-in atrium" "$tmp/cl" && \
  grep -q "^explain: lights: generated point lights, interior box" "$tmp/cl" && ok || { bad "atrium: camera/lights lines"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/cube.gltf" >"$tmp/cl" && \
  grep -q "^explain: camera: auto framing (object, no glTF camera: bounds radius 0.866, distance 2.01" "$tmp/cl" && \
  grep -q "^explain: lights: generated point lights, object box (bounds grown by 0.6 x radius per side, none within 0.15 x radius of the bounds), radius 1.3, intensity 0.336, ambient 0.02; ambient 0 (the environment light instead)$" "$tmp/cl" && ok || { bad "cube: camera/lights lines"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/cube.gltf" --ambient 0 >"$tmp/cl" && grep -q "^explain: lights: generated point lights, object box.*; ambient 0 from --ambient$" "$tmp/cl" \
  && ok || { bad "cube --ambient 0: lights line"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/camera.gltf" >"$tmp/cl" && grep -q "^explain: camera: glTF camera 0 'front' (node 'front_node', perspective), the scene's first camera" "$tmp/cl" \
  && ok || { bad "camera.gltf: default camera line"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/camera.gltf" --camera auto >"$tmp/cl" && grep -q "^explain: camera: auto framing (--camera auto" "$tmp/cl" \
  && ok || { bad "camera.gltf --camera auto"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/two_cameras.gltf" --camera side_node >"$tmp/cl" && grep -q "^explain: camera: glTF camera 0 'side' (node 'side_node', perspective), selected by --camera side_node" "$tmp/cl" \
  && ok || { bad "two_cameras --camera side_node"; cat "$tmp/cl" "$tmp/cerr"; }
camline --scene "$objs/cube.gltf" --scenario "$root/assets/scenarios/cis565.json" >"$tmp/cl" && \
  grep -q "^explain: camera: scenario .*cis565.json" "$tmp/cl" && grep -q "^explain: lights: generated point lights, scenario .*cis565.json" "$tmp/cl" \
  && ok || { bad "scenario camera/lights lines"; cat "$tmp/cl" "$tmp/cerr"; }
# a scenario's lights.count and lights.seed (without --lights/--seed): the seed was never used, and
# --explain gave the intensity of the default count
printf '{"lights": {"count": 20, "seed": 7}}\n' >"$tmp/sc_seed7.json"
printf '{"lights": {"count": 20, "seed": 1}}\n' >"$tmp/sc_seed1.json"
for s in 1 7; do
  "$PG" render --scene "$objs/cube.gltf" --scenario "$tmp/sc_seed$s.json" --size 64x36 --explain --out "$tmp/sc$s.png" \
    >"$tmp/sc$s.out" 2>/dev/null || bad "scenario seed $s: render"
done
"$PG" render --scene "$objs/cube.gltf" --lights 20 --seed 7 --environment none --size 64x36 --out "$tmp/l20s7.png" >/dev/null 2>&1
cmp -s "$tmp/sc7.png" "$tmp/l20s7.png" && ! cmp -s "$tmp/sc1.png" "$tmp/sc7.png" && ok \
  || bad "a scenario's lights.seed: want the image of --lights 20 --seed 7 --environment none (a scenario brings no environment), unlike seed 1's"
"$PG" render --scene "$objs/cube.gltf" --lights 20 --seed 7 --size 64x36 --explain --out "$tmp/l20s7.png" 2>/dev/null \
  | grep -o 'intensity [0-9.e+-]*' | head -1 >"$tmp/want_i"
grep -q "^explain: lights: .*$(cat "$tmp/want_i"), .*; count and seed from scenario .*sc_seed7.json" "$tmp/sc7.out" && ok \
  || { bad "a scenario's count: --explain names it with that count's intensity ($(cat "$tmp/want_i"))"; grep lights: "$tmp/sc7.out"; }
# bench takes a scenario's count and seed as render does (its rows were 100/1000/5000 lights, seed 1)
"$PG" bench --scene "$objs/cube.gltf" --scenario "$tmp/sc_seed7.json" --pipelines naive --size 32x18 --frames 1 \
  --warmup 0 --quiet --out "$tmp/bsc" >/dev/null 2>"$tmp/err" \
  && [ "$(cut -d, -f5,13 "$tmp/bsc/results.csv" | tail -n +2)" = "20,7" ] && ok \
  || { bad "bench --scenario: its lights.count and lights.seed"; cat "$tmp/err"; cut -d, -f5,13 "$tmp/bsc/results.csv"; }
# --explain names the shading model and the environment; a file with several glTF scenes gets a
# line, --gltf-scene picks one, out of range is an error naming the count
"$PG" render --size 64x36 --lights 8 --explain --scene "$objs/two_scenes.gltf" --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "^explain: shading: auto -> pbr (the glTF metallic-roughness BRDF) (a glTF file's materials)$" "$tmp/cl" && grep -q "^explain: environment: the neutral default sky, mean radiance 0.25 (a glTF file without lights)" "$tmp/cl" &&
  grep -q "^explain: scene: .*two_scenes.gltf has 2 scenes; drawing scene 0 'small' (the file's default); --gltf-scene N draws another$" "$tmp/cl" &&
  grep -q "^passgraph: .*two_scenes.gltf has 2 scenes; drawing scene 0 'small'" "$tmp/cerr" \
  && ok || { bad "two_scenes: explain shading/environment/scene lines"; cat "$tmp/cl" "$tmp/cerr"; }
# without a "scene" key the first is drawn, and the line says the file names no default
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d.pop('scene'); json.dump(d, open(sys.argv[2], 'w'))" \
  "$objs/two_scenes.gltf" "$tmp/no_default.gltf"
"$PG" render --size 16x9 --lights 4 --scene "$tmp/no_default.gltf" --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr" &&
  grep -q "drawing scene 0 'small' (the first: the file names no default scene)" "$tmp/cerr" \
  && ok || { bad "a file without a default scene: the line says it is the file's default"; cat "$tmp/cerr"; }
# the environment light: --environment none / FILE.hdr (a flat RGBE file written here) / errors naming
# the file and the cause, exit 1
"$PG" render --size 64x36 --lights 8 --explain --scene "$objs/two_scenes.gltf" --environment none --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "^explain: environment: none (--environment none)" "$tmp/cl" && grep -q "filter_environment.*no environment light" "$tmp/cl" \
  && ok || { bad "--environment none"; cat "$tmp/cl" "$tmp/cerr"; }
python3 - "$tmp/sky.hdr" "$tmp/tall.hdr" "$tmp/cut.hdr" <<'PYEOF'
import sys
def hdr(path, w, h, px, cut=False):
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
    body = bytes(px * (w * h))
    open(path, "wb").write(head + (body[: len(body) // 2] if cut else body))
hdr(sys.argv[1], 16, 8, [128, 128, 160, 129])
hdr(sys.argv[2], 8, 16, [128, 128, 128, 129])
hdr(sys.argv[3], 16, 8, [128, 128, 128, 129], cut=True)
PYEOF
"$PG" render --size 64x36 --lights 8 --explain --scene "$objs/two_scenes.gltf" --environment "$tmp/sky.hdr" --environment-intensity 2 --environment-rotation 90 --validation --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "^explain: environment: .*sky.hdr, 16x8, 4 levels (--environment); intensity 2, rotation 90 deg" "$tmp/cl" \
  && ok || { bad "--environment FILE.hdr"; cat "$tmp/cl" "$tmp/cerr"; }
# an OpenEXR environment: an HDR image passgraph itself wrote at 2:1; one that is not 2:1 is refused
"$PG" render --size 32x16 --lights 16 --out "$tmp/env.exr" >/dev/null 2>&1 &&
  "$PG" render --size 64x36 --lights 8 --explain --scene "$objs/two_scenes.gltf" --environment "$tmp/env.exr" --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "^explain: environment: .*env.exr, 32x16, 5 levels (--environment)" "$tmp/cl" \
  && ok || { bad "--environment FILE.exr"; cat "$tmp/cl" "$tmp/cerr"; }
"$PG" render --size 32x18 --lights 16 --out "$tmp/env_wide.exr" >/dev/null 2>&1
"$PG" render --size 64x36 --scene "$objs/two_scenes.gltf" --environment "$tmp/env_wide.exr" --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr"
[ $? -eq 1 ] && grep -q "env_wide.exr: 32 x 18: an equirectangular environment is 2:1" "$tmp/cerr" && ok || { bad "--environment not-2:1.exr"; cat "$tmp/cerr"; }
for bad_env in "$tmp/missing.hdr:cannot open" "$tmp/tall.hdr:2:1" "$tmp/cut.hdr:truncated" "$root/README.md:not a Radiance HDR file"; do
  f="${bad_env%%:*}"; why="${bad_env#*:}"
  "$PG" render --size 64x36 --scene "$objs/two_scenes.gltf" --environment "$f" --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr"
  [ $? -eq 1 ] && grep -q "$(basename "$f").*$why" "$tmp/cerr" && ok || { bad "--environment $f: expected '$why'"; cat "$tmp/cerr"; }
done
"$PG" render --size 64x36 --lights 8 --explain --scene "$objs/two_scenes.gltf" --gltf-scene 1 --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "drawing scene 1 'big' (--gltf-scene)" "$tmp/cl" && ok || { bad "--gltf-scene 1"; cat "$tmp/cl" "$tmp/cerr"; }
"$PG" render --size 64x36 --scene "$objs/two_scenes.gltf" --gltf-scene 2 --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr"
[ $? -eq 1 ] && grep -q "two_scenes.gltf: --gltf-scene 2: out of range (the file has 2 scenes: 0 'small', 1 'big')" "$tmp/cerr" \
  && ok || { bad "--gltf-scene out of range"; cat "$tmp/cerr"; }
"$PG" render --size 64x36 --gltf-scene 0 --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr"
[ $? -eq 1 ] && grep -q "the built-in atrium is not a glTF file" "$tmp/cerr" && ok || { bad "--gltf-scene on the atrium"; cat "$tmp/cerr"; }
# KHR_materials_variants: a line lists the variants, --variant NAME draws one (explain says so), an
# unknown name is an error listing them
shoe="$root/tests/corpus/gltf/variants/shoe.gltf"
"$PG" render --size 64x36 --scene "$shoe" --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr" &&
  grep -q "^passgraph: .*shoe.gltf has 3 material variants (0 'red', 1 'blue', 2 'midnight'); drawing the default materials; --variant N|NAME draws one$" "$tmp/cerr" \
  && ok || { bad "variants line"; cat "$tmp/cerr"; }
"$PG" render --size 64x36 --explain --scene "$shoe" --variant midnight --out "$tmp/c.png" >"$tmp/cl" 2>"$tmp/cerr" &&
  grep -q "^explain: scene: .*drawing variant 2 'midnight' (--variant)$" "$tmp/cl" && ok || { bad "--variant midnight"; cat "$tmp/cl" "$tmp/cerr"; }
"$PG" render --size 64x36 --scene "$shoe" --variant green --out "$tmp/c.png" >/dev/null 2>"$tmp/cerr"
[ $? -eq 1 ] && grep -q "shoe.gltf: --variant 'green': not a variant of the file (3: 0 'red', 1 'blue', 2 'midnight')" "$tmp/cerr" \
  && ok || { bad "--variant green"; cat "$tmp/cerr"; }
# lights-table: N generated lights frozen into a file, as a binary table and as KHR_lights_punctual
# JSON: the two render the same image; the output may sit in another folder (relative buffer
# URIs rewritten); bad options exit 2
lt="$root/tests/corpus/gltf/lights/rgb_points.gltf"
mkdir -p "$tmp/lt/sub"
"$PG" lights-table --scene "$lt" --lights 200 --out "$tmp/lt/t.gltf" >/dev/null &&
  "$PG" lights-table --scene "$lt" --lights 200 --json --out "$tmp/lt/j.gltf" >/dev/null &&
  [ -s "$tmp/lt/t.lights.bin" ] && [ "$(stat -c %s "$tmp/lt/t.lights.bin")" -eq 6400 ] &&
  "$PG" render --scene "$tmp/lt/t.gltf" --size 64x36 --explain --out "$tmp/lt/t.png" >"$tmp/lt/t.txt" 2>&1 &&
  "$PG" render --scene "$tmp/lt/j.gltf" --size 64x36 --out "$tmp/lt/j.png" >/dev/null 2>&1 &&
  cmp -s "$tmp/lt/t.png" "$tmp/lt/j.png" &&
  grep -q "^explain: lights: the file's 203 lights (203 point, 0 spot, 0 directional)$" "$tmp/lt/t.txt" \
  && ok || { bad "lights-table: table and JSON renders differ or failed"; cat "$tmp/lt/t.txt"; }
"$PG" lights-table --scene "$root/tests/corpus/gltf/compressed/q_s16.gltf" --lights 10 --out "$tmp/lt/sub/q.gltf" \
  >/dev/null 2>"$tmp/err" && grep -q '"uri":"\.\./' "$tmp/lt/sub/q.gltf" &&
  "$PG" render --scene "$tmp/lt/sub/q.gltf" --size 32x18 --out "$tmp/lt/q.png" >/dev/null 2>&1 \
  && ok || { bad "lights-table: output in another folder"; cat "$tmp/err"; }
# bench on a scene with its own lights: without --lights one block of those lights alone; with
# --lights the generated ones are added (the lights column counts every light rendered)
"$PG" bench --scene "$lt" --pipelines "$root/pipelines/naive.json" --size 32x18 --frames 1 --warmup 0 --no-hdr-flip \
  --out "$tmp/lt/b" 2>&1 | grep -c "^bench: naive .* lights=3 ok" | grep -qx 1 &&
  "$PG" bench --scene "$lt" --pipelines "$root/pipelines/naive.json" --size 32x18 --frames 1 --warmup 0 --no-hdr-flip \
    --lights 10 --out "$tmp/lt/b2" 2>&1 | grep -q "^bench: naive .* lights=13 ok" \
  && ok || bad "bench on a scene with its own lights"
expect_fail "lights-table without --out" "--scene IN.gltf and --out OUT.gltf are required" lights-table --scene "$lt"
expect_fail "lights-table of a .glb" "must be .gltf files" lights-table --scene "$root/tests/corpus/gltf/models/crate.glb" \
  --out "$tmp/lt/x.gltf"
expect_fail "lights-table of a missing file" "cannot open" lights-table --scene "$tmp/lt/none.gltf" --out "$tmp/lt/x.gltf"
expect_fail "lights-table unknown option" "unknown option '--nope'" lights-table --nope
# no light, or lights of radius 0 (no light from them; a range of 0 in the file is an infinite reach):
# refused instead of a file that does not load, or one that lights the scene
expect_fail "lights-table --lights 0" "no light to write" lights-table --scene "$lt" --lights 0 --out "$tmp/lt/z.gltf"
expect_fail "lights-table --radius 0" "a radius of 0" lights-table --scene "$lt" --lights 4 --radius 0 --out "$tmp/lt/z.gltf"
[ ! -e "$tmp/lt/z.gltf" ] && [ ! -e "$tmp/lt/z.lights.bin" ] && ok || bad "lights-table: a refused table left files"
# a file that already holds a table (a second one replaced it: its lights were lost), the output
# being the input (a file whose buffer no longer matched), an output folder, lights past a file
# light's limits: refused, nothing written; --json joins the scene --gltf-scene names
expect_fail "lights-table of a file with a table" "already holds a PASSGRAPH_lights_table: a file has one table" \
  lights-table --scene "$tmp/lt/t.gltf" --lights 4 --out "$tmp/lt/z.gltf"
cp "$lt" "$tmp/lt/inplace.gltf"
expect_fail "lights-table in place" "inplace.gltf is the input file: write the output to another file" \
  lights-table --scene "$tmp/lt/inplace.gltf" --lights 4 --out "$tmp/lt/inplace.gltf"
cmp -s "$lt" "$tmp/lt/inplace.gltf" && [ ! -e "$tmp/lt/inplace.lights.bin" ] && ok || bad "lights-table in place: the input changed"
mkdir -p "$tmp/lt/zdir.gltf"
expect_fail "lights-table --out a folder" "--out '$tmp/lt/zdir.gltf': cannot write: Is a directory" \
  lights-table --scene "$lt" --lights 4 --out "$tmp/lt/zdir.gltf"
printf '{"lights": {"count": 4, "intensity": 1e30}}\n' >"$tmp/lt/bright.json"
expect_fail "lights-table: an intensity a file light cannot have" "light 0: intensity 3.14159e+30 candela (pi x the generated intensity), over the 1e+30" \
  lights-table --scene "$lt" --scenario "$tmp/lt/bright.json" --out "$tmp/lt/z.gltf"
[ ! -e "$tmp/lt/z.gltf" ] && [ ! -e "$tmp/lt/z.lights.bin" ] && [ ! -e "$tmp/lt/zdir.lights.bin" ] && ok \
  || bad "lights-table: a refused table left files"
"$PG" lights-table --scene "$objs/two_scenes.gltf" --gltf-scene 1 --lights 4 --json --out "$tmp/lt/two_j.gltf" >/dev/null &&
  "$PG" lights-table --scene "$objs/two_scenes.gltf" --gltf-scene 1 --lights 4 --out "$tmp/lt/two_t.gltf" >/dev/null &&
  "$PG" render --scene "$tmp/lt/two_j.gltf" --gltf-scene 1 --size 32x18 --out "$tmp/lt/two_j.png" >/dev/null 2>&1 &&
  "$PG" render --scene "$tmp/lt/two_t.gltf" --gltf-scene 1 --size 32x18 --out "$tmp/lt/two_t.png" >/dev/null 2>&1 &&
  cmp -s "$tmp/lt/two_j.png" "$tmp/lt/two_t.png" && ok || bad "lights-table --json --gltf-scene 1: the lights join scene 1"
# the default render of a glTF with a camera is the render with that camera named
"$PG" render --size 64x36 --lights 8 --scene "$objs/camera.gltf" --out "$tmp/cam_default.png" >/dev/null 2>&1 &&
  "$PG" render --size 64x36 --lights 8 --scene "$objs/camera.gltf" --camera 0 --out "$tmp/cam_0.png" >/dev/null 2>&1 &&
  "$PG" render --size 64x36 --lights 8 --scene "$objs/camera.gltf" --camera auto --out "$tmp/cam_auto.png" >/dev/null 2>&1 &&
  cmp -s "$tmp/cam_default.png" "$tmp/cam_0.png" && ! cmp -s "$tmp/cam_default.png" "$tmp/cam_auto.png" \
  && ok || bad "camera.gltf: default render != --camera 0, or == --camera auto"
# the same camera with znear 1e-8 (zfar 100): the near plane is raised to 1e-6 x the
# distance of the scene's farthest point, and the cube
# is drawn as with znear 0.1 (every depth rounded to 1 in the depth buffer: nothing was drawn)
"$PG" render --size 64x36 --lights 8 --scene "$objs/camera_near_1e-8.gltf" --set background=none \
    --out "$tmp/cam_near.png" >/dev/null 2>&1 &&
  "$PG" render --size 64x36 --lights 8 --scene "$objs/camera.gltf" --set background=none \
    --out "$tmp/cam_near_ref.png" >/dev/null 2>&1 &&
  [ "$(python3 "$root/tests/cli/png_stats.py" "$tmp/cam_near.png" | cut -d' ' -f3)" = \
    "$(python3 "$root/tests/cli/png_stats.py" "$tmp/cam_near_ref.png" | cut -d' ' -f3)" ] &&
  python3 "$root/tests/cli/png_stats.py" "$tmp/cam_near.png" | awk '{ exit !($3 > 0.1) }' \
  && ok || bad "camera_near_1e-8.gltf: not drawn like camera.gltf ($(python3 "$root/tests/cli/png_stats.py" "$tmp/cam_near.png"))"
two="$objs/two_cameras.gltf"
expect_fail "unknown camera lists the cameras" "available: 0 'side' (node 'side_node'), 1 'top' (node 'top_node', orthographic), or auto" \
  render --scene "$two" --camera nope --size 32x18 --out "$tmp/x.png"
expect_fail "camera index out of range" "--camera 2: no such camera" render --scene "$two" --camera 2 --size 32x18 --out "$tmp/x.png"
# (stdout to a file: `| grep -q` would exit at the first match and a later write would kill the render
# by SIGPIPE before it wrote the PNG; that failed once under ASan)
"$PG" render --scene "$two" --camera top --size 32x18 --lights 8 --explain --out "$tmp/top.png" >"$tmp/cout" \
  2>"$tmp/cerr" && grep -q "^explain: camera: glTF camera 1 'top' (node 'top_node', orthographic), selected by --camera top" \
  "$tmp/cout" && [ -s "$tmp/top.png" ] && ok || { bad "orthographic camera: render"; cat "$tmp/cerr"; }
expect_fail "camera on a file without cameras" "has no cameras; use --camera auto" \
  render --scene "$objs/cube.gltf" --camera 0 --size 32x18 --out "$tmp/x.png"
expect_fail "camera on the atrium" "has no cameras" render --camera 0 --size 32x18 --out "$tmp/x.png"
expect_fail "empty camera" "--camera: empty name" render --camera "" --size 32x18 --out "$tmp/x.png"
expect_fail "camera without value" "--camera: missing value" render --camera
expect_fail "compare: unknown camera" "no such camera" compare --scene "$two" --camera nope --size 32x18
expect_fail "dump: unknown camera" "no such camera" dump --scene "$two" --camera nope
expect_fail "bench: unknown camera" "no such camera" bench --scene "$two" --camera nope --size 32x18 --frames 1 --out "$tmp/b_cam"
# the reference under the neutral sky: no pixel black. A NaN its Monte Carlo made (pow(1 - V.H, 5)
# with V.H rounded past 1 where the sampled light is the view direction) was turned into black by the
# output's sanitizing: pixel (53, 10) of this render, at the default seed
"$PG" render --scene "$root/tests/corpus/gltf/objects/cube.gltf" --pipeline "$root/pipelines/reference.json" \
  --size 160x90 --out "$tmp/ref_sky.png" >/dev/null 2>"$tmp/ref_sky.err" \
  && python3 "$root/tests/cli/png_stats.py" "$tmp/ref_sky.png" | awk '{ exit !($3 == 1.0000) }' && ok \
  || { bad "reference of cube.gltf under the sky: a black pixel ($(python3 "$root/tests/cli/png_stats.py" "$tmp/ref_sky.png" 2>&1))"; cat "$tmp/ref_sky.err"; }
# with PASSGRAPH_KEEP_NAN=1 the shaders store the NaNs they compute (no sanitizing to 0), so
# nonfinite counts them: none in any pipeline here (that NaN gave nonfinite=1 this way)
for p in "$root"/pipelines/*.json; do
  sz=96x54; [ "$(basename "$p")" = reference.json ] && sz=160x90
  PASSGRAPH_KEEP_NAN=1 "$PG" render --scene "$root/tests/corpus/gltf/objects/cube.gltf" --pipeline "$p" --size $sz \
    --out "$tmp/nan.png" >"$tmp/nan.out" 2>&1 && grep -q ' nonfinite=0 ' "$tmp/nan.out" && ok \
    || { bad "PASSGRAPH_KEEP_NAN=1 $(basename "$p"): a NaN or a failure"; cat "$tmp/nan.out"; }
done
# an output of 4 bytes a pixel that is not 8-bit RGBA (d32f) was written as a PNG of garbage, exit 0
sed "s#\"fragments/#\"$root/pipelines/fragments/#g; s#\"output\": \"ldr\"#\"output\": \"depth\"#" "$root/pipelines/naive.json" >"$tmp/out_depth.json"
# an --out past the path limit was cut to a prefix (another file, written); the same for the
# lights-table's OUT.lights.bin beside its --out
long_dir="$tmp/$(printf 'd%.0s' $(seq 300))"
"$PG" render --size 32x18 --out "$long_dir/$(printf 'a%.0s' $(seq 206)).png.png" >/dev/null 2>"$tmp/err"
[ $? = 2 ] && grep -q "path too long" "$tmp/err" && ok || { bad "render: a too long --out: want exit 2"; cat "$tmp/err"; }
"$PG" lights-table --scene "$root/tests/corpus/gltf/ok_animation.gltf" --lights 4 \
  --out "$tmp/$(printf 'a%.0s' $(seq 530)).gltf" >/dev/null 2>"$tmp/err"
[ $? = 2 ] && grep -q "path longer than 511 bytes" "$tmp/err" && ok || { bad "lights-table: a too long --out: want exit 2"; cat "$tmp/err"; }
expect_fail "render: a d32f output" "output 'depth' must be an 8-bit RGBA image (rgba8 or rgba8_srgb) to write $tmp/x.png, not d32f" \
  render --pipeline "$tmp/out_depth.json" --size 16x9 --lights 4 --out "$tmp/x.png"
# deferred lighting into an hdr of another size than its G-buffer (without the background and
# transparent passes, whose attachment check caught it): a magnified corner or black, exit 0
mkdir -p "$tmp/dl" && cp -r "$root/pipelines/fragments" "$tmp/dl/" && cp "$root/pipelines/deferred_packed.json" "$tmp/dl/"
python3 -c '
import json, sys
p = sys.argv[1] + "/fragments/deferred_body.json"
d = json.load(open(p))
d["passes"] = [x for x in d["passes"] if x["name"] not in ("background", "transparent")]
for r in d["resources"]:
    if r["name"] == "hdr":
        r["scale"] = 0.5
json.dump(d, open(p, "w"))' "$tmp/dl"
expect_fail "deferred lighting: hdr of another size" "its output (8x5) and its G-buffer depth (16x9) differ in size" \
  render --pipeline "$tmp/dl/deferred_packed.json" --size 16x9 --lights 4 --out "$tmp/x.png"
# every shipped pipeline takes every value of its own parameters' lists (stochastic.json refused
# five of its views: its transparent pass, skipped under any view, checked them against "lights": "all")
for p in "$root"/pipelines/*.json; do
  while read -r kv; do
    "$PG" dump --pipeline "$p" --set "$kv" >/dev/null 2>"$tmp/kv.err" && ok \
      || { bad "$(basename "$p") --set $kv: refused"; head -2 "$tmp/kv.err"; }
  done < <(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
for k, v in d.get("parameters", {}).items():
    for x in v.get("values", []):
        print("%s=%s" % (k, x))' "$p")
done
# the ten object models (tests/corpus/gltf/models, gen_models.py): the committed files are what the
# generator writes; a render with default options (but the size) exits 0 and writes a PNG, and with
# the background left black (--set background=none: the neutral sky fills every other pixel) it is
# framed (3%..90% of the pixels not black; 0.04%..0.2% if framed from 10x the distance) and lit
# (mean 8-bit luma of those > 40; 43..108 measured, 12..33 with --lights 0, the object ambient
# alone); the desk lamp's own camera is its default view
models="$root/tests/corpus/gltf/models"
python3 "$models/gen_models.py" --out "$tmp/gen" >/dev/null && ok || bad "gen_models.py failed"
nmodels=0
for m in "$models"/*.gltf "$models"/*.glb; do
  n=$(basename "$m"); nmodels=$((nmodels + 1))
  cmp -s "$m" "$tmp/gen/$n" && ok || bad "model $n: committed file differs from gen_models.py's output"
  rm -f "$tmp/m.png" "$tmp/mstat"
  if "$PG" render --scene "$m" --size 96x54 --out "$tmp/m.png" >"$tmp/mout" 2>"$tmp/merr" && [ -s "$tmp/m.png" ] &&
     "$PG" render --scene "$m" --size 96x54 --set background=none --out "$tmp/m0.png" >>"$tmp/mout" 2>>"$tmp/merr" &&
     python3 "$root/tests/cli/png_stats.py" "$tmp/m0.png" >"$tmp/mstat" &&
     awk '{ exit !($1 == 96 && $2 == 54 && $3 >= 0.03 && $3 <= 0.9 && $4 > 40) }' "$tmp/mstat"; then ok
  else bad "model $n: default render failed or not framed/lit (W H cover mean: $(cat "$tmp/mstat" 2>/dev/null))"; cat "$tmp/merr"; fi
done
[ $nmodels -eq 11 ] && ok || bad "expected 11 models in $models, found $nmodels"
camline --scene "$models/desk_lamp.gltf" >"$tmp/cl" && \
  grep -q "^explain: camera: glTF camera 0 'product_shot' (node 'camera', perspective), the scene's first camera" "$tmp/cl" \
  && ok || { bad "desk_lamp.gltf: default camera line"; cat "$tmp/cl" "$tmp/cerr"; }
# ---- new-user mistakes: one clear line each ----
gcorp="$root/tests/corpus/gltf"
mkdir -p "$tmp/adir"
expect_fail "--scene is a directory" "scene '$tmp/adir': is a directory, not a regular file" \
  render --scene "$tmp/adir" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "--scenario is a directory" "scenario '$tmp/adir': is a directory, not a regular file" \
  render --scenario "$tmp/adir" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "--pipeline is a directory" "pipeline '$tmp/adir': is a directory, not a regular file" \
  render --pipeline "$tmp/adir" --size 32x18 --lights 4 --out "$tmp/x.png"
grep -q "out of memory" "$tmp/err" && bad "a directory still reads as 'out of memory'" || ok
expect_fail "--ocio-config is a directory" "OCIO config '$tmp/adir': is a directory, not a regular file" \
  render --ocio-config "$tmp/adir" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "compare --reference is a directory" "reference: pipeline '$tmp/adir': is a directory, not a regular file" \
  compare --reference "$tmp/adir" --size 32x18 --lights 4
expect_fail "--scene an OBJ file" "$gcorp/cube.obj: not a glTF 2.0 file (passgraph reads .gltf and .glb only)" \
  render --scene "$gcorp/cube.obj" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "--scene a glTF 1.0 file" "glTF 1.0 is not supported, only 2.0" \
  render --scene "$gcorp/version_1.gltf" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "--scene: an unsupported required extension" "extensionsRequired: 'EXT_made_up' is not supported (passgraph implements only these glTF extensions: EXT_mesh_gpu_instancing, EXT_meshopt_compression, EXT_texture_webp, KHR_draco_mesh_compression, KHR_lights_punctual, KHR_materials_emissive_strength, KHR_materials_unlit, KHR_materials_variants, KHR_mesh_quantization, KHR_texture_transform, PASSGRAPH_lights_table)" \
  render --scene "$gcorp/required_made_up.gltf" --size 32x18 --lights 4 --out "$tmp/x.png"
expect_fail "--out .bmp" "--out $tmp/x.bmp: unsupported image extension '.bmp' (accepted: .png, .jpg, .jpeg, .exr)" \
  render --size 32x18 --lights 4 --out "$tmp/x.bmp"
expect_fail "--out without extension" "--out $tmp/x: no file extension (accepted: .png, .jpg, .jpeg, .exr)" \
  render --size 32x18 --lights 4 --out "$tmp/x"
[ ! -e "$tmp/x.bmp" ] && [ ! -e "$tmp/x" ] && ok || bad "a refused --out extension wrote a file"
expect_fail "compare --heatmap .bmp" "--heatmap: $tmp/h.bmp: unsupported image extension '.bmp' (accepted: .png, .jpg, .jpeg)" \
  compare --reference "$naive" --size 32x18 --lights 4 --heatmap "$tmp/h.bmp"
expect_fail "view --screenshot .bmp" "--screenshot $tmp/s.bmp: unsupported image extension '.bmp' (accepted: .png, .jpg, .jpeg)" \
  view --frames 1 --screenshot "$tmp/s.bmp"
expect_fail "view --at N:screenshot=.tga" "unsupported image extension '.tga'" view --frames 2 --at 1:screenshot="$tmp/s.tga"
# --out x.jpg writes a JPEG (not PNG bytes under a .jpg name)
"$PG" render --size 32x18 --lights 4 --out "$tmp/r.jpg" >"$tmp/out" 2>"$tmp/err" \
  && [ "$(head -c 3 "$tmp/r.jpg" | od -An -tx1 | tr -d ' ')" = "ffd8ff" ] && grep -q -- "-> $tmp/r.jpg" "$tmp/out" \
  && ok || { bad "render --out x.jpg: not a JPEG"; cat "$tmp/err"; }
"$PG" render --size 32x18 --lights 4 --out "$tmp/r2.JPEG" >"$tmp/out" 2>"$tmp/err" \
  && [ "$(head -c 3 "$tmp/r2.JPEG" | od -An -tx1 | tr -d ' ')" = "ffd8ff" ] && ok || { bad "render --out x.JPEG"; cat "$tmp/err"; }
# unsupported glTF features: one warning line on stderr, once, and listed by --explain
skin_w="passgraph: warning: $gcorp/ok_skins.gltf: 1 primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, unskinned"
"$PG" render --scene "$gcorp/ok_skins.gltf" --size 32x18 --lights 4 --explain --out "$tmp/sk.png" >"$tmp/out" 2>"$tmp/err" \
  && [ "$(grep -cxF -- "$skin_w" "$tmp/err")" = 1 ] && [ "$(grep -c 'warning' "$tmp/err")" = 1 ] \
  && grep -qxF "explain: scene warning: $gcorp/ok_skins.gltf: 1 primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, unskinned" "$tmp/out" \
  && ok || { bad "render: skins warning"; cat "$tmp/err" "$tmp/out"; }
"$PG" render --scene "$gcorp/ok_minimal.gltf" --size 32x18 --lights 4 --out "$tmp/mi.png" >"$tmp/out" 2>"$tmp/err" \
  && ! grep -q "warning" "$tmp/err" && ok || { bad "render: a plain glTF warns"; cat "$tmp/err"; }
"$PG" compare --scene "$gcorp/ok_skins.gltf" --reference "$naive" --size 32x18 --lights 4 --quiet >"$tmp/out" 2>"$tmp/err" \
  && [ "$(grep -cxF -- "$skin_w" "$tmp/err")" = 1 ] \
  && ok || { bad "compare: scene warning once"; cat "$tmp/err"; }
# pass types from a plug-in (docs/plugins.md): the example 'tint' renders; each bad plug-in is refused
plugdir="$(dirname "$PG")/plugins"
tintp="$root/examples/plugins/tint/tint.json"
if [ -f "$plugdir/libpg_tint.so" ]; then
  "$PG" render --plugin "$plugdir/libpg_tint.so" --pipeline "$tintp" --validation --size 64x36 --lights 16 \
    --set tint_r=1 --set tint_g=0 --set tint_b=0 --explain --out "$tmp/tint.png" >"$tmp/out" 2>"$tmp/err" \
    && grep -qF "tint: multiplies the image by (1, 0, 0)" "$tmp/out" \
    && python3 "$root/tests/cli/png_channels.py" "$tmp/tint.png" >"$tmp/tstat" \
    && awk '{ exit !($1 > 5 && $5 <= 1 && $6 <= 1) }' "$tmp/tstat" \
    && ok || { bad "render with the tint plug-in (R G B means, maxima: $(cat "$tmp/tstat" 2>/dev/null))"; cat "$tmp/err"; }
  expect_fail "--plugin: missing file" "$tmp/no-such.so: cannot load plug-in: No such file or directory" \
    render --plugin "$tmp/no-such.so" --size 16x16 --out "$tmp/x.png"
  ln -sf "$tmp/loop_b.so" "$tmp/loop_a.so" && ln -sf "$tmp/loop_a.so" "$tmp/loop_b.so"
  expect_fail "--plugin: a link loop" "loop_a.so: cannot load plug-in: Too many levels of symbolic links" \
    render --plugin "$tmp/loop_a.so" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: an empty path" '--plugin "": an empty path' render --plugin "" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: not a shared object" "$tintp: cannot load plug-in: " \
    render --plugin "$tintp" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: no entry points" "libpg_tint_noentry.so: not a passgraph plug-in: no passgraph_plugin_api_version" \
    render --plugin "$plugdir/libpg_tint_noentry.so" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: API version" "libpg_tint_badversion.so: plug-in API version 999; this passgraph has 2" \
    render --plugin "$plugdir/libpg_tint_badversion.so" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: a type name pipelines cannot write" "libpg_tint_badname.so: pass type name 'tint-x' cannot be written in a pipeline: a type name matches [A-Za-z0-9_]+, at most 63 characters" \
    render --plugin "$plugdir/libpg_tint_badname.so" --size 16x16 --out "$tmp/x.png"
  expect_fail "--plugin: a type without create()" "libpg_tint_nocreate.so: pass type 'tint' has no create function" \
    render --plugin "$plugdir/libpg_tint_nocreate.so" --pipeline "$tintp" --size 16x16 --out "$tmp/x.png"
  # a library is loaded once by its real path (named twice, or through a link); a copy of it in another
  # file registers its type twice and is refused
  ln -sf "$plugdir/libpg_tint.so" "$tmp/tint_link.so"
  "$PG" dump --plugin "$plugdir/libpg_tint.so" --plugin "$plugdir/libpg_tint.so" --plugin "$tmp/tint_link.so" \
    --pipeline "$tintp" >"$tmp/out" 2>"$tmp/err" && ok || { bad "--plugin twice and through a link: not loaded once"; cat "$tmp/err"; }
  cp "$plugdir/libpg_tint.so" "$tmp/tint_copy.so"
  expect_fail "--plugin: a copy in another file" "tint_copy.so: pass type 'tint' is registered twice" \
    render --plugin "$plugdir/libpg_tint.so" --plugin "$tmp/tint_copy.so" --size 16x16 --out "$tmp/x.png"
  expect_fail "a plug-in's pass type without the plug-in" "'tint'" \
    render --pipeline "$tintp" --size 16x16 --out "$tmp/x.png"
  # a pipeline file's own "plugins" list (next to the file, under the include rules): no --plugin needed
  pld="$tmp/plugpipe"
  mkdir -p "$pld"
  cp "$plugdir/libpg_tint.so" "$pld/"
  sed -e "s#\"\.\./\.\./\.\./pipelines/fragments/#\"$root/pipelines/fragments/#g" \
      -e 's#^  "include"#  "plugins": ["libpg_tint.so"],\n  "include"#' "$tintp" >"$pld/tint.json"
  "$PG" render --pipeline "$pld/tint.json" --validation --size 32x18 --lights 4 --out "$tmp/tint2.png" \
    --plugin "$pld/libpg_tint.so" >"$tmp/out" 2>"$tmp/err" && ok || { bad "render: a pipeline's plugins list and --plugin of the same file"; cat "$tmp/err"; }
  "$PG" render --pipeline "$pld/tint.json" --size 32x18 --lights 4 --out "$tmp/tint3.png" >"$tmp/out" 2>"$tmp/err" \
    && ok || { bad "render: a pipeline's plugins list"; cat "$tmp/err"; }
  sed 's#"plugins": \["libpg_tint.so"\]#"plugins": ["nope.so"]#' "$pld/tint.json" >"$pld/missing.json"
  expect_fail "pipeline plugins: missing file" "missing.json: plugins[0]: plug-in 'nope.so' ($pld/nope.so): No such file or directory" \
    render --pipeline "$pld/missing.json" --size 16x16 --out "$tmp/x.png"
  mkdir -p "$pld/nope.so"
  expect_fail "pipeline plugins: a directory" "missing.json: plugins[0]: plug-in 'nope.so' ($pld/nope.so): is a directory" \
    render --pipeline "$pld/missing.json" --size 16x16 --out "$tmp/x.png"
  rmdir "$pld/nope.so"
  sed 's#"plugins": \["libpg_tint.so"\]#"plugins": ["/usr/lib/x86_64-linux-gnu/libm.so.6"]#' "$pld/tint.json" >"$pld/outside.json"
  expect_fail "pipeline plugins: outside the folders" "outside.json: plugins[0]: plug-in '/usr/lib/x86_64-linux-gnu/libm.so.6' is outside the allowed folders" \
    render --pipeline "$pld/outside.json" --size 16x16 --out "$tmp/x.png"
  # only the top-level file may name plug-ins: an included fragment's list is refused by name
  printf '{"plugins": ["libpg_tint.so"], "parameters": {}}\n' >"$pld/frag_plugins.json"
  sed 's#^  "include": \[#  "include": ["frag_plugins.json", #' "$pld/tint.json" >"$pld/frag_top.json"
  expect_fail "pipeline plugins: in an included fragment" "frag_plugins.json: (top level): unknown key 'plugins' in an included fragment" \
    render --pipeline "$pld/frag_top.json" --size 16x16 --out "$tmp/x.png"
else
  bad "the example plug-in was not built: $plugdir/libpg_tint.so"
fi
# user passes written in JSON + GLSL (docs/user-passes.md): the examples render with validation;
# a bad shader pass fails naming the pipeline file, the JSON path, the shader and the cause
for ex in tonemap bloom ssao lighting normals vis_surface; do
  "$PG" render --pipeline "$root/pipelines/examples/$ex/$ex.json" --validation --size 64x36 --lights 16 \
    --out "$tmp/ex_$ex.png" >"$tmp/out" 2>"$tmp/err" && [ -s "$tmp/ex_$ex.png" ] && ! grep -q "VUID" "$tmp/err" \
    && ok || { bad "render: example user pass $ex"; cat "$tmp/err"; }
  # with the other HDR format they offer (bloom's composite declared rgba16f and refused rgba32f)
  if grep -q '"\$hdr_format"' "$root/pipelines/examples/$ex/$ex.json"; then
    "$PG" render --pipeline "$root/pipelines/examples/$ex/$ex.json" --set hdr_format=rgba32f --validation --size 32x18 \
      --lights 8 --out "$tmp/ex32_$ex.png" >"$tmp/out" 2>"$tmp/err" && ! grep -q "VUID" "$tmp/err" \
      && ok || { bad "render: example user pass $ex with hdr_format=rgba32f"; cat "$tmp/err"; }
  fi
done
up="$tmp/userpass"
mkdir -p "$up"
cp "$root/pipelines/examples/tonemap/tonemap.frag" "$up/"
sed "s#\"\.\./\.\./fragments/#\"$root/pipelines/fragments/#g" "$root/pipelines/examples/tonemap/tonemap.json" >"$up/ok.json"
sed 's/"hdr_image": {/"hdr_img": {/' "$up/ok.json" >"$up/b_name.json"
sed 's/"access": "sampled"/"access": "storage_read"/' "$up/ok.json" >"$up/b_access.json"
sed 's/"tonemap.frag"/"nope.frag"/' "$up/ok.json" >"$up/b_missing.json"
sed 's/float L = /float L = no_such_thing + /' "$up/tonemap.frag" >"$up/broken.frag"
sed 's/"tonemap.frag"/"broken.frag"/' "$up/ok.json" >"$up/b_glsl.json"
sed 's/"white": "\$white"/"whit": 2/' "$up/ok.json" >"$up/b_param.json"
sed 's#"tonemap.frag"#"../../../etc/passwd"#' "$up/ok.json" >"$up/b_outside.json"
sed 's/uniform sampler2D hdr_image;/uniform sampler2D hdr_image;\nlayout(set = 2, binding = 1) uniform sampler2D extra;/' \
  "$up/tonemap.frag" >"$up/extra.frag"
sed 's/"tonemap.frag"/"extra.frag"/' "$up/ok.json" >"$up/b_unbound.json"
sed 's/uniform sampler2D hdr_image;/uniform usampler2D hdr_image;/; s/texelFetch(hdr_image, texel, 0).rgb/vec3(texelFetch(hdr_image, texel, 0).rgb)/' \
  "$up/tonemap.frag" >"$up/uint.frag"
sed 's/"tonemap.frag"/"uint.frag"/' "$up/ok.json" >"$up/b_uint.json"
expect_fail "shader pass: texel type" "shader 'uint.frag' binding 'hdr_image' (set 2, binding 0) reads integer texels but resource 'hdr' is rgba16f" \
  dump --pipeline "$up/b_uint.json"
"$PG" dump --pipeline "$up/ok.json" >"$tmp/out" 2>"$tmp/err" && grep -q "user fullscreen shader tonemap.frag" "$tmp/out" \
  && ok || { bad "dump: a shader pass"; cat "$tmp/err"; }
expect_fail "shader pass: binding name" "b_name.json: passes[3].options.bindings.hdr_img: pass 'tonemap': shader 'tonemap.frag' has no binding 'hdr_img' in set 2" \
  dump --pipeline "$up/b_name.json"
expect_fail "shader pass: access" "bindings.hdr_image: pass 'tonemap': shader 'tonemap.frag' binding 'hdr_image' (set 2, binding 0) is a combined image sampler: it needs an image bound \"sampled\", not image 'hdr' bound storage_read" \
  dump --pipeline "$up/b_access.json"
expect_fail "shader pass: missing shader" "b_missing.json: passes[3].options.fullscreen: pass 'tonemap': cannot open shader 'nope.frag'" \
  dump --pipeline "$up/b_missing.json"
expect_fail "shader pass: glslang error" "broken.frag:22: 'no_such_thing' : undeclared identifier" \
  dump --pipeline "$up/b_glsl.json"
expect_fail "shader pass: push member" "passes[3].options.params.white: pass 'tonemap': shader 'tonemap.frag' push-constant member 'white' (float x 1) has no value" \
  dump --pipeline "$up/b_param.json"
expect_fail "shader pass: outside the folders" "shader '../../../etc/passwd' is outside the allowed folders" \
  dump --pipeline "$up/b_outside.json"
# keys that were dropped silently: a typo in a binding object, depth options of a fullscreen pass
sed 's/"access": "sampled"/"acess": "sampled"/' "$up/ok.json" >"$up/b_typo.json"
expect_fail "shader pass: a binding key typo" "bindings.hdr_image: pass 'tonemap': unknown key 'acess' (resource, access)" \
  dump --pipeline "$up/b_typo.json"
sed 's/"fullscreen": "tonemap.frag"/"fullscreen": "tonemap.frag", "depth_test": "equal"/' "$up/ok.json" >"$up/b_fsdepth.json"
expect_fail "shader pass: depth_test on a fullscreen pass" "options.depth_test: pass 'tonemap': a fullscreen shader has no depth attachment" \
  dump --pipeline "$up/b_fsdepth.json"
expect_fail "shader pass: unbound binding" "shader 'extra.frag' binding 'extra' (set 2, binding 1, a combined image sampler) is not bound" \
  render --pipeline "$up/b_unbound.json" --size 16x16 --out "$tmp/x.png"
# an #include inside the user's shader stays in its folder and the library's: '..' and absolute
# names were joined onto shaders/ and read (a file's first line came back in glslang's message)
for inc in ../../../../etc/hostname /etc/passwd sub/../../x.glsl; do
  sed "s#^void main#\#include \"$inc\"\nvoid main#" "$up/tonemap.frag" >"$up/inc.frag"
  sed 's/"tonemap.frag"/"inc.frag"/' "$up/ok.json" >"$up/b_inc.json"
  expect_fail "shader pass: #include $inc" "inc.frag:$(grep -nF "#include \"$inc\"" "$up/inc.frag" | cut -d: -f1): #include \"$inc\" (looked up in $up then" \
    dump --pipeline "$up/b_inc.json"
  grep -qF "outside the allowed folders" "$tmp/err" && ok || { bad "#include $inc: not refused as outside"; cat "$tmp/err"; }
done
# a #version glslang's Vulkan built-ins cannot parse (it printed 4,546 lines of them on stdout)
sed 's/^#version 460/#version 140/' "$up/tonemap.frag" >"$up/inc.frag"
"$PG" dump --pipeline "$up/b_inc.json" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && [ ! -s "$tmp/out" ] && grep -qF "inc.frag: #version 140: Vulkan GLSL needs #version 150 or later" "$tmp/err" \
  && ok || { bad "#version 140: not refused alone"; head -3 "$tmp/out" "$tmp/err"; }
# a name GLSL's #line cannot carry
cp "$up/tonemap.frag" "$up/q\"uote.frag" && sed 's/"tonemap.frag"/"q\\"uote.frag"/' "$up/ok.json" >"$up/b_quote.json"
expect_fail "shader pass: a quote in the file name" "cannot be named by GLSL's #line; rename the file" dump --pipeline "$up/b_quote.json"
sed 's#^void main#\#include "nope.glsl"\nvoid main#' "$up/tonemap.frag" >"$up/inc.frag"
expect_fail "shader pass: missing #include" "#include \"nope.glsl\" (looked up in $up then" dump --pipeline "$up/b_inc.json"
# the simple tone mappers (display_tonemap) on values a user pass may write: NaN, +-inf, 1e30,
# negatives, past the half range; each a column of the image. NaN and negatives black, the huge
# ones white, 0.5 as the operator's formula says (Reinhard made +inf black, ACES 1e30 black and
# -0.5 white)
cat >"$up/sp.json" <<EOF
{"name": "sp", "include": ["$root/pipelines/fragments/display.json"],
 "resources": [{"name": "hdr", "type": "image", "format": "rgba32f"}],
 "passes": [{"name": "gen", "type": "shader", "writes": ["hdr"], "options": {"compute": "sp.comp", "bindings": {"hdr_image": "hdr"}}}],
 "output": "ldr", "hdr_output": "hdr"}
EOF
cat >"$up/sp.comp" <<'EOF'
#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, rgba32f) uniform writeonly image2D hdr_image;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(hdr_image)))) return;
    float zero = 0.0, v[8] = float[8](zero / zero, 1.0 / zero, -1.0 / zero, 1e30, -0.5, -2.0, 70000.0, 0.5);
    imageStore(hdr_image, p, vec4(vec3(v[p.x % 8]), 1.0));
}
EOF
for tm in clamp reinhard aces; do
  "$PG" render --pipeline "$up/sp.json" --size 8x2 --lights 0 --set tonemap=$tm --out "$tmp/sp_$tm.png" >/dev/null 2>"$tmp/err" \
    && python3 - "$tmp/sp_$tm.png" $tm "$root/tests/cli" <<'PYEOF' && ok || { bad "display_tonemap $tm on special values"; cat "$tmp/err"; }
import sys
sys.path.insert(0, sys.argv[3])
from png_read import read_png
w, h, bpp, rows = read_png(sys.argv[1])
got = [rows[0][x * bpp] for x in range(8)]
f = {"clamp": lambda x: min(x, 1.0), "reinhard": lambda x: x / (1 + x),
     "aces": lambda x: min(max(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0), 1.0)}[sys.argv[2]]
s = lambda c: c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
half = round(255 * s(f(0.5)))
want = [0, 255, 0, 255, 0, 0, 255, half]
assert all(abs(a - b) <= 1 for a, b in zip(got, want)), (sys.argv[2], got, want)
PYEOF
done
# a fullscreen pass without targets had a 0 x 0 viewport (nothing drawn, a validation error), and
# an integer image sampled through the default "linear" sampler was a validation error at the
# dispatch: both refused when the pipeline compiles, naming the option
cat >"$up/ui.comp" <<'EOF'
#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform usampler2D cnt;
layout(set = 2, binding = 1, rgba8) uniform writeonly image2D ldr_image;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(ldr_image)))) return;
    imageStore(ldr_image, p, vec4(float(texelFetch(cnt, ivec2(0), 0).r), 0.0, 0.0, 1.0));
}
EOF
cat >"$up/uclr.comp" <<'EOF'
#version 460
layout(local_size_x = 1) in;
layout(set = 2, binding = 0, r32ui) uniform writeonly uimage2D cnt;
void main() { imageStore(cnt, ivec2(0), uvec4(1u)); }
EOF
for filter in "" ', "filter": "nearest"'; do
  cat >"$up/ui.json" <<EOF
{"name": "ui", "resources": [{"name": "cnt", "type": "image", "format": "r32ui", "extent": [1, 1]}, {"name": "ldr", "type": "image", "format": "rgba8"}],
 "passes": [{"name": "clr", "type": "shader", "writes": ["cnt"], "options": {"compute": "uclr.comp", "bindings": {"cnt": "cnt"}, "dispatch": {"groups": [1, 1, 1]}}},
            {"name": "show", "type": "shader", "reads": ["cnt"], "writes": ["ldr"], "options": {"compute": "ui.comp", "bindings": {"cnt": "cnt", "ldr_image": "ldr"}$filter}}],
 "output": "ldr"}
EOF
  "$PG" dump --pipeline "$up/ui.json" >/dev/null 2>"$tmp/err"
  rc=$?
  if [ -z "$filter" ]; then
    [ $rc = 1 ] && grep -qF "passes[1].options.filter: pass 'show': resource 'cnt' is r32ui, which cannot be filtered" "$tmp/err" \
      && ok || { bad "an integer image through the linear sampler: not refused (rc $rc)"; cat "$tmp/err"; }
  else
    [ $rc = 0 ] && ok || { bad "an integer image through a nearest sampler: refused"; cat "$tmp/err"; }
  fi
done
sed 's/"targets": \["ldr"\]/"targets": []/' "$up/ok.json" >"$up/b_notargets.json"
expect_fail "shader pass: a fullscreen pass without targets" "a fullscreen shader needs at least one target" dump --pipeline "$up/b_notargets.json"
# a compute user pass whose SPIR-V is valid but that no pipeline image or device can run: refused
# by name (an empty file, an image that is not one 2D layer, a shadow sampler, a workgroup or shared
# memory past the device's limits) instead of a crash or validation messages
cat >"$up/c.json" <<EOF
{"name": "upc", "include": ["$root/pipelines/fragments/lights.json", "$root/pipelines/fragments/shading_params.json"],
 "resources": [{"name": "hdr", "type": "image", "format": "rgba16f"}, {"name": "depth", "type": "image", "format": "d32f"},
               {"name": "ldr", "type": "image", "format": "rgba8"}],
 "passes": [{"name": "shade", "type": "forward_naive", "reads": ["lights", "environment", "geometry"], "writes": ["hdr", "depth"],
             "options": {"shading": "\$shading", "ambient": "\$ambient"}},
            {"name": "tm", "type": "shader", "reads": ["hdr"], "writes": ["ldr"],
             "options": {"compute": "c.comp", "bindings": {"hdr_image": "hdr", "ldr_image": "ldr"}}}],
 "output": "ldr", "hdr_output": "hdr"}
EOF
cat >"$up/c.comp" <<'EOF'
#version 460
layout(set = 2, binding = 0) uniform sampler2D hdr_image;
layout(set = 2, binding = 1, rgba8) uniform writeonly image2D ldr_image;
layout(local_size_x = 8, local_size_y = 8) in;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(ldr_image)))) return;
    imageStore(ldr_image, p, vec4(texelFetch(hdr_image, p, 0).rgb, 1.0));
}
EOF
"$PG" render --pipeline "$up/c.json" --validation --size 32x18 --lights 4 --out "$tmp/uc.png" >"$tmp/out" 2>"$tmp/err" \
  && ! grep -q "VUID" "$tmp/err" && ok || { bad "render: the compute user pass"; cat "$tmp/err"; }
: >"$up/c_empty.comp"
sed 's/sampler2D hdr_image/sampler3D hdr_image/; s/texelFetch(hdr_image, p, 0)/texelFetch(hdr_image, ivec3(p, 0), 0)/' \
  "$up/c.comp" >"$up/c_3d.comp"
sed 's/image2D ldr_image/image2DArray ldr_image/; s/imageSize(ldr_image)/imageSize(ldr_image).xy/; s/imageStore(ldr_image, p,/imageStore(ldr_image, ivec3(p, 0),/' \
  "$up/c.comp" >"$up/c_layers.comp"
sed 's/sampler2D hdr_image/sampler2DShadow hdr_image/; s/texelFetch(hdr_image, p, 0).rgb/vec3(texture(hdr_image, vec3(0.5)))/' \
  "$up/c.comp" >"$up/c_shadow.comp"
sed 's/local_size_x = 8, local_size_y = 8/local_size_x = 1024, local_size_y = 1024/' "$up/c.comp" >"$up/c_wg.comp"
sed 's/^void main()/shared vec4 big[16384];\nvoid main()/; s/^{/{\n    big[gl_LocalInvocationIndex] = vec4(1.0);\n    barrier();/' \
  "$up/c.comp" >"$up/c_shared.comp"
for v in empty 3d layers shadow wg shared; do sed "s/\"c.comp\"/\"c_$v.comp\"/" "$up/c.json" >"$up/c_$v.json"; done
expect_fail "shader pass: empty file" "c_empty.comp: empty file (no #version line)" \
  dump --pipeline "$up/c_empty.json"
# a capability passgraph does not enable (Float64: a validation error, else undefined), and a fixed
# block larger than its buffer (read past the end without a word): refused by name
cat >"$up/cap.comp" <<'EOF'
#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, rgba8) uniform writeonly image2D outimg;
layout(push_constant) uniform Params { float v; } params;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(outimg)))) return;
    double d = double(params.v) * 1.0000001lf;
    imageStore(outimg, p, vec4(float(d)));
}
EOF
printf '%s' '{"name": "cap", "resources": [{"name": "ldr", "type": "image", "format": "rgba8"}],
 "passes": [{"name": "fill", "type": "shader", "writes": ["ldr"],
   "options": {"compute": "cap.comp", "bindings": {"outimg": "ldr"}, "params": {"v": 0.5}}}], "output": "ldr"}' >"$up/cap.json"
expect_fail "shader pass: Float64" "cap.json: passes[0]: shader '$up/cap.comp' uses the SPIR-V capability Float64" \
  render --pipeline "$up/cap.json" --size 16x9 --out "$tmp/x.png"
cat >"$up/ubo.comp" <<'EOF'
#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, rgba8) uniform writeonly image2D outimg;
layout(set = 2, binding = 1) uniform U { vec4 c[64]; } u;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(outimg)))) return;
    imageStore(outimg, p, u.c[63]);
}
EOF
printf '%s' '{"name": "ubo", "resources": [{"name": "ldr", "type": "image", "format": "rgba8"},
   {"name": "small", "type": "buffer", "stride": 4, "count": [1], "lifetime": "persistent"}],
 "passes": [{"name": "fill", "type": "shader", "reads": ["small"], "writes": ["ldr"],
   "options": {"compute": "ubo.comp", "bindings": {"outimg": "ldr", "u": "small"}}}], "output": "ldr"}' >"$up/ubo.json"
expect_fail "shader pass: a block larger than its buffer" "binding 1 is a block of 1024 bytes (without a runtime array), buffer 'small' is" \
  render --pipeline "$up/ubo.json" --size 16x9 --out "$tmp/x.png"
# the draw form's fragment shader is held to the same capabilities (it reached the driver)
sed 's#"\.\./\.\./fragments/#"'"$root"'/pipelines/fragments/#g; s#"normals.frag"#"normals64.frag"#' \
  "$root/pipelines/examples/normals/normals.json" >"$up/normals64.json"
sed 's#out_color = vec4(s.normal \* 0.5 + 0.5, 1.0);#double d = double(s.normal.x) * 1.0000001lf;\n    out_color = vec4(float(d) * 0.5 + 0.5, 0.0, 0.0, 1.0);#' \
  "$root/pipelines/examples/normals/normals.frag" >"$up/normals64.frag"
expect_fail "shader pass (draw): Float64" "shader '$up/normals64.frag' uses the SPIR-V capability Float64" \
  render --pipeline "$up/normals64.json" --size 16x9 --out "$tmp/x.png"
# a buffer the device cannot create: the message names the resource and its size (it named only
# the Vulkan call)
sed 's/"stride": 4, "count": \[1\]/"stride": 16, "count": [1048576, 16384]/' "$up/ubo.json" >"$up/huge.json"
sed 's/layout(set = 2, binding = 1) uniform U { vec4 c\[64\]; } u;/layout(set = 2, binding = 1) readonly buffer U { vec4 c[]; } u;/' \
  "$up/ubo.comp" >"$up/huge.comp"
sed -i 's/"ubo.comp"/"huge.comp"/' "$up/huge.json"
expect_fail "shader pass: a buffer the device cannot create" "resource 'small' (buffer, 256.0 GiB): vkCreateBuffer" \
  render --pipeline "$up/huge.json" --size 16x9 --out "$tmp/x.png"
# a storage image without a format qualifier: said what to declare (was "declares format unknown")
sed 's/layout(set = 2, binding = 1, rgba8) uniform writeonly image2D ldr_image;/layout(set = 2, binding = 1) uniform writeonly image2D ldr_image;/' \
  "$up/c.comp" >"$up/c_nofmt.comp"
sed 's/"c.comp"/"c_nofmt.comp"/' "$up/c.json" >"$up/c_nofmt.json"
expect_fail "shader pass: a storage image without a format" "binding 'ldr_image' (set 2, binding 1) is a storage image without a format qualifier (reading or writing one needs device features passgraph does not enable): declare it layout(rgba8)" \
  dump --pipeline "$up/c_nofmt.json"
# push-constant members of 16 or 64 bits: a 4-byte value went into an 8-byte double (the image came
# out black) or a 2-byte half (validation errors); a bool member (a uint in SPIR-V) takes true
for m in "double d" "float16_t d" "bool d"; do
  cat >"$up/pc.comp" <<EOF
#version 460
#extension GL_EXT_shader_explicit_arithmetic_types : enable
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0, rgba8) uniform writeonly image2D outimg;
layout(push_constant) uniform Params { float v; $m; } params;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(outimg)))) return;
    imageStore(outimg, p, vec4(params.v + (float(params.d) > 0.5 ? 1.0 : 0.0)));
}
EOF
  printf '%s' '{"name": "pc", "resources": [{"name": "ldr", "type": "image", "format": "rgba8"}],
   "passes": [{"name": "fill", "type": "shader", "writes": ["ldr"],
     "options": {"compute": "pc.comp", "bindings": {"outimg": "ldr"}, "params": {"v": 0.0, "d": true}}}], "output": "ldr"}' \
    >"$up/pc.json"
  case $m in
  bool*)
    "$PG" render --pipeline "$up/pc.json" --validation --size 16x9 --out "$tmp/pc.png" >"$tmp/out" 2>&1 && ! grep -q VUID "$tmp/out" \
      && [ "$(python3 "$root/tests/cli/png_stats.py" "$tmp/pc.png")" = "16 9 1.0000 255.0" ] && ok \
      || { bad "shader pass: a bool push member given true"; tail -3 "$tmp/out"; } ;;
  double*) expect_fail "shader pass: a double push member" "push-constant member 'd' is a 64-bit float: params values are 32-bit" \
      dump --pipeline "$up/pc.json" ;;
  *) expect_fail "shader pass: a float16_t push member" "push-constant member 'd' is a 16-bit float" dump --pipeline "$up/pc.json" ;;
  esac
done
# a persistent image only read, never written: its first frame left it UNDEFINED while the pass
# sampled it (validation error); a first-frame barrier now takes it out of UNDEFINED once
cat >"$up/hist.comp" <<'EOF'
#version 460
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 2, binding = 0) uniform sampler2D hist;
layout(set = 2, binding = 1, rgba8) uniform writeonly image2D outimg;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(outimg)))) return;
    imageStore(outimg, p, vec4(0.25 + 0.0 * texelFetch(hist, ivec2(0), 0).a));
}
EOF
printf '%s' '{"name": "hist", "resources": [{"name": "ldr", "type": "image", "format": "rgba8"},
   {"name": "hist", "type": "image", "format": "rgba8", "lifetime": "persistent"}],
 "passes": [{"name": "fill", "type": "shader", "reads": ["hist"], "writes": ["ldr"],
   "options": {"compute": "hist.comp", "bindings": {"outimg": "ldr", "hist": {"resource": "hist", "access": "sampled"}}}}],
 "output": "ldr"}' >"$up/hist.json"
"$PG" render --pipeline "$up/hist.json" --validation --frames 3 --size 16x9 --out "$tmp/hist.png" >"$tmp/out" 2>&1 \
  && ! grep -q "validation error" "$tmp/out" && [ "$(python3 "$root/tests/cli/png_stats.py" "$tmp/hist.png")" = "16 9 1.0000 64.0" ] \
  && "$PG" dump --pipeline "$up/hist.json" 2>&1 | grep -q "undefined -> shader_read_only  (first frame)" && ok \
  || { bad "shader pass: a persistent image only read"; tail -3 "$tmp/out"; }
expect_fail "shader pass: 3D image" "binding 'hdr_image' (set 2, binding 0) is a 3D image: a pipeline image is bound as one 2D layer" \
  dump --pipeline "$up/c_3d.json"
expect_fail "shader pass: image array" "binding 'ldr_image' (set 2, binding 1) is an image array (layers)" \
  dump --pipeline "$up/c_layers.json"
expect_fail "shader pass: shadow sampler" "binding 'hdr_image' (set 2, binding 0) is a shadow sampler" \
  dump --pipeline "$up/c_shadow.json"
expect_fail "shader pass: workgroup past the device" "c_wg.json: passes[1]: shader" \
  render --pipeline "$up/c_wg.json" --validation --size 32x18 --lights 4 --out "$tmp/x.png"
grep -qE "(local_size_[xyz] = 1024|1048576 invocations) is more than .* allows" "$tmp/err" && ! grep -q "VUID" "$tmp/err" \
  && ok || { bad "shader pass: workgroup refusal"; cat "$tmp/err"; }
expect_fail "shader pass: shared memory past the device" "c_shared.comp': 262144 bytes of shared memory (at least) are more than" \
  render --pipeline "$up/c_shared.json" --validation --size 32x18 --lights 4 --out "$tmp/x.png"
! grep -q "VUID" "$tmp/err" && ok || { bad "shader pass: shared memory refusal after validation messages"; cat "$tmp/err"; }
# a glTF animation: played at --time by the geometry_animate pass, named by --explain; an unknown
# --animation is an error listing the file's
acorp="$gcorp/animation"
"$PG" render --scene "$acorp/skinned.gltf" --time 1 --size 32x18 --lights 4 --explain --out "$tmp/an.png" >"$tmp/out" 2>"$tmp/err" \
  && grep -qF "explain: animation: animation 0 'bend' of 1 (2 s loop) at t = 1 s; 1 skin (2 joints)" "$tmp/out" \
  && grep -q "animate_geometry: deforms" "$tmp/out" && ! grep -q "warning" "$tmp/err" \
  && ok || { bad "render: animated glTF"; cat "$tmp/err" "$tmp/out"; }
"$PG" render --scene "$acorp/skinned.gltf" --animation walk --size 32x18 --out "$tmp/an2.png" >"$tmp/out" 2>"$tmp/err"
[ $? -ne 0 ] && grep -qF -- "--animation walk: no such animation; available: 0 'bend', all or none" "$tmp/err" \
  && ok || { bad "render --animation walk: not refused"; cat "$tmp/err"; }
# BLEND is drawn now: no warning, and the transparent pass runs
"$PG" render --scene "$gcorp/ok_alpha_blend.gltf" --size 32x18 --lights 4 --out "$tmp/ab.png" >"$tmp/out" 2>"$tmp/err" \
  && ! grep -q "warning" "$tmp/err" && grep -q "transparent" "$tmp/out" && ok || { bad "render: BLEND scene"; cat "$tmp/err" "$tmp/out"; }
"$PG" bench --scene "$gcorp/ok_skins.gltf" --pipelines naive --lights 4,8 --size 32x18 --frames 1 --warmup 0 --out "$tmp/bw" \
  >"$tmp/out" 2>"$tmp/err" && [ "$(grep -cxF -- "$skin_w" "$tmp/err")" = 1 ] \
  && ok || { bad "bench: skins warning once"; cat "$tmp/err"; }
# glTF surface variants (PG_VERTEX_COLORS, PG_UV1, PG_UV_TRANSFORM): compiled only for a scene that
# uses them; otherwise each scene-drawing pass explains why not (dump: the plan's defines)
feat="$gcorp/features"
for pl in forward_plus deferred_oct16; do
  "$PG" dump --scene "$gcorp/ok_minimal.gltf" --pipeline "$root/pipelines/$pl.json" >"$tmp/d0" 2>"$tmp/err" \
    && ! grep -qE "defines:.*(PG_VERTEX_COLORS|PG_UV1|PG_UV_TRANSFORM)" "$tmp/d0" \
    && grep -qE ": no vertex colours: colour attribute path compiled out$" "$tmp/d0" \
    && grep -qE ": no texture reads TEXCOORD_1: second UV stream compiled out$" "$tmp/d0" \
    && grep -qE ": no KHR_texture_transform: UV transform compiled out$" "$tmp/d0" \
    && ok || { bad "$pl: a plain glTF compiles a surface variant or does not say why not"; cat "$tmp/err" "$tmp/d0"; }
  for fv in vcolor_unorm8.gltf:PG_VERTEX_COLORS texcoord1.gltf:PG_UV1 xform_offset.gltf:PG_UV_TRANSFORM \
            xform_texcoord.gltf:PG_UV1 xform_texcoord.gltf:PG_UV_TRANSFORM; do
    f=${fv%%:*} def=${fv#*:}
    # the scene-drawing passes: forward+'s depth pre-pass (its default) and shade share the vertex path
    want=1; [ $pl = forward_plus ] && want=2
    n=$("$PG" dump --scene "$feat/$f" --pipeline "$root/pipelines/$pl.json" 2>"$tmp/err" | grep -cE "defines:.* $def( |$)")
    [ "$n" = $want ] && ok || { bad "$pl $f: $n passes compiled with $def (want the $want scene-drawing passes)"; cat "$tmp/err"; }
  done
  "$PG" dump --scene "$feat/vcolor_unorm8.gltf" --pipeline "$root/pipelines/$pl.json" 2>"$tmp/err" \
    | grep -qE "defines:.*(PG_UV1|PG_UV_TRANSFORM)" && bad "$pl vcolor_unorm8: UV variants compiled" || ok
done

check_finish cli_test
