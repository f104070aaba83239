# SPDX-License-Identifier: GPL-2.0-or-later
"""Light rewriting of the C part of a .comp file.

Only one thing is rewritten: ``name[i]`` for a pin or parameter array
becomes ``name(i)``, so both spellings LinuxCNC users write reach the same
accessor macro.  Comments, string and character literals are left alone, as
are member accesses (``x.name[i]``, ``p->name[i]``).
"""

from __future__ import annotations

import re

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _skip_literal(code: str, i: int) -> int:
    """Index after the comment or literal starting at i (or i if none)."""
    if code.startswith("//", i):
        nl = code.find("\n", i)
        return len(code) if nl < 0 else nl
    if code.startswith("/*", i):
        end = code.find("*/", i + 2)
        return len(code) if end < 0 else end + 2
    if code[i] in "\"'":
        q = code[i]
        j = i + 1
        while j < len(code) and code[j] != q and code[j] != "\n":
            j += 2 if code[j] == "\\" else 1
        return min(j + 1, len(code))
    return i


def rewrite_array_subscripts(code: str, arrays: set[str]) -> str:
    if not arrays:
        return code
    out: list[str] = []
    stack: list[bool] = []  # per open '[': was it rewritten to '('?
    i = 0
    n = len(code)
    sig = "  "  # the last two significant characters before the current token
    while i < n:
        j = _skip_literal(code, i)
        if j != i:
            out.append(code[i:j])
            i = j
            sig = sig[1] + '"'
            continue
        c = code[i]
        m = _IDENT.match(code, i) if (c.isalpha() or c == "_") else None
        if m:
            word = m.group(0)
            out.append(word)
            i = m.end()
            member = sig[1] == "." or sig == "->"
            if word in arrays and not member:
                k = i
                while k < n and code[k] in " \t":
                    k += 1
                if k < n and code[k] == "[":
                    out.append(code[i:k] + "(")
                    stack.append(True)
                    i = k + 1
                    sig = "a("
                    continue
            sig = "aa"
            continue
        if c == "[":
            stack.append(False)
        elif c == "]" and stack and stack.pop():
            out.append(")")
            i += 1
            sig = sig[1] + ")"
            continue
        out.append(c)
        if not c.isspace():
            sig = sig[1] + c
        i += 1
    return "".join(out)


def uses_function_macro(code: str) -> bool:
    """The seed's rule: a one-function component whose C never mentions
    FUNCTION is the body of that function."""
    return "FUNCTION" in code


def blank_comments_and_strings(code: str) -> str:
    """The code with comments and string/char literals replaced by spaces
    (newlines kept), so searches see only real code at the same offsets."""
    out = []
    i = 0
    while i < len(code):
        j = _skip_literal(code, i)
        if j != i:
            out.append("".join(c if c == "\n" else " " for c in code[i:j]))
            i = j
        else:
            out.append(code[i])
            i += 1
    return "".join(out)
