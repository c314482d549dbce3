#!/usr/bin/env python3
"""doc_examples.py ROOT PASSGRAPH [--write] - every output example the docs mark as generated is
what the tool prints today.

A marker line `<!-- output of: passgraph ARGS -->` in README.md or docs/*.md (not docs/results/)
is followed by a fenced block: the standard output of `PASSGRAPH ARGS`, run from ROOT without a
GPU (dump and other commands that need none). A block fenced as ```json is compared re-indented
with two spaces (the tool indents with tabs), keys in the tool's order. Exit 0 when every block
matches; 1 otherwise, each mismatch printed with file, line, command and the first differing line.
Before the docs, the check proves it can fail: a block with one line changed must be reported.

--write rewrites each differing block with what the command prints (then read the prose around it:
it may describe the old output)."""
import glob
import json
import os
import shlex
import subprocess
import sys

MARK = "<!-- output of: passgraph "


def run(root, exe, args, is_json):
    p = subprocess.run([exe] + args, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=300, env=dict(os.environ, PASSGRAPH_DATA_DIR=root))
    if p.returncode != 0:
        raise RuntimeError("exit %d: %s" % (p.returncode, p.stderr.strip()))
    out = p.stdout
    if is_json:
        out = json.dumps(json.loads(out), indent=2, ensure_ascii=False) + "\n"
    return [line.rstrip() for line in out.rstrip("\n").split("\n")]


def blocks(lines):
    """(marker index, args, fence start, fence end, is_json) of each marked block."""
    for i, line in enumerate(lines):
        s = line.strip()
        if not (s.startswith(MARK) and s.endswith("-->")):
            continue
        args = shlex.split(s[len(MARK):-3])
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        if j >= len(lines) or not lines[j].startswith("```"):
            yield i, args, None, None, False
            continue
        k = j + 1
        while k < len(lines) and not lines[k].startswith("```"):
            k += 1
        yield i, args, j, k, lines[j].strip() == "```json"


def first_difference(a, b):
    for n, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return n, x, y
    n = min(len(a), len(b))
    return n, a[n] if n < len(a) else "(end)", b[n] if n < len(b) else "(end)"


def check_file(root, exe, path, write):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    bad, count, edits = 0, 0, []
    for i, args, j, k, is_json in blocks(lines):
        count += 1
        where = "%s:%d" % (os.path.relpath(path, root), i + 1)
        if j is None:
            print("%s: marker without a fenced block after it" % where)
            bad += 1
            continue
        try:
            want = run(root, exe, args, is_json)
        except (RuntimeError, ValueError, subprocess.TimeoutExpired) as e:
            print("%s: passgraph %s: %s" % (where, " ".join(args), e))
            bad += 1
            continue
        have = [line.rstrip() for line in lines[j + 1:k]]
        if have != want:
            n, x, y = first_difference(have, want)
            print("%s: passgraph %s: block line %d is\n    %s\n  the tool prints\n    %s" %
                  (where, " ".join(args), n + 1, x, y))
            bad += 1
            edits.append((j + 1, k, want))
    if write and edits:
        for start, end, want in reversed(edits):
            lines[start:end] = want
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
    return bad, count


def self_test(root, exe):
    """One marked block with a changed line must be reported."""
    import contextlib
    import io
    import tempfile
    with tempfile.TemporaryDirectory() as d, contextlib.redirect_stdout(io.StringIO()):
        doc = os.path.join(d, "x.md")
        args = "dump --pipeline pipelines/naive.json --size 64x36 --lights 0"
        good = run(root, exe, shlex.split(args), False)
        with open(doc, "w") as f:
            f.write("%s%s -->\n```\n%s\n```\n" % (MARK, args, "\n".join(good)))
        ok_good = check_file(root, exe, doc, False)[0] == 0
        with open(doc, "w") as f:
            f.write("%s%s -->\n```\n%s\n```\n" % (MARK, args, "\n".join(good[:-1] + ["changed"])))
        ok_bad = check_file(root, exe, doc, False)[0] == 1
    return ok_good and ok_bad


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    root, exe = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    write = "--write" in sys.argv[3:]
    if not self_test(root, exe):
        print("doc_examples: the self-test failed: a changed block was not reported (or a good one was)")
        return 1
    files = [os.path.join(root, "README.md")] + sorted(
        p for p in glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True)
        if os.sep + "results" + os.sep not in p)
    bad = total = 0
    for p in files:
        b, n = check_file(root, exe, p, write)
        bad += b
        total += n
    print("doc_examples: %d marked blocks, %d differ%s" % (total, bad, " (rewritten)" if write and bad else ""))
    return 1 if bad and not write else 0


if __name__ == "__main__":
    sys.exit(main())
