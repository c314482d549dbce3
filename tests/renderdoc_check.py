#!/usr/bin/python3
"""renderdoc_check.py CAPTURE.rdc DUMP.json - opens a RenderDoc capture of `passgraph render
--capture` with RenderDoc's Python module (Debian python3-renderdoc), replays it and checks that
it reads like the dump (`passgraph dump --format json` of the same pipeline, size and lights):
  - the top-level labelled regions (vkCmdBeginDebugUtilsLabelEXT) are exactly the dump's "order",
    one per executed pass, in plan order, each holding at least one GPU command;
  - every resource the plan keeps (not culled) is a named object in the capture.
Prints one line per check; exit status 1 on any failure."""
import json
import sys

import renderdoc as rd

cap_path, dump_path = sys.argv[1], sys.argv[2]
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
ctrl.Shutdown()
cap.Shutdown()
rd.ShutdownReplay()
sys.exit(1 if failed else 0)
