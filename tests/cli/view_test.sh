#!/usr/bin/env bash
# view_test.sh PASSGRAPH_BINARY - the viewer under Xvfb with lavapipe, validation and
# synchronization validation on: every pipeline is cycled through, the window is resized, a
# pipeline file is broken on disk (the error is reported, the last good graph keeps running) and
# mended (it reloads), parameters, the OCIO view and display and the difference view (linear error,
# then FLIP) are switched,
# and the screenshot (scene + UI) is written. Any validation message fails the run.
set -u
PG=$1
. "$(dirname "$0")/check_lib.sh"
root=$(cd "$(dirname "$0")/../.." && pwd)
if ! command -v xvfb-run >/dev/null; then echo "view_test: skipped: xvfb-run not installed"; exit 77; fi
cp -r "$root/pipelines" "$tmp/"
printf '{ "name": broken' >"$tmp/broken.json"

xvfb-run -a -s "-screen 0 1024x768x24" "$PG" view --validation --size 320x180 --frames 66 --lights 48 \
  --pipeline "$tmp/pipelines/forward_plus.json" --pipelines "$tmp/pipelines" --cycle-pipelines --cycle-every 6 \
  --at 3:resize=400x240 --at 9:set=view=cluster_heat --at 13:copy="$tmp/broken.json:$tmp/pipelines/naive.json" \
  --at 15:pipeline="$tmp/pipelines/naive.json" --at 20:copy="$root/pipelines/naive.json:$tmp/pipelines/naive.json" \
  --at 25:diff=on --at 27:diff=flip --at 30:diff=off --at 33:resize=320x180 --at 35:lights=0 --at 40:lights=64 \
  --at "42:ocioview=Filmic (ACES)" --at 44:display=Rec.1886 \
  --screenshot "$tmp/shot.png" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc -eq 0 ] && ok || { bad "view exit $rc"; tail -20 "$tmp/err"; }
grep -q "validation message" "$tmp/err" && { bad "validation messages"; grep -m3 "validation" "$tmp/err"; } || ok
grep -q "switching to" "$tmp/out" && ok || bad "no pipeline cycling"
grep -Eq '^view: FLIP against the reference: mean [0-9.e+-]+ \([0-9]+x[0-9]+, ' "$tmp/out" && ok || bad "diff=flip: no FLIP map computed"
grep -q "JSON syntax error" "$tmp/err" && ok || bad "broken pipeline error not reported"
[ "$(grep -c 'change on disk' "$tmp/out")" -ge 2 ] && ok || bad "edits on disk not reloaded"
grep -Eq '^view: 66 frames' "$tmp/out" && ok || { bad "did not run 66 frames"; tail -3 "$tmp/out"; }
grep -q "frame 42: ocioview Filmic (ACES)" "$tmp/out" && grep -q "frame 44: display Rec.1886" "$tmp/out" \
  && ok || bad "OCIO view / display not switched"
grep -Eq 'swapchain builds' "$tmp/out" && ! grep -q '1 swapchain builds' "$tmp/out" && ok || bad "resize did not rebuild the swapchain"
[ "$(head -c 4 "$tmp/shot.png" 2>/dev/null | tail -c 3)" = PNG ] && ok || bad "no screenshot"
# 10 pipelines, one every 6 frames: frame 60 comes back to the first
for p in naive forward_plus deferred deferred_oct16 deferred_packed reference ris visibility lightcut stochastic; do
  grep -q "switching to $p.json\|pipeline $p.json" "$tmp/out" && ok || bad "pipeline $p.json never shown"
done

