#!/usr/bin/env python3
"""gpu_tests_table.py DIR | NAME=DIR NAME=DIR... - a markdown table of runs of the GPU tests by hand
(scripts/gpu_tests_bundle.sh's run.sh): DIR holds run.sh's TEST.txt outputs and its summary
(summary.txt: "TEST rc=N S s validation messages: M" lines). One DIR: one row per test with its exit
code, seconds, checks passed and failed (the test's last "N passed, M failed" line), the validation
messages it counted, and its failed checks (file:line and message, shortened). Several named runs
(e.g. the same tests under two validation layers): one row per test with each run's exit code,
failed checks and validation messages, and the failed checks of each run that failed. Exit 1 when
a DIR has no summary."""
import os
import re
import sys


def failed_checks(text, limit=4):
    out = []
    for line in text.splitlines():
        m = re.search(r"/(tests/[^:]+:\d+): CHECK failed: (.*)", line)
        if m:
            msg = m.group(2)
            if len(msg) > 110:
                msg = msg[:107] + "..."
            out.append("`%s` %s" % (m.group(1), msg.replace("|", "\\|")))
    extra = len(out) - limit
    out = out[:limit]
    if extra > 0:
        out.append("and %d more" % extra)
    return out


def read_run(d):
    """{test: (rc, seconds, passed, failed, validation messages, failed checks)} of one run, or None."""
    summary = os.path.join(d, "summary.txt")
    if not os.path.exists(summary):
        sys.stderr.write("%s: no summary.txt\n" % d)
        return None
    run = {}
    for line in open(summary, encoding="utf-8", errors="replace"):
        m = re.match(r"(\S+) rc=(\d+) (\d+) s validation messages: (.*)$", line.strip())
        if not m:
            continue
        name, rc, secs, msgs = m.group(1), int(m.group(2)), int(m.group(3)), m.group(4)
        path = os.path.join(d, name + ".txt")
        text = open(path, encoding="utf-8", errors="replace").read() if os.path.exists(path) else ""
        counts = re.findall(r"^%s: (\d+) passed, (\d+) failed" % re.escape(name), text, re.M)
        passed, failed = counts[-1] if counts else ("-", "-")
        run[name] = (rc, secs, passed, failed, msgs if msgs != "none reported" else "-",
                     failed_checks(text))
    return run


def compare(named):
    runs = []
    for arg in named:
        label, d = arg.split("=", 1)
        run = read_run(d)
        if run is None:
            return 1
        runs.append((label, run))
    tests = sorted(set().union(*[set(r) for _, r in runs]))
    head = ["test"]
    for label, _ in runs:
        head += ["%s: exit" % label, "%s: failed checks" % label, "%s: validation messages" % label]
    print("| " + " | ".join(head + ["failed checks"]) + " |")
    print("|---|" + "---:|" * (3 * len(runs)) + "---|")
    for t in tests:
        cells, notes = [t], []
        for label, run in runs:
            r = run.get(t)
            cells += [str(r[0]), r[3], r[4]] if r else ["-", "-", "-"]
            if r and r[5]:
                notes.append((label, "<br>".join(r[5][:2] + (["and %d more" % (len(r[5]) - 2)]
                                                            if len(r[5]) > 2 else []))))
        if len(notes) == len(runs) > 1 and len(set(n for _, n in notes)) == 1:
            notes = [("every run", notes[0][1])]  # the same failed checks in every run: once
        print("| " + " | ".join(cells + ["<br>".join("%s: %s" % n for n in notes)]) + " |")
    print()
    for label, run in runs:
        bad = sorted(t for t, r in run.items() if r[0] != 0)
        print("%s: %d tests, %d exited 0; not 0: %s." % (label, len(run), len(run) - len(bad),
                                                        ", ".join(bad) if bad else "none"))
    return 0


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    if "=" in argv[1]:
        return compare(argv[1:])
    if len(argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    run = read_run(argv[1])
    if run is None:
        return 1
    rows = sorted((name,) + r[:5] + ("<br>".join(r[5]),) for name, r in run.items())
    print("| test | exit | s | checks passed | failed | validation messages | failed checks |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for r in rows:
        print("| %s | %d | %d | %s | %s | %s | %s |" % r)
    bad = [r[0] for r in rows if r[1] != 0]
    print()
    print("%d tests, %d exited 0; not 0: %s." % (len(rows), len(rows) - len(bad), ", ".join(bad) if bad else "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
