#!/usr/bin/env bash
# renderdoc_test.sh PASSGRAPH_BINARY - passgraph under RenderDoc (Debian renderdoccmd, which
# reports every device as Vulkan 1.2) on lavapipe:
#  - `devices` under RenderDoc lists the device as usable ("used as 1.2 + extensions");
#  - `render --capture` without RenderDoc is an error naming the cause, exit status 1;
#  - for each pipeline below, `renderdoccmd capture -w passgraph render --capture X.rdc` writes
#    X.rdc and the same image as a render without RenderDoc; tests/renderdoc_check.py replays the
#    capture with RenderDoc's Python module and checks one labelled region per executed pass in
#    the order of `passgraph dump --format json`, and every plan resource named;
#  - the Vulkan 1.2 + extensions path forced on the 1.3 device (PASSGRAPH_VULKAN_1_2=1) renders
#    every pipeline with validation + synchronization validation, zero messages, byte-identical;
#  - a 1.2 device lacking a needed extension is refused with its name (PASSGRAPH_HIDE_EXTENSION);
#  - the executable calls no Vulkan 1.3 core command directly (they go through vk_context.h).
# Skipped (exit 77, reason printed) only when renderdoccmd or python3-renderdoc is missing;
# tools/setup.sh installs both.
set -u
PG=$(realpath "$1")
. "$(dirname "$0")/check_lib.sh"
root=$(cd "$(dirname "$0")/../.." && pwd)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
if ! command -v renderdoccmd >/dev/null; then echo "renderdoc_test: skipped: renderdoccmd not installed (Debian renderdoccmd; tools/setup.sh)"; exit 77; fi
if ! "$PY" -c "import renderdoc" 2>/dev/null; then echo "renderdoc_test: skipped: $PY cannot import renderdoc (Debian python3-renderdoc; tools/setup.sh)"; exit 77; fi
cd "$tmp"
# renderdoc_check.py on CAPTURE and DUMP into OUT (extra arguments first). RenderDoc's Python replay
# crashed once in a CI run (SIGSEGV inside the module, on a capture whose check passed 34 times in
# a row on rerun): a run killed by a signal is retried once, and says so; a check that fails, or
# crashes twice, still fails.
rd_check() {
  local rdc=$1 json=$2 out=$3; shift 3
  "$PY" "$root/tests/cli/renderdoc_check.py" "$@" "$rdc" "$json" >"$out" 2>&1
  local rc=$?
  if [ $rc -ge 128 ]; then
    echo "renderdoc_test: the replay of $rdc died by signal $((rc - 128)); retrying once"
    "$PY" "$root/tests/cli/renderdoc_check.py" "$@" "$rdc" "$json" >"$out" 2>&1
    rc=$?
  fi
  return $rc
}
SIZE=160x90
LIGHTS=64

# no direct reference to any Vulkan 1.3 core command (a 1.2 device has them only under their
# extension names): a new one must be added to the list in core/vk/vk_context.h
if command -v nm >/dev/null; then
  v13='CmdPipelineBarrier2|QueueSubmit2|CmdWriteTimestamp2|CmdBeginRendering|CmdEndRendering|CmdSetCullMode'
  v13+='|CmdSetEvent2|CmdResetEvent2|CmdWaitEvents2|Cmd(Blit|Copy|Resolve)Image2|CmdCopyBuffer2|CmdCopyBufferToImage2'
  v13+='|CmdCopyImageToBuffer2|CmdSetFrontFace|CmdSetPrimitiveTopology|CmdSet(Viewport|Scissor)WithCount'
  v13+='|CmdBindVertexBuffers2|CmdSetDepth(Test|Write|BoundsTest|Bias)Enable|CmdSetDepthCompareOp|CmdSetStencil(TestEnable|Op)'
  v13+='|CmdSetRasterizerDiscardEnable|CmdSetPrimitiveRestartEnable|GetDevice(Buffer|Image|ImageSparse)MemoryRequirements'
  v13+='|(Create|Destroy)PrivateDataSlot|(Set|Get)PrivateData|GetPhysicalDeviceToolProperties'
  direct=$(nm -u "$PG" | grep -E " vk($v13)\$")
  [ -z "$direct" ] && ok || bad "direct Vulkan 1.3 calls (route them through core/vk/vk_context.h): $direct"
fi

renderdoccmd capture -w "$PG" devices >devices.out 2>&1
grep -q "Vulkan 1\.2.*used as 1.2 + extensions" devices.out && ! grep -q "too old" devices.out && ok \
  || { bad "devices under RenderDoc"; cat devices.out; }

