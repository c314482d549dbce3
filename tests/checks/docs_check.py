#!/usr/bin/env python3
"""docs_check.py ROOT: the documentation rules that a test can keep.

Fails (one line per break, exit 1) when:
  - README.md is over 12,000 bytes;
  - a tracked file's path contains "issue" (any case);
  - README.md, docs/**/*.md (CHANGELOG.md aside), pipelines/README.md,
    assets/**/README.md or tests/**/README.md name an issue number, or so
    does a tracked source, shader, script or build file (CHANGELOG.md is the
    only file that names issues; docs/results/ holds run outputs);
  - code embedded in README.md or a docs/ page differs from the file it
    names: the line `<!-- code: PATH -->` or `<!-- code: PATH:FIRST-LAST -->`
    stands right before a ``` block whose lines must be byte-identical to PATH
    (or to its lines FIRST..LAST, 1-based, inclusive); README.md must embed
    at least one (its small pass);
  - a relative markdown link `](path)` in README.md or docs/**/*.md (outside
    docs/results/) names a file or folder that does not exist.
Standard library only.
"""
import os
import re
import subprocess
import sys

README_LIMIT = 12000
ISSUE_RE = re.compile(r"(?i)\bissues? *#?[0-9]+")
CODE_MARK_RE = re.compile(r"^<!-- code: ([^ :]+)(?::([0-9]+)-([0-9]+))? -->$")
LINK_RE = re.compile(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"],
                             capture_output=True, check=True).stdout
        files = [f for f in out.decode("utf-8", "replace").split("\0") if f]
        if files:
            return files
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames
                       if d not in (".git", "build") and not d.startswith("build-")]
        for name in filenames:
            files.append(os.path.relpath(os.path.join(dirpath, name), root))
    return files


SOURCE_EXT = (".c", ".h", ".cpp", ".hpp", ".glsl", ".comp", ".frag", ".vert", ".py", ".sh", ".json",
              ".cmake", ".txt", ".sbatch", ".in")


def source_files(files):
    """tracked sources, shaders, scripts and build files (docs/results/ aside)"""
    return [f for f in files
            if not f.startswith("docs/results/") and (f.endswith(SOURCE_EXT) or f == ".ci/run")]


def doc_pages(files):
    pages = []
    for f in files:
        if not f.endswith(".md"):
            continue
        base = os.path.basename(f)
        if f == "README.md":
            pages.append(f)
        elif f.startswith("docs/") and base != "CHANGELOG.md":
            pages.append(f)
        elif f == "pipelines/README.md":
            pages.append(f)
        elif (f.startswith("assets/") or f.startswith("tests/")) and base == "README.md":
            pages.append(f)
    return sorted(pages)


def read_bytes(path):
    with open(path, "rb") as fh:
        return fh.read()


def check_code_blocks(root, page, errors):
    """the embedded code of one page; returns how many marks it has"""
    path = os.path.join(root, page)
    lines = read_bytes(path).split(b"\n")
    found = 0
    for i, raw in enumerate(lines):
        m = CODE_MARK_RE.match(raw.decode("utf-8", "replace").rstrip("\r"))
        if not m:
            continue
        found += 1
        src, first, last = m.group(1), m.group(2), m.group(3)
        where = "%s:%d" % (page, i + 1)
        if i + 1 >= len(lines) or not lines[i + 1].startswith(b"```"):
            errors.append("%s: code mark for %s is not followed by a ``` block" % (where, src))
            continue
        end = None
        for j in range(i + 2, len(lines)):
            if lines[j].rstrip(b"\r") == b"```":
                end = j
                break
        if end is None:
            errors.append("%s: code block for %s is not closed" % (where, src))
            continue
        block = lines[i + 2:end]
        src_path = os.path.join(root, src)
        if not os.path.isfile(src_path):
            errors.append("%s: embedded file %s does not exist" % (where, src))
            continue
        src_lines = read_bytes(src_path).split(b"\n")
        if src_lines and src_lines[-1] == b"":
            src_lines = src_lines[:-1]
        if first is not None:
            a, b = int(first), int(last)
            if a < 1 or b < a or b > len(src_lines):
                errors.append("%s: line range %d-%d is outside %s (%d lines)"
                              % (where, a, b, src, len(src_lines)))
                continue
            want = src_lines[a - 1:b]
            label = "%s:%d-%d" % (src, a, b)
        else:
            want = src_lines
            label = src
        if block != want:
            for k in range(max(len(block), len(want))):
                got_k = block[k] if k < len(block) else None
                want_k = want[k] if k < len(want) else None
                if got_k != want_k:
                    errors.append("%s: embedded code differs from %s at its line %d"
                                  % (where, label, k + 1))
                    break
    return found


def check_links(root, page, errors):
    text = read_bytes(os.path.join(root, page)).decode("utf-8", "replace")
    in_fence = False
    for n, line in enumerate(text.split("\n"), 1):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        for m in LINK_RE.finditer(line):
            target = m.group(1)
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("#"):
                continue
            target = target.split("#", 1)[0].split("?", 1)[0]
            if not target:
                continue
            if target.startswith("/"):
                errors.append("%s:%d: absolute link %s" % (page, n, target))
                continue
            full = os.path.normpath(os.path.join(root, os.path.dirname(page), target))
            if not os.path.exists(full):
                errors.append("%s:%d: link to missing %s" % (page, n, target))


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: docs_check.py ROOT\n")
        return 2
    root = argv[1]
    errors = []

    readme = os.path.join(root, "README.md")
    if not os.path.isfile(readme):
        errors.append("README.md: missing")
    else:
        size = os.path.getsize(readme)
        if size > README_LIMIT:
            errors.append("README.md: %d bytes, over the %d-byte limit" % (size, README_LIMIT))

    files = tracked_files(root)
    for f in files:
        if "issue" in f.lower():
            errors.append("%s: file path names an issue" % f)

    for page in doc_pages(files) + source_files(files):
        full = os.path.join(root, page)
        if not os.path.isfile(full):
            continue
        text = read_bytes(full).decode("utf-8", "replace")
        for n, line in enumerate(text.split("\n"), 1):
            m = ISSUE_RE.search(line)
            if m:
                errors.append("%s:%d: names an issue number (%s)" % (page, n, m.group(0)))

    if os.path.isfile(readme):
        link_pages = ["README.md"] + sorted(
            f for f in files
            if f.startswith("docs/") and not f.startswith("docs/results/") and f.endswith(".md"))
        for page in link_pages:
            if os.path.isfile(os.path.join(root, page)):
                check_links(root, page, errors)
                found = check_code_blocks(root, page, errors)
                if page == "README.md" and found == 0:
                    errors.append("README.md: no embedded pass code (<!-- code: renderer/passes/... --> before a ``` block)")

    for e in errors:
        print(e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
