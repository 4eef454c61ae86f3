#!/usr/bin/env python3
"""Structure limits (issue 22): no source file over 700 lines unless it says
'// Why one file:' in its first 40 lines, and no function body over 120 lines.
Usage: scripts/structure_check.py [DIR...]  (default: builder kiosk platform shared)
Prints each breach; exits 1 when there is one. Tests and generated files are not checked."""
import os, re, sys

MAX_FILE, MAX_FUNC = 700, 120
EXTS = ('.cpp', '.h', '.hpp', '.c')
CONTROL = re.compile(r'\b(if|for|while|switch|catch|do|else|try)\b\s*(\(|\{|$)')


def strip(text):
    """Blanks comments, string and char literals (keeps newlines)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if not m:
                out.append(c); i += 1; continue
            end = ')' + m.group(1) + '"'
            j = text.find(end, i)
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(' ' * (j + 1 - i)); i = j + 1
        else:
            out.append(c); i += 1
    return ''.join(out)


def functions(code):
    """(start_line, end_line, header) of brace blocks that are function bodies
    (opened after ')' and not by a control statement), outermost only."""
    stack, found = [], []
    line = 1
    for idx, c in enumerate(code):
        if c == '\n':
            line += 1
        elif c == '{':
            before = code[max(0, idx - 300):idx]
            head = before.split(';')[-1].split('}')[-1].split('{')[-1]
            is_func = bool(re.search(r'\)\s*(const|noexcept|override|final|mutable|->\s*[\w:<>,\s*&]+|\s)*$', head)) \
                and not CONTROL.search(head.strip().split('\n')[-1] if head.strip() else '') \
                and not re.search(r'\[[^\]]*\]\s*\([^)]*\)\s*(mutable\s*)?(->[^{]*)?$', head)
            inside_func = any(kind for kind, _, _ in stack)
            stack.append((is_func and not inside_func, line, head.strip().replace('\n', ' ')[-80:]))
        elif c == '}':
            if stack:
                is_func, start, head = stack.pop()
                if is_func:
                    found.append((start, line, head))
    return found


def main(dirs):
    bad = 0
    for d in dirs:
        for root, _, files in os.walk(d):
            for f in sorted(files):
                if not f.endswith(EXTS):
                    continue
                path = os.path.join(root, f)
                text = open(path, encoding='utf-8', errors='replace').read()
                lines = text.count('\n')
                if lines > MAX_FILE and '// Why one file:' not in '\n'.join(text.split('\n')[:40]):
                    print(f'{path}: {lines} lines (> {MAX_FILE}, no "// Why one file:" line)')
                    bad += 1
                for start, end, head in functions(strip(text)):
                    if end - start + 1 > MAX_FUNC:
                        print(f'{path}:{start}: function of {end - start + 1} lines (> {MAX_FUNC}): {head}')
                        bad += 1
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:] or ['builder', 'kiosk', 'platform', 'shared']))
