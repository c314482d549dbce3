#!/usr/bin/env python3
"""function_size.py [ROOT] [--list] - no function of the project's C and C++ sources is longer
than MAX_LINES lines, but those in EXCEPTIONS, each with its reason.

A function's length is counted from the line of its name to its closing brace. The parser is a
simple one: comments, strings, character literals and preprocessor lines are blanked (newlines
kept), then braces are matched. A brace block whose header ends in ")" (with C++ qualifiers or a
trailing return type after it) is a function; namespace, extern "C", struct, class, union and
enum bodies are looked into (so methods count on their own); anything else (an initializer) is
skipped. Lambdas and local classes count as part of the function they are in.

Every .c/.cpp under SOURCE_DIRS is read. An entry of EXCEPTIONS that is no longer over the limit
(or no longer exists) is a break too, so the list stays true. --list prints every function over
the limit with its length, longest first. Exit 0 when no break; else one line per break and 1.
"""
import os, re, sys

MAX_LINES = 120
SOURCE_DIRS = ('core', 'scene', 'color', 'image', 'renderer', 'app')

# "path:function" -> why it may be longer than MAX_LINES
EXCEPTIONS = {
}


def blank(text):
    """text with comments, strings, char literals and preprocessor lines replaced by spaces
    (newlines kept, so line numbers hold)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in ' \t':
            out.append(c)
            i += 1
            continue
        if line_start and c == '#':  # preprocessor line, with its continuations
            while i < n and text[i] != '\n':
                if text[i] == '\\' and i + 1 < n and text[i + 1] == '\n':
                    out.append(' \n')
                    i += 2
                    continue
                out.append(' ')
                i += 1
            continue
        line_start = False
        if c == '\n':
            out.append(c)
            line_start = True
            i += 1
        elif text.startswith('//', i):
            while i < n and text[i] != '\n':
                out.append(' ')
                i += 1
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c == 'R' and text.startswith('"', i + 1) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(')' + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            j = min(j + 1, n)
            out.append(c + ' ' * (j - i - 2) + c if j - i >= 2 else ' ' * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return ''.join(out)


FUNC_TAIL = re.compile(r'\)\s*(?:(?:const|noexcept|override|final|volatile|&|&&|mutable)\s*|'
                       r'->\s*[\w:<>,\s\*&]+|__attribute__\s*\(\(.*?\)\)\s*)*$', re.S)
OPEN_BODY = re.compile(r'\b(namespace|struct|class|union|extern|enum)\b')


def name_of(header, header_start, text):
    """(name, line) of the function whose header (text[header_start:]) ends before its body."""
    end = header.rfind(')')
    depth = 0
    for k in range(end, -1, -1):
        if header[k] == ')':
            depth += 1
        elif header[k] == '(':
            depth -= 1
            if depth == 0:
                break
    m = re.search(r'([~\w:]+(?:operator\s*\S+?)?)\s*$', header[:k])
    if not m:
        return '?', text.count('\n', 0, header_start + k) + 1
    return m.group(1), text.count('\n', 0, header_start + m.start(1)) + 1


def functions(text):
    """[(name, first line, last line)] of the functions in (blanked) text."""
    found = []
    n = len(text)

    def skip_block(i):  # i at '{': index after its matching '}'
        depth = 0
        while i < n:
            if text[i] == '{':
                depth += 1
            elif text[i] == '}':
                depth -= 1
                if depth == 0:
                    return i + 1
            i += 1
        return n

    def scan(i, stop):  # a level whose blocks may be functions: namespace / file / class body
        head = i
        while i < stop:
            c = text[i]
            if c in ';':
                head = i + 1
            elif c == '}':
                return i + 1
            elif c == '{':
                header = text[head:i]
                if FUNC_TAIL.search(header.rstrip()) and not re.search(r'=\s*$', header):
                    name, line = name_of(header.rstrip(), head, text)
                    j = skip_block(i)
                    found.append((name, line, text.count('\n', 0, j - 1) + 1))
                    i = j
                elif OPEN_BODY.search(header) and '=' not in header:
                    i = scan(i + 1, stop)
                else:
                    i = skip_block(i)
                head = i
                continue
            i += 1
        return i

    scan(0, n)
    return found


def measure(root):
    """{"path:function": lines} for every function of the sources."""
    sizes = {}
    for top in SOURCE_DIRS:
        for d, dirs, names in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(names):
                if not re.search(r'\.(c|cpp)$', name):
                    continue
                p = os.path.join(d, name)
                rel = os.path.relpath(p, root).replace(os.sep, '/')
                with open(p, encoding='utf-8') as fh:
                    text = blank(fh.read())
                for fn, a, b in functions(text):
                    key = f'{rel}:{fn}'
                    sizes[key] = max(sizes.get(key, 0), b - a + 1)
    return sizes


def main(argv):
    args = [a for a in argv if not a.startswith('--')]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), '..', '..'))
    sizes = measure(root)
    over = sorted(((n, k) for k, n in sizes.items() if n > MAX_LINES), reverse=True)
    if '--list' in argv:
        for n, k in over:
            print(f'{n:5d} {k}')
        return 0
    errors = []
    for n, k in over:
        if k not in EXCEPTIONS:
            errors.append(f'{k}: {n} lines, more than {MAX_LINES}: split it into named steps '
                          f'(or list it in EXCEPTIONS with the reason)')
    for k in sorted(EXCEPTIONS):
        if k not in sizes:
            errors.append(f'{k}: listed in EXCEPTIONS but no such function: drop it')
        elif sizes[k] <= MAX_LINES:
            errors.append(f'{k}: {sizes[k]} lines, no longer over {MAX_LINES}: drop it from '
                          f'EXCEPTIONS')
    for e in errors:
        print(e)
    print(f'function_size: {len(sizes)} functions, {len(over)} over {MAX_LINES} lines, '
          f'{len(EXCEPTIONS)} exceptions, {len(errors)} breaks')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
