#!/usr/bin/env python3
"""Lines of each function body in C++ sources, longest first.

    scripts/function_lengths.py [--over N] DIR_OR_FILE...

A brace counter, not a parser: a function is a `{` at the end of a line
whose text before it ends in `)` (optionally followed by const, override,
noexcept, a trailing return type or an initialiser list), counted to its
matching `}`. Lambdas inside a function count towards it. Strings, character
literals and comments are skipped.
"""
import argparse
import os
import re
import sys

HEAD = re.compile(r"\)\s*(const\s*)?(override\s*)?(noexcept\s*)?(->\s*[\w:<>,\s*&]+)?\s*(:.*)?$")
NOT_FUNCTION = re.compile(r"^\s*(if|for|while|switch|catch|else|do)\b|\[[^\]]*\]\s*\(.*\)\s*(mutable\s*)?(->.*)?$")


def strip(line, in_comment):
    """The line without comments and literals; whether a /* comment continues."""
    out, i = [], 0
    while i < len(line):
        if in_comment:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_comment = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_comment, i = True, i + 2
        elif line[i] in "\"'":
            quote, i = line[i], i + 1
            while i < len(line) and line[i] != quote:
                i += 2 if line[i] == "\\" else 1
            i += 1
        else:
            out.append(line[i])
            i += 1
    return "".join(out), in_comment


def functions(path):
    lines = open(path, encoding="utf-8", errors="replace").read().split("\n")
    code, in_comment = [], False
    for line in lines:
        text, in_comment = strip(line, in_comment)
        code.append(text)
    found, i = [], 0
    while i < len(code):
        text = code[i].rstrip()
        if text.endswith("{"):
            head = text[:-1].rstrip()
            # The signature may start on earlier lines.
            j, sig = i, head
            while j > 0 and sig.count("(") < sig.count(")"):
                j -= 1
                sig = code[j].strip() + " " + sig
            if HEAD.search(head) and not NOT_FUNCTION.search(sig.strip()) and "=" not in sig.split("(")[0]:
                depth, k = 0, i
                while k < len(code):
                    depth += code[k].count("{") - code[k].count("}")
                    if depth <= 0:
                        break
                    k += 1
                name = re.findall(r"([~\w:]+)\s*\(", sig)
                found.append((k - i - 1, path, j + 1, name[0] if name else "?"))
                i = k
        i += 1
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--over", type=int, default=0, help="list only functions longer than this")
    args = ap.parse_args()
    files = []
    for p in args.paths:
        if os.path.isdir(p):
            for root, _, names in os.walk(p):
                files += [os.path.join(root, n) for n in names if n.endswith((".cc", ".h")) and "_test" not in n]
        else:
            files.append(p)
    rows = sorted((f for path in sorted(files) for f in functions(path)), reverse=True)
    for length, path, line, name in rows:
        if length > args.over:
            print(f"{length:5d}  {path}:{line}  {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
