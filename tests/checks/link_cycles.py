#!/usr/bin/env python3
"""link_cycles.py LIB.a... [--objects NAME OBJ.o...] - no call cycles between the files of a library.

For each library archive (and each named group of object files, e.g. the passgraph executable's
own objects), two object files form a cycle when each one uses (an undefined symbol) a symbol the
other defines. A library's files should call down to leaf files, never both ways: a cycle is the
seam of a file split in two that still works as one. Symbols come from `nm -A` (C and C++ objects).

Each cycle prints as "libX.a: a.o <-> b.o (a.o uses b_sym..., b.o uses a_sym...)". Those in
EXCEPTIONS ("libX.a: a.o <-> b.o", the objects sorted by name) are allowed, each with its reason;
an exception that no longer holds fails the check too, so the list stays true.
Exit 0 when no cycle is left but the listed ones; else 1.
"""
import os, re, subprocess, sys

# "group: a.o <-> b.o" (sorted by name) -> why the cycle stays for now
EXCEPTIONS = {
}


def objects_of(files):
    """global symbols defined and undefined symbols used, per object: ({obj: set}, {obj: set})."""
    out = subprocess.run(['nm', '-A', '-P'] + files, check=True, capture_output=True,
                         text=True).stdout
    defs, uses = {}, {}
    for line in out.splitlines():
        # "lib.a[obj.o]: name T value size" for an archive, "dir/obj.o: name U" for an object
        head, sep, rest = line.rpartition(': ')
        parts = rest.split()
        if not sep or len(parts) < 2:
            continue
        name, kind = parts[0], parts[1]
        m = re.match(r'.*\[(.*)\]$', head)
        obj = m.group(1) if m else os.path.basename(head)
        if kind == 'U':
            uses.setdefault(obj, set()).add(name)
        elif kind.isupper():  # global: T D B R, and weak V W (C++ inline functions)
            defs.setdefault(obj, set()).add(name)
    return defs, uses


def demangle(names):
    """C++ names as a reader knows them (c++filt), the arguments left out."""
    if not any(n.startswith('_Z') for n in names):
        return names
    out = subprocess.run(['c++filt'], input='\n'.join(names), capture_output=True,
                         text=True).stdout.split('\n')
    return [o.split('(')[0] for o in out[:len(names)]]


def cycles(group, files):
    defs, uses = objects_of(files)
    found = {}
    objs = sorted(set(defs) | set(uses))
    for i, a in enumerate(objs):
        for b in objs[i + 1:]:
            ab = sorted(uses.get(a, set()) & defs.get(b, set()))
            ba = sorted(uses.get(b, set()) & defs.get(a, set()))
            if ab and ba:
                key = f'{group}: {a} <-> {b}'
                found[key] = (f'{key} ({a} uses {", ".join(demangle(ab))}; '
                              f'{b} uses {", ".join(demangle(ba))})')
    return found


def main(argv):
    groups = []  # (name, [files])
    i = 0
    while i < len(argv):
        if argv[i] == '--objects':
            name = argv[i + 1]
            objs = []
            i += 2
            while i < len(argv) and argv[i] != '--objects' and not argv[i].endswith('.a'):
                objs.append(argv[i])
                i += 1
            groups.append((name, objs))
        else:
            groups.append((os.path.basename(argv[i]), [argv[i]]))
            i += 1
    found = {}
    for name, files in groups:
        found.update(cycles(name, files))
    bad = 0
    for key in sorted(found):
        if key in EXCEPTIONS:
            print(f'allowed: {found[key]}: {EXCEPTIONS[key]}')
        else:
            print(f'FAIL: {found[key]}')
            bad += 1
    for key in sorted(EXCEPTIONS):
        if key not in found:
            print(f'FAIL: EXCEPTIONS lists "{key}", which is no longer a cycle: drop it')
            bad += 1
    print(f'link_cycles: {len(groups)} groups, {len(found)} cycles, '
          f'{len(EXCEPTIONS)} exceptions, {bad} breaks')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
