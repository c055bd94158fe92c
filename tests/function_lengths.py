#!/usr/bin/env python3
"""function_lengths.py LIMIT FILE... - prints every C++ function longer than
LIMIT lines (signature to closing brace) and exits 1 if there is one; used by
tests/check_sizes.sh. Comments, string and character literals and
preprocessor lines are removed first; then braces are matched, and a brace
opens a function where the statement before it is a parameter list (with
const, noexcept, override, a trailing return type or a constructor's member
initializers after it) outside any other function. Lambdas and blocks inside
a function count as part of it. A file whose braces do not match cannot be
measured and is reported as such."""
import re, sys

def strip(src):
    out = []; i = 0; n = len(src)
    while i < n:
        c = src[i]
        if src.startswith('//', i):
            j = src.find('\n', i); j = n if j < 0 else j
            i = j; continue
        if src.startswith('/*', i):
            j = src.find('*/', i + 2); j = n if j < 0 else j + 2
            out.append('\n' * src.count('\n', i, j)); i = j; continue
        m = re.match(r'R"([^(]*)\(', src[i:i+20]) if c == 'R' and (i == 0 or not (src[i-1].isalnum() or src[i-1] == '_')) else None
        if m:
            end = ')' + m.group(1) + '"'
            j = src.find(end, i + len(m.group(0))); j = n if j < 0 else j + len(end)
            out.append('""' + '\n' * src.count('\n', i, j)); i = j; continue
        if c in '"\'':
            if c == "'" and i > 0 and src[i-1].isalnum():  # digit separator 1'000
                out.append(c); i += 1; continue
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == '\\' else 1
            out.append(c + c + '\n' * src.count('\n', i, j)); i = j + 1; continue
        if c == '#' and (i == 0 or src[i-1] == '\n'):  # preprocessor line
            j = i
            while True:
                k = src.find('\n', j); k = n if k < 0 else k
                if src[k-1:k] == '\\': j = k + 1; continue
                break
            out.append('\n' * src.count('\n', i, k)); i = k; continue
        out.append(c); i += 1
    return ''.join(out)

def functions(path):
    code = strip(open(path, encoding='utf-8', errors='replace').read())
    stack = []  # (kind, start line, name)
    stmt_start = 0  # index where the current statement began
    line = 1; found = []
    for i, c in enumerate(code):
        if c == '\n': line += 1
        if c in ';{}':
            stack_top_was_init = False
            text = code[stmt_start:i]
            in_function = any(e[0] == 'function' for e in stack)
            if c == '{':
                head = ' '.join(text.split())
                if in_function: kind = 'block'
                elif re.search(r'\bnamespace\b', head) or head.startswith('extern "'): kind = 'namespace'
                elif re.search(r'\b(class|struct|union|enum)\b', head) and '(' not in head.split(':')[0]: kind = 'class'
                elif head.endswith(')') or re.search(r'\)\s*(const|noexcept|override|final|->.*|:.*)?\s*$', head): kind = 'function'
                else: kind = 'other'
                lead = len(text) - len(text.lstrip(' \t\n,'))
                first = line - code.count('\n', stmt_start + lead, i)
                stack.append((kind, first, head[-80:], stmt_start))
            elif c == '}' and not stack:
                raise ValueError(f'{path}:{line}: a closing brace without an opening one')
            elif c == '}':
                kind, first, head, head_start = stack.pop()
                stack_top_was_init = kind == 'function' and re.search(r'\)\s*:(?!:)', code[head_start:i]) is not None
                init_head_start = head_start
                if kind == 'function' and not any(e[0] == 'function' for e in stack):
                    found.append((line - first + 1, first, head))
            # A brace-initialized member (`: a_{x}, b_{y} {`) continues the
            # constructor's head: its body's brace follows.
            rest = code[i + 1:i + 200].lstrip()
            if c == '}' and stack_top_was_init and rest[:1] in (',', '{'):
                stmt_start = init_head_start
            else:
                stmt_start = i + 1
    if stack:
        raise ValueError(f'{path}:{stack[-1][1]}: a brace that is never closed')
    return found

limit = int(sys.argv[1]); bad = 0
for path in sys.argv[2:]:
    try:
        found = functions(path)
    except ValueError as e:
        print(f'{e} (cannot measure its functions)'); bad += 1; continue
    for length, first, head in found:
        if length > limit:
            print(f'{path}:{first}: {length} lines: {head}'); bad += 1
sys.exit(1 if bad else 0)