# bad scripted values and unknown keys are refused by name, not read as 0 or ignored: a light count
# that is not a whole number in range, a pipeline that is no file and none of the list, a --set or
# --at set key no pipeline declares, a value a pipeline refuses (named by the option that gave it)
for bad_arg in "--at 2:lights=1e3|--at 2:lights 1e3: expected a whole number in [0, 16777216]" \
               "--at 2:lights=-1|--at 2:lights -1: expected a whole number" \
               "--at 2:pipeline=$tmp/none.json|--at 2:pipeline: $tmp/none.json: neither a file nor one of the viewer's" \
               "--at 2:set=bogus=1|--at 2:set=bogus=1: no pipeline of the viewer declares a parameter 'bogus'" \
               "--set bogus=1|--set bogus=1: no pipeline of the viewer declares a parameter 'bogus'" \
               "--set shading=bogus|--set shading=bogus: pipeline " \
               "--debug-view bogus|--debug-view bogus: pipeline " \
               "--at 2:set=grid_x=0|--at 2:set=grid_x=0: " \
               "--at 2:env_intensity=1e38|--at 2:env_intensity=1e38: expected a number in [0, 1e+06]" \
               "--at 2:env_rotation=1e30|--at 2:env_rotation=1e30: expected a number in [-36000, 36000]" \
               "--at 2:resize=320x180junk|--at 2:resize=320x180junk: expected WxH" \
               "--at 2:variant=default|--at 2:variant=default: the scene has no material variants" \
               "--frames-in-flight 2x|--frames-in-flight 2x: expected 1 or 2"; do
  # shellcheck disable=SC2086
  xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 4 --lights 4 ${bad_arg%%|*} >"$tmp/out3" 2>"$tmp/err3"
  rc=$?
  [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -qF -- "${bad_arg#*|}" "$tmp/err3" && ok \
    || { bad "view ${bad_arg%%|*}: want a refusal naming it (exit $rc)"; cat "$tmp/err3"; }
  # the command line's --set and --debug-view: bad options, exit 2 as in render and dump (it was 1)
  # (xvfb-run exits 5 when its own clean-up fails, whatever the program returned: seen once under ASan)
  case "${bad_arg%% *}" in --set|--debug-view)
    { [ $rc = 2 ] || { [ $rc = 5 ] && grep -q "xvfb-run: error: problem while cleaning up" "$tmp/err3"; }; } && ok \
      || bad "view ${bad_arg%%|*}: exit $rc, want 2";; esac
done
# a screenshot that cannot be written: --screenshot refused before any frame (it ran every frame and
# then failed); an --at one is shown and the viewer goes on (it ended the run)
if [ -d /proc/self ] && [ "$(id -u)" = 0 ]; then
  xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 3 --lights 4 --screenshot /proc/pg.png \
    >"$tmp/out3" 2>"$tmp/err3"
  [ $? -eq 2 ] && grep -qF -- "--screenshot '/proc/pg.png': cannot write" "$tmp/err3" && ok \
    || { bad "view --screenshot /proc/pg.png: want exit 2 before a frame"; cat "$tmp/err3"; }
fi
mkdir -p "$tmp/ro"
chmod 555 "$tmp/ro"
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 4 --lights 4 --at "2:screenshot=$tmp/ro/x.png" \
  >"$tmp/out3" 2>"$tmp/err3"
rc=$?
chmod 755 "$tmp/ro"
if [ "$(id -u)" = 0 ]; then : "root writes into a 555 folder: only the exit is checked"; fi
[ $rc -ne 1 ] && [ $rc -lt 128 ] && grep -Eq '^view: 4 frames' "$tmp/out3" && ok \
  || { bad "view --at screenshot= unwritable: the viewer must go on (exit $rc)"; cat "$tmp/err3"; }

# a scene change while the running pipeline's file is broken on disk: no graph until it is mended
# (it crashed: the session was dropped for the new scene and the broken file left none)
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 16 --lights 8 \
  --scene "$root/tests/corpus/gltf/objects/two_scenes.gltf" --pipeline "$tmp/pipelines/naive.json" --pipelines "$tmp/pipelines" \
  --at 3:copy="$tmp/broken.json:$tmp/pipelines/naive.json" --at 6:gltf_scene=1 \
  --at 10:copy="$root/pipelines/naive.json:$tmp/pipelines/naive.json" --screenshot "$tmp/shot_scene.png" >"$tmp/out4" 2>"$tmp/err4"
rc=$?
[ $rc -eq 0 ] && grep -q "JSON syntax error" "$tmp/err4" && grep -Eq '^view: 16 frames' "$tmp/out4" \
  && grep -q "frame 10: naive.json.* ready in" "$tmp/out4" && ! grep -q "validation message" "$tmp/err4" && ok \
  || { bad "view: a scene change while the pipeline file is broken (exit $rc)"; tail -5 "$tmp/err4"; }
# the difference view's reference broken on disk: the view turns off, says why, the graph goes on
# (the run ended); a data folder of links with its own copy of pipelines/
mkdir -p "$tmp/data"
ln -sfn "$root/shaders" "$tmp/data/shaders"
ln -sfn "$root/assets" "$tmp/data/assets"
cp -r "$root/pipelines" "$tmp/data/"
PASSGRAPH_DATA_DIR="$tmp/data" xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 10 \
  --lights 8 --pipeline "$tmp/data/pipelines/forward_plus.json" --at 2:diff=on \
  --at 4:copy="$tmp/broken.json:$tmp/data/pipelines/reference.json" >"$tmp/out5" 2>"$tmp/err5"
