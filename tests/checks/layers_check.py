#!/usr/bin/env python3
"""layers_check.py - the include rules of README "Architecture", checked on the source tree.

1. No include cycle among the project's headers (a header that includes itself through others).
2. A file of one library includes only headers of that library and of the libraries it may use
   (LAYERS below, the same picture as CMakeLists.txt's pg_library() calls): the build enforces
   this too, but only for what a library links, so a layer that links more than it should would
   pass there and fails here.
3. A header named *_internal.h (what the files of one split source share) is included only by files
   of its own folder: it is no part of its library's interface.
(The size rule is per function now: tests/checks/function_size.py.)
Exit 0 when all three hold; else one line per break and exit 1.
"""
import os, re, sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..'))
# folder -> folders whose headers it may include (transitively closed below)
LAYERS = {
    'core/base': [],
    'core/graph': ['core/base'],
    'core/dump': ['core/graph'],
    'core/vk': ['core/base'],
    'core/runtime': ['core/graph', 'core/vk'],
    'scene': ['core/base'],
    'image': ['core/base'],
    'color': ['core/base'],
    'renderer': ['core/runtime', 'scene', 'color', 'image', 'renderer/common'],
    'renderer/common': ['core/runtime', 'scene', 'color', 'image', 'renderer'],
    'renderer/passes': ['renderer', 'renderer/common'],
    'app/stats': ['core/base'],
    'app': ['renderer', 'core/dump', 'app/stats'],
    'app/bench': ['app'],
    'app/view': ['app'],
}

def closure(f, seen=None):
    seen = set() if seen is None else seen
    for d in LAYERS[f]:
        if d not in seen:
            seen.add(d)
            closure(d, seen)
    return seen

def main():
    headers = {}  # basename -> folder
    files = []
    for folder in LAYERS:
        d = os.path.join(ROOT, folder)
        for name in sorted(os.listdir(d)):
            p = os.path.join(d, name)
            if not os.path.isfile(p) or not re.search(r'\.(c|h|cpp)$', name):
                continue
            files.append((folder, name, p))
            if name.endswith('.h'):
                if name in headers:
                    print(f'header {name} is in both {headers[name]} and {folder}')
                    return 1
                headers[name] = folder
    errors = []
    graph = {}
    for folder, name, p in files:
        allowed = closure(folder) | {folder}
        incs = re.findall(r'^\s*#\s*include\s+"([^"]+)"', open(p, encoding='utf-8').read(), re.M)
        for inc in incs:
            if inc not in headers:
                continue  # a generated name (shader.h's examples) or a system header
            owner = headers[inc]
            if owner not in allowed:
                errors.append(f'{folder}/{name} includes {owner}/{inc}: {folder} may use only '
                              f'{", ".join(sorted(allowed - {folder})) or "nothing"}')
            if inc.endswith('_internal.h') and owner != folder:
                errors.append(f'{folder}/{name} includes {owner}/{inc}: an internal header is only '
                              f'for the files of {owner}')
            if name.endswith('.h'):
                graph.setdefault(name, []).append(inc)
    # cycles among headers: depth-first search with colours
    colour = {}
    def dfs(h, stack):
        colour[h] = 1
        for n in graph.get(h, []):
            if colour.get(n) == 1:
                errors.append('include cycle: ' + ' -> '.join(stack[stack.index(n):] + [n]))
            elif not colour.get(n):
                dfs(n, stack + [n])
        colour[h] = 2
    for h in sorted(graph):
        if not colour.get(h):
            dfs(h, [h])
    for e in errors:
        print(e)
    print(f'layers_check: {len(files)} files, {len(headers)} headers, {len(errors)} breaks')
    return 1 if errors else 0

if __name__ == '__main__':
    sys.exit(main())
