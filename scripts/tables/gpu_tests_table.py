#!/usr/bin/env python3
"""gpu_tests_table.py DIR [--lavapipe-costs FILE] - a markdown table of one run of the GPU tests by
hand (scripts/gpu_tests_bundle.sh's run.sh): DIR holds run.sh's TEST.txt outputs and its summary
(summary.txt: "TEST rc=N S s validation messages: M" lines). One row per test: exit code, seconds,
checks passed and failed (the test's last "N passed, M failed" line), the validation messages it
counted, and its failed checks (file:line and message, shortened). Exit 1 when DIR has no summary."""
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


def main(argv):
    if len(argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    d = argv[1]
    summary = os.path.join(d, "summary.txt")
    if not os.path.exists(summary):
        sys.stderr.write("%s: no summary.txt\n" % d)
        return 1
    rows = []
    for line in open(summary, encoding="utf-8", errors="replace"):
        m = re.match(r"(\S+) rc=(\d+) (\d+) s validation messages: (.*)$", line.strip())
        if not m:
            continue
        name, rc, secs, msgs = m.group(1), int(m.group(2)), int(m.group(3)), m.group(4)
        path = os.path.join(d, name + ".txt")
        text = open(path, encoding="utf-8", errors="replace").read() if os.path.exists(path) else ""
        counts = re.findall(r"^%s: (\d+) passed, (\d+) failed" % re.escape(name), text, re.M)
        passed, failed = counts[-1] if counts else ("-", "-")
        rows.append((name, rc, secs, passed, failed, msgs if msgs != "none reported" else "-",
                     "<br>".join(failed_checks(text))))
    rows.sort()
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