rc=$?
[ $rc -eq 0 ] && grep -q "difference view off: .*reference.json:1:.*JSON syntax error" "$tmp/err5" && grep -Eq '^view: 10 frames' "$tmp/out5" \
  && ok || { bad "view: the difference view's reference broken on disk (exit $rc)"; tail -5 "$tmp/err5"; }
# a fragment the running pipeline includes from outside the watched folders (--include-dir): its
# edit reloads (it was not watched)
mkdir -p "$tmp/frag/examples/tonemap"
cp -r "$root/pipelines/fragments" "$tmp/frag/"
cp "$root/pipelines/examples/tonemap/"* "$tmp/frag/examples/tonemap/"
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 12 --lights 8 --include-dir "$tmp/frag" \
  --pipeline "$tmp/frag/examples/tonemap/tonemap.json" --at 3:copy="$tmp/broken.json:$tmp/frag/fragments/lights.json" \
  --at 7:copy="$root/pipelines/fragments/lights.json:$tmp/frag/fragments/lights.json" >"$tmp/out6" 2>"$tmp/err6"
rc=$?
[ $rc -eq 0 ] && [ "$(grep -c 'change on disk' "$tmp/out6")" -ge 2 ] && grep -q "lights.json:1:.*JSON syntax error" "$tmp/err6" \
  && ok || { bad "view: an included fragment elsewhere is watched (exit $rc)"; cat "$tmp/out6" "$tmp/err6" | tail -8; }
# a light count past what the device's storage bindings span (lavapipe: 128 MiB, 16M lights of 32
# bytes) drops the graph with its error; a count it can draw loads it again (the run ended)
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 10 --lights 0 --set grid_x=8 \
  --set grid_y=4 --set grid_z=8 --pipeline "$root/pipelines/deferred_packed.json" --at 2:lights=16777216 --at 5:lights=16 \
  >"$tmp/out7" 2>"$tmp/err7"
rc=$?
if grep -q "more than one binding spans" "$tmp/err7"; then
  [ $rc -eq 0 ] && grep -Eq '^view: 10 frames, 2 pipeline loads' "$tmp/out7" && ok \
    || { bad "view: a light count past the device's bindings must drop the graph, not end the run (exit $rc)"; tail -3 "$tmp/err7"; }
else
  [ $rc -eq 0 ] && ok || { bad "view --at lights=16777216 (exit $rc)"; tail -3 "$tmp/err7"; }
fi
# a --pipelines DIR file named like a shipped one is listed as "naive.json (dup)" and can be picked
# by that name (both were "naive.json", and the name always gave the shipped one)
mkdir -p "$tmp/dup"
printf '{ "name": broken' >"$tmp/dup/naive.json"
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 4 --lights 4 --pipelines "$tmp/dup" \
  --at "2:pipeline=naive.json (dup)" >"$tmp/out8" 2>"$tmp/err8"
[ $? -eq 0 ] && grep -q "dup/naive.json:1:11: JSON syntax error" "$tmp/err8" && ok \
  || { bad "view: a --pipelines file named like a shipped one, picked as 'naive.json (dup)'"; tail -3 "$tmp/err8"; }
# a debug view only some listed pipelines have (naive has no cluster_heat, forward+ has) starts
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 3 --lights 4 \
  --pipeline "$root/pipelines/forward_plus.json" --debug-view cluster_heat >"$tmp/out_dv" 2>"$tmp/err_dv" \
  && ok || { bad "view --debug-view cluster_heat with forward_plus.json: refused"; cat "$tmp/err_dv"; }
# a set= the shown pipeline refuses but another takes (naive has no cluster_heat) is said and not
# kept: kept, every later reload failed with it and later set= values were never applied
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --pipeline "$root/pipelines/naive.json" --size 64x36 --lights 4 \
  --frames 8 --at 2:set=view=cluster_heat --at 4:set=exposure=4 --at 6:set=ambient=0.5 >"$tmp/out_sv" 2>"$tmp/err_sv"
