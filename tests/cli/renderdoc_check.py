#!/usr/bin/python3
"""renderdoc_check.py [--ui] CAPTURE.rdc DUMP.json - opens a RenderDoc capture of `passgraph render
--capture` with RenderDoc's Python module (Debian python3-renderdoc), replays it and checks that
it reads like the dump (`passgraph dump --format json` of the same pipeline, size and lights):
  - the top-level labelled regions (vkCmdBeginDebugUtilsLabelEXT) are exactly the dump's "order",
    one per executed pass, in plan order, each holding at least one GPU command;
  - every resource the plan keeps (not culled) is a named object in the capture, and so is every
    memory block of the dump, at least one pipeline per executed pass (PASS or PASS.variant) and
    every shader module.
Prints one line per check; exit status 1 on any failure."""
import json
import sys

import renderdoc as rd

# --ui: a viewer capture, where Dear ImGui's Vulkan backend makes two shader modules of its own
ui = "--ui" in sys.argv[1:]
cap_path, dump_path = [a for a in sys.argv[1:] if a != "--ui"][:2]
dump = json.load(open(dump_path))
order = dump["order"]
kept = [r["name"] for r in dump["resources"] if not r["culled"]]

rd.InitialiseReplay(rd.GlobalEnvironment(), [])
cap = rd.OpenCaptureFile()
res = cap.OpenFile(cap_path, "", None)
if res != rd.ResultCode.Succeeded:
    sys.exit("renderdoc_check: cannot open %s: %s" % (cap_path, res))
if not cap.LocalReplaySupport():
    sys.exit("renderdoc_check: %s cannot be replayed here" % cap_path)
res, ctrl = cap.OpenCapture(rd.ReplayOptions(), None)
if res != rd.ResultCode.Succeeded:
    sys.exit("renderdoc_check: replay of %s failed: %s" % (cap_path, res))

sf = ctrl.GetStructuredFile()
WORK = (rd.ActionFlags.Drawcall | rd.ActionFlags.Dispatch | rd.ActionFlags.Clear | rd.ActionFlags.Copy
        | rd.ActionFlags.Resolve)


def work_in(a):
    return sum(1 for c in a.children if c.flags & WORK) + sum(work_in(c) for c in a.children)


regions = [a for a in ctrl.GetRootActions() if a.flags & rd.ActionFlags.PushMarker]
names = [a.GetName(sf) for a in regions]
failed = 0
if names == order:
    print("ok: %d labelled regions in plan order: %s" % (len(names), " ".join(names)))
else:
    failed += 1
    print("FAIL: labelled regions %s, plan order %s" % (names, order))
for a in regions:
    n = work_in(a)
    if n == 0:
        failed += 1
        print("FAIL: region %s holds no GPU command" % a.GetName(sf))
    else:
        print("ok: region %s: %d GPU commands" % (a.GetName(sf), n))
named = {r.name for r in ctrl.GetResources()}
missing = [n for n in kept if n not in named]
if missing:
    failed += 1
    print("FAIL: plan resources without a name in the capture: %s" % ", ".join(missing))
else:
    print("ok: all %d plan resources named in the capture" % len(kept))
# the memory blocks of the dump (block0..blockN-1), one pipeline per executed pass named after it
# (the pass name, or PASS.variant), and every shader module named
mem = {r.name for r in ctrl.GetResources() if r.type == rd.ResourceType.Memory}
blocks = ["block%d" % b["index"] for b in dump["blocks"]]
missing = [b for b in blocks if b not in mem]
if missing:
    failed += 1
    print("FAIL: memory blocks without their name: %s" % ", ".join(missing))
else:
    print("ok: all %d memory blocks named" % len(blocks))
pipes = [r.name for r in ctrl.GetResources() if r.type == rd.ResourceType.PipelineState]
unnamed = [p for p in order if not any(n == p or n.startswith(p + ".") for n in pipes)]
if unnamed:
    failed += 1
    print("FAIL: passes without a pipeline named after them: %s (pipelines: %s)" % (", ".join(unnamed), pipes))
else:
    print("ok: every pass has a named pipeline (%d pipelines)" % len(pipes))
shaders = [r.name for r in ctrl.GetResources() if r.type == rd.ResourceType.Shader]
unnamed = [n for n in shaders if not n or n.startswith("Shader ")]
if not shaders or len(unnamed) > (2 if ui else 0):
    failed += 1
    print("FAIL: shader modules without a name: %s" % shaders)
else:
    print("ok: all %d shader modules named" % len(shaders))
ctrl.Shutdown()
cap.Shutdown()
rd.ShutdownReplay()
sys.exit(1 if failed else 0)
