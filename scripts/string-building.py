#!/usr/bin/env python3
"""Finds (and with --fix rewrites) string concatenations that start with a string literal.

`"text" + s` calls operator+(const char*, std::string&&), which inserts at the front of the
temporary; GCC 12 at -O2/-O3 misreads that insert as overlapping memcpy and warns (-Wrestrict),
which fails a user's -Werror build. The library builds every such message with
cellforge::detail::cat(...) (core/detail/text.hpp) instead.

    string-building.py [--fix] FILE...     exit 1 (check) when a chain is found
"""
import re
import sys

TERMINATORS = {",", ";", ")", "]", "}", "?", ":", "==", "!=", "&&", "||", "=", "+=", "<<", ">>"}


def tokenize(text):
    """Yields (kind, start, end): kind is 'str', 'chr', 'id', 'num', 'op', 'open', 'close'."""
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c.isspace():
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
        elif c == '"' or (c in "uUL" and re.match(r'(u8|u|U|L)?"', text[i:i + 3])):
            j = text.index('"', i) + 1
            while text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            yield ("str", i, j + 1)
            i = j + 1
        elif c == "R" and text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.index(")" + m.group(1) + '"', i) + len(m.group(1)) + 2
            yield ("str", i, end)
            i = end
        elif c == "'":
            j = i + 1
            while text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            yield ("chr", i, j + 1)
            i = j + 1
        elif c.isalpha() or c == "_":
            j = i
            while j < n and (text[j].isalnum() or text[j] == "_"):
                j += 1
            yield ("id", i, j)
            i = j
        elif c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            m = re.match(r"[0-9.]+([eE][+-]?[0-9]+)?[a-zA-Z0-9_']*", text[i:])
            yield ("num", i, i + m.end())
            i += m.end()
        elif c in "([{":
            yield ("open", i, i + 1)
            i += 1
        elif c in ")]}":
            yield ("close", i, i + 1)
            i += 1
        else:
            for op in ("<<=", ">>=", "->", "::", "++", "--", "+=", "-=", "==", "!=", "&&", "||", "<<", ">>", "<=",
                       ">="):
                if text.startswith(op, i):
                    yield ("op", i, i + len(op))
                    i += len(op)
                    break
            else:
                yield ("op", i, i + 1)
                i += 1


def chains(text):
    """Spans (start, end, [operand spans]) of `+` chains whose first operand is a string literal
    (adjacent literals count as one) or std::string(...)."""
    toks = list(tokenize(text))
    val = [text[a:b] for _, a, b in toks]
    out = []
    k = 0
    while k < len(toks):
        kind = toks[k][0]
        prev = val[k - 1] if k > 0 else ";"
        starts = False
        first_end = k
        if kind == "str" and prev not in ("+",) and toks[k - 1][0] != "str":
            first_end = k
            while first_end + 1 < len(toks) and toks[first_end + 1][0] == "str":
                first_end += 1
            starts = True
        elif (kind == "id" and val[k] == "std" and k + 3 < len(toks) and val[k + 1] == "::"
              and val[k + 2] == "string" and val[k + 3] == "(" and prev != "+" and prev != "::"):
            depth, j = 0, k + 3
            while True:
                if toks[j][0] == "open":
                    depth += 1
                elif toks[j][0] == "close":
                    depth -= 1
                    if depth == 0:
                        break
                j += 1
            first_end = j
            starts = True
        if not starts or first_end + 1 >= len(toks) or val[first_end + 1] != "+":
            k += 1
            continue
        # Operands separated by '+' at depth 0, up to a terminator at depth 0.
        operands = [(toks[k][1], toks[first_end][2])]
        j = first_end + 1
        while j < len(toks) and val[j] == "+":
            j += 1
            depth, a = 0, j
            while j < len(toks):
                t, v = toks[j][0], val[j]
                if t == "open":
                    depth += 1
                elif t == "close":
                    if depth == 0:
                        break
                    depth -= 1
                elif depth == 0 and (v in TERMINATORS or v == "+"):
                    break
                j += 1
            operands.append((toks[a][1], toks[j - 1][2]))
        out.append((operands[0][0], operands[-1][1], operands))
        k = j
    return out


def fix(text):
    pieces, last = [], 0
    for start, end, operands in chains(text):
        pieces.append(text[last:start])
        pieces.append("cellforge::detail::cat(" + ", ".join(text[a:b] for a, b in operands) + ")")
        last = end
    pieces.append(text[last:])
    return "".join(pieces)


def main(argv):
    do_fix = "--fix" in argv
    files = [a for a in argv if a != "--fix"]
    found = 0
    for path in files:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        hits = chains(text)
        if not hits:
            continue
        if do_fix:
            new = fix(text)
            if "core/detail/text.hpp" not in new and not path.endswith("core/detail/text.hpp"):
                line = '#include "cellforge/core/detail/text.hpp"\n'
                incs = list(re.finditer(r'^#include "cellforge/[^"]+"\n', new, re.M))
                after = [m for m in incs if m.group(0) > line]
                if after:
                    at = after[0].start()
                elif incs:
                    at = incs[-1].end()
                else:
                    sys_incs = list(re.finditer(r"^#include <[^>]+>\n", new, re.M))
                    at = sys_incs[-1].end() if sys_incs else 0
                    line = "\n" + line if sys_incs else line
                new = new[:at] + line + new[at:]
            with open(path, "w", encoding="utf-8") as f:
                f.write(new)
            print(f"{path}: {len(hits)} rewritten")
        else:
            for start, _, _ in hits:
                line = text.count("\n", 0, start) + 1
                print(f"{path}:{line}: a string built from a literal with '+': use cellforge::detail::cat")
        found += len(hits)
    if not do_fix and found:
        print(f"{found} string concatenations start with a literal (GCC 12 -Wrestrict at -O3)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