[ $? -eq 0 ] && [ "$(grep -c "set=view=cluster_heat: .*(not applied)" "$tmp/err_sv")" = 1 ] \
  && grep -q "frame 4: naive.json ready .*rebuilt: values" "$tmp/out_sv" && grep -q "frame 6: naive.json ready .*rebuilt: values" "$tmp/out_sv" \
  && ok || { bad "view: a set= the shown pipeline refuses blocked later changes"; cat "$tmp/err_sv"; tail -5 "$tmp/out_sv"; }
# the light slider from 0 to 1,000,000 and back (tiny window): the light lists grow, a small list
# budget drops and reports references (also at 300,000 lights after the 1,000,000 frames: the lists
# need 14.9 MiB there), and the viewer keeps running. An 8 x 4 x 8 cluster grid: the checks do not
# depend on the grid, and the default 16 x 9 x 32 one has 18 times the clusters, each walking the
# light masks of every light (this run took 48 s of the script's 59 on lavapipe, 8 s now)
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 14 --lights 0 \
  --set grid_x=8 --set grid_y=4 --set grid_z=8 \
  --pipeline "$root/pipelines/deferred_packed.json" --at 2:lights=1000 --at 4:lights=100000 --at 6:lights=1000000 \
  --at 8:set=list_budget_mb=8 --at 10:lights=300000 --at 12:lights=0 >"$tmp/out2" 2>"$tmp/err2"
rc=$?
[ $rc -eq 0 ] && ok || { bad "light sweep: view exit $rc"; tail -20 "$tmp/err2"; }
grep -q "validation message" "$tmp/err2" && { bad "light sweep: validation messages"; grep -m3 "validation" "$tmp/err2"; } || ok
grep -Eq '^view: 14 frames' "$tmp/out2" && ok || { bad "light sweep: did not run 14 frames"; tail -3 "$tmp/out2"; }
grep -Eq '^view: cluster_lights grew .* at 1000000 lights' "$tmp/out2" && ok || { bad "light sweep: no growth at 1,000,000"; cat "$tmp/out2"; }
grep -Eq '^view: light lists need .* over the 8.0 MiB budget' "$tmp/out2" && ok || { bad "light sweep: budget overflow not reported"; cat "$tmp/out2"; }
# ... and at 300,000 lights too, with references dropped: the lists hold at most the budget also in
# the buffer grown at 1,000,000 lights before it was lowered
[ "$(grep -Ec 'over the 8.0 MiB budget: [1-9][0-9]* refs dropped' "$tmp/out2")" -ge 2 ] && ok ||
  { bad "light sweep: the lists at 300,000 lights do not hold to the lowered budget"; cat "$tmp/out2"; }
# glTF cameras: the viewer prints its camera / light choice, switches between the file's
# cameras (the orthographic one included) and auto framing
objs="$root/tests/corpus/gltf/objects"
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 8 --lights 8 \
  --scene "$objs/two_cameras.gltf" --at 2:camera=auto --at 4:camera=side --at 6:camera=1 \
  --at 3:env_intensity=2.5 --at 5:env_rotation=45 >"$tmp/out3" 2>"$tmp/err3"
rc=$?
[ $rc -eq 0 ] && ok || { bad "cameras: exit $rc"; cat "$tmp/err3"; }
grep -q "^view: camera: glTF camera 1 'top'" "$tmp/out3" && ok || { bad "cameras: orthographic camera line"; cat "$tmp/out3"; }
grep -q "^view: camera: glTF camera 0 'side'" "$tmp/out3" && ok || { bad "cameras: start camera line"; cat "$tmp/out3"; }
grep -q "^view: camera: auto framing" "$tmp/out3" && ok || { bad "cameras: auto framing line"; cat "$tmp/out3"; }
grep -q "^view: lights: generated point lights, object box" "$tmp/out3" && ok || { bad "cameras: lights line"; cat "$tmp/out3"; }
grep -q "validation message" "$tmp/err3" && bad "cameras: validation messages" || ok
# the environment light's run-time knobs (the neutral sky of a glTF file without lights): scripted,
# no rebuild; a bad value is an error naming the action
grep -q "^view: frame 3: env_intensity 2.5" "$tmp/out3" && grep -q "^view: frame 5: env_rotation 45" "$tmp/out3" \
  && ok || { bad "environment knobs not applied"; cat "$tmp/out3"; }
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 4 --lights 4 --scene "$objs/two_cameras.gltf" \
  --at 2:env_intensity=-1 >"$tmp/out5" 2>"$tmp/err5"