# a 1.2 device without a needed extension is refused, naming it (hidden: PASSGRAPH_HIDE_EXTENSION)
PASSGRAPH_VULKAN_1_2=1 PASSGRAPH_HIDE_EXTENSION=VK_KHR_dynamic_rendering "$PG" devices >hide.out 2>&1
grep -q "\[Vulkan 1.2 without VK_KHR_dynamic_rendering (needs 1.3, or 1.2 with these)\]" hide.out && ok \
  || { bad "devices: missing extension not named"; cat hide.out; }
PASSGRAPH_VULKAN_1_2=1 PASSGRAPH_HIDE_EXTENSION=VK_EXT_extended_dynamic_state "$PG" render --size 32x18 --out hide.png >hide.out 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "no usable Vulkan device matches .*: Vulkan 1.2 without VK_EXT_extended_dynamic_state" hide.out && ok \
  || { bad "render: 1.2 device without an extension: exit $rc"; cat hide.out; }

"$PG" render --size $SIZE --lights $LIGHTS --capture nord.rdc --out nord.png >nord.out 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "not started under RenderDoc" nord.out && [ ! -e nord.rdc ] && ok \
  || { bad "render --capture outside RenderDoc: exit $rc"; cat nord.out; }

for p in naive forward_plus deferred deferred_packed; do
  pj="$root/pipelines/$p.json"
  renderdoccmd capture -w -c "$tmp/rdtmp" "$PG" render --pipeline "$pj" --size $SIZE --lights $LIGHTS \
    --capture "$tmp/$p.rdc" --out "$tmp/$p.rd.png" >"$p.rd.out" 2>&1
  if ! grep -q "^render: .*capture $tmp/$p.rdc" "$p.rd.out" || [ ! -s "$p.rdc" ]; then
    bad "$p: render --capture under RenderDoc"; cat "$p.rd.out"; continue
  fi
  ok
  "$PG" render --pipeline "$pj" --size $SIZE --lights $LIGHTS --out "$p.png" >/dev/null 2>"$p.err" || bad "$p: plain render"
  cmp -s "$p.png" "$p.rd.png" && ok || bad "$p: image under RenderDoc differs from the plain render"
  "$PG" dump --pipeline "$pj" --size $SIZE --lights $LIGHTS --format json --out "$p.json" || { bad "$p: dump"; continue; }
  rd_check "$p.rdc" "$p.json" "$p.check" && ok || { bad "$p: capture check"; cat "$p.check"; }
  sed "s/^/  $p: /" "$p.check"
  PASSGRAPH_VULKAN_1_2=1 "$PG" render --validation --pipeline "$pj" --size $SIZE --lights $LIGHTS --out "$p.v12.png" >"$p.v12.out" 2>&1
  rc=$?
  [ $rc -eq 0 ] && grep -q "used as 1.2 + extensions" "$p.v12.out" && ! grep -q "validation" <(grep -v "validation + sync validation on" "$p.v12.out") && ok \
    || { bad "$p: PASSGRAPH_VULKAN_1_2=1 --validation: exit $rc"; tail -5 "$p.v12.out"; }
  cmp -s "$p.png" "$p.v12.png" && ok || bad "$p: 1.2-path image differs"
done

# the viewer: --at N:capture (what the C key and the button do) under RenderDoc, and without it a
# message while the viewer goes on
if command -v xvfb-run >/dev/null; then
  pj="$root/pipelines/deferred.json"
  xvfb-run -a -s "-screen 0 640x480x24" renderdoccmd capture -w "$PG" view --size $SIZE --frames 4 --lights $LIGHTS \
    --pipeline "$pj" --at 2:capture="$tmp/view.rdc" >view.out 2>&1
  if grep -q "^view: RenderDoc capture $tmp/view.rdc" view.out && [ -s view.rdc ]; then
    ok
    "$PG" dump --pipeline "$pj" --size $SIZE --lights $LIGHTS --format json --out view.json 2>/dev/null
    rd_check view.rdc view.json view.check --ui && ok || { bad "view: capture check"; cat view.check; }
  else
    bad "view: capture under RenderDoc"; tail -5 view.out
  fi
  xvfb-run -a -s "-screen 0 640x480x24" "$PG" view --size $SIZE --frames 4 --lights $LIGHTS --pipeline "$pj" \
    --at 2:capture="$tmp/view0.rdc" >view0.out 2>&1
  rc=$?
  [ $rc -eq 0 ] && grep -q "RenderDoc capture: this process was not started under RenderDoc" view0.out && [ ! -e view0.rdc ] && ok \
    || { bad "view: capture without RenderDoc: exit $rc"; tail -5 view0.out; }
else
  echo "renderdoc_test: xvfb-run not installed: viewer capture not checked"
fi

check_finish renderdoc_test