[ $? -ne 0 ] && grep -qF "env_intensity=-1: expected a number in [0, 1e+06]" "$tmp/err5" && ok || { bad "env_intensity=-1 accepted"; cat "$tmp/err5"; }
# KHR_materials_variants: the viewer switches variants (scripted like its "variant" combo box)
# without losing its camera: the default shoe has no yellow lace, variant 'midnight' does (in the
# middle of the window, between the two UI windows); an unknown
# variant is an error naming the action
shoe="$root/tests/corpus/gltf/variants/shoe.gltf"
for at in "" "--at 2:variant=midnight"; do
  xvfb-run -a -s "-screen 0 1280x720x24" "$PG" view --validation --size 960x540 --frames 4 --scene "$shoe" $at \
    --screenshot "$tmp/shoe.png" >"$tmp/out6" 2>"$tmp/err6"
  [ $? -eq 0 ] && ok || { bad "variant ($at): exit"; tail -5 "$tmp/err6"; }
  grep -q "validation message" "$tmp/err6" && bad "variant ($at): validation messages" || ok
  yellow=$(python3 - "$tmp/shoe.png" "$root/tests/cli" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
from png_read import read_png
w, h, bpp, rows = read_png(sys.argv[1])
print(sum(1 for r in rows for x in range(0, w * bpp, bpp) if r[x] > 120 and r[x + 1] > 100 and r[x + 2] < 50))
PY
)
  if [ -z "$at" ]; then [ "$yellow" = 0 ] && ok || bad "variant: the default shoe has $yellow yellow pixels"
  else [ "${yellow:-0}" -gt 20 ] && grep -q "^view: .*shoe.gltf has 3 material variants .* drawing variant 2 'midnight'" "$tmp/out6" \
         && ok || { bad "variant midnight: $yellow yellow pixels"; cat "$tmp/out6"; }
  fi
done
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 3 --scene "$shoe" --at 2:variant=green \
  >"$tmp/out7" 2>"$tmp/err7"
[ $? -ne 0 ] && grep -q "at 2:variant: .*--variant 'green': not a variant of the file" "$tmp/err7" && ok \
  || { bad "variant=green accepted"; cat "$tmp/err7"; }
# a file with two glTF scenes: the viewer switches to the other (scripted like its "glTF scene"
# combo box) and says so; an index past them is an error listing them
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --validation --size 64x36 --frames 4 --scene "$objs/two_scenes.gltf" \
  --at 2:gltf_scene=1 >"$tmp/out8" 2>"$tmp/err8"
[ $? -eq 0 ] && grep -q "^view: .*two_scenes.gltf has 2 scenes; drawing scene 1 'big'" "$tmp/out8" && ok \
  || { bad "gltf_scene=1"; cat "$tmp/out8" "$tmp/err8"; }
grep -q "validation message" "$tmp/err8" && bad "gltf_scene=1: validation messages" || ok
xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 3 --scene "$objs/two_scenes.gltf" \
  --at 2:gltf_scene=5 >"$tmp/out9" 2>"$tmp/err9"
[ $? -ne 0 ] && grep -q "at 2:gltf_scene: .*--gltf-scene 5: out of range (the file has 2 scenes: 0 'small', 1 'big')" "$tmp/err9" \
  && ok || { bad "gltf_scene=5 accepted"; cat "$tmp/err9"; }
# a glTF with a feature the loader does not draw: the warning line once on stderr (the UI lists it
# too); a .jpg screenshot is a JPEG
skins="$root/tests/corpus/gltf/ok_skins.gltf"
xvfb-run -a -s "-screen 0 1024x768x24" "$PG" view --size 64x36 --frames 2 --lights 4 --scene "$skins" \
  --screenshot "$tmp/shot.jpg" >"$tmp/out4" 2>"$tmp/err4"
[ $? -eq 0 ] && ok || { bad "view of a warned glTF: exit"; tail -5 "$tmp/err4"; }
[ "$(grep -cxF "passgraph: warning: $skins: 1 primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, unskinned" "$tmp/err4")" = 1 ] \
  && ok || { bad "view: skins warning not printed once"; cat "$tmp/err4"; }
[ "$(head -c 3 "$tmp/shot.jpg" 2>/dev/null | od -An -tx1 | tr -d ' ')" = "ffd8ff" ] && ok || bad "view --screenshot x.jpg: not a JPEG"
# a user pass (pipelines/examples/tonemap: JSON + GLSL) hot-reloaded: the shader is broken on disk
# (its glslang error with the file and line is shown, the last good graph keeps running), emptied
# (named, no crash), then edited
# (the new image is shown; the reload's time is printed); the examples are in the viewer's list
ut="$tmp/usertone"
mkdir -p "$ut"
cp "$root/pipelines/examples/tonemap/tonemap.frag" "$ut/"
sed "s#\"\.\./\.\./fragments/#\"$root/pipelines/fragments/#g" "$root/pipelines/examples/tonemap/tonemap.json" >"$ut/tonemap.json"
sed 's/float L = /float L = no_such_thing + /' "$ut/tonemap.frag" >"$tmp/tm_broken.frag"
sed 's/out_color = vec4(pg_srgb_encode(c \* scale), 1.0);/out_color = vec4(pg_srgb_encode(c * scale).bgr, 1.0);/' \
  "$ut/tonemap.frag" >"$tmp/tm_swapped.frag"
: >"$tmp/tm_empty.frag" # as an editor leaves a file it is about to write: an error, no crash
xvfb-run -a -s "-screen 0 1024x768x24" "$PG" view --validation --size 640x360 --frames 12 --lights 16 \
  --pipeline "$ut/tonemap.json" --at 3:copy="$tmp/tm_broken.frag:$ut/tonemap.frag" \
  --at 5:copy="$tmp/tm_empty.frag:$ut/tonemap.frag" --at 7:copy="$tmp/tm_swapped.frag:$ut/tonemap.frag" >"$tmp/out6" 2>"$tmp/err6"
rc=$?
[ $rc -eq 0 ] && ok || { bad "user pass reload: view exit $rc"; tail -20 "$tmp/err6"; }
grep -q "validation message" "$tmp/err6" && bad "user pass reload: validation messages" || ok
grep -q "tonemap.frag:22: 'no_such_thing' : undeclared identifier" "$tmp/err6" \
  && ok || { bad "user pass reload: the shader error was not shown"; cat "$tmp/err6"; }
grep -q "tonemap.frag: empty file (no #version line)" "$tmp/err6" \
  && ok || { bad "user pass reload: an empty shader file was not reported"; cat "$tmp/err6"; }
grep -Eq '^view: frame 1[01]: .* ready in [0-9.]+ ms' "$tmp/out6" || grep -Eq '^view: frame [7-9]: .*ready in [0-9.]+ ms' "$tmp/out6" \
  && ok || { bad "user pass reload: the edited shader was not shown"; cat "$tmp/out6"; }
grep -Eq '^view: 12 frames' "$tmp/out6" && ok || { bad "user pass reload: did not run 12 frames"; tail -3 "$tmp/out6"; }
grep -E 'ready in' "$tmp/out6" | tail -1
# a glTF camera on an animated node follows it as the clock plays (tests/corpus/gltf/animation/
# lantern.gltf: camera 'eye' rides a node that turns about +Y at 90 deg/s, at (0, 3, 6) in it): the
# start view, and the camera chosen again after auto framing, are where the pose puts them
lantern="$root/tests/corpus/gltf/animation/lantern.gltf"
for at in "--validation" "--at 2:camera=auto --at 4:camera=eye"; do
  # shellcheck disable=SC2086
  xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size 64x36 --frames 16 --scene "$lantern" --screenshot "$tmp/follow.png" $at \
    >"$tmp/out7" 2>"$tmp/err7"
  [ $? -eq 0 ] && ok || { bad "follow camera ($at): view exit"; tail -5 "$tmp/err7"; }
  grep -q "^view: camera: glTF camera 0 'eye' follows its node 'eye'" "$tmp/out7" && ok || { bad "follow camera ($at): no follow line"; cat "$tmp/out7"; }
  grep -q "validation message" "$tmp/err7" && bad "follow camera: validation messages" || ok
  line=$(grep "^view: frame 15: camera at" "$tmp/out7")
  python3 - "$line" <<'PY' && ok || bad "follow camera ($at): not where the pose puts it: $line"
import math, re, sys
x, y, z, t = map(float, re.search(r"\(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\), time ([0-9.]+)", sys.argv[1]).groups())
a = math.radians(90.0 * t)
want = (6 * math.sin(a), 3.0, 6 * math.cos(a))
sys.exit(0 if t > 0.4 and max(abs(p - q) for p, q in zip((x, y, z), want)) < 1e-3 else 1)
PY
done
check_finish view_test
