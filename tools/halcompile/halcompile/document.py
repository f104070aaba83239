# SPDX-License-Identifier: GPL-2.0-or-later
"""``halcompile --document``: a man page in the markdown format of docs/.

Documentation strings of a .comp file are groff -man text (the seed
chapter); the common requests and font escapes are turned into markdown
(.B/.I lines, \\fB...\\fR, .IP/.TP items, .PP/.br breaks), anything else is
kept as written.
"""

from __future__ import annotations

import re

from .model import Component, Item
from .names import comp_prefix, hal_name

_FONT = re.compile(r"\\f([BIRP])(.*?)(?=\\f[BIRP]|$)", re.S)


def groff_to_md(text: str) -> str:
    out: list[str] = []
    in_list = False  # inside an .IP/.TP item: text continues it, indented
    for line in text.strip("\n").split("\n"):
        s = line.rstrip()
        if s.startswith((".PP", ".LP", ".P ", ".sp")) or s in (".P", ".br"):
            out.append("")
            in_list = False
            continue
        m = re.match(r"\.(B|I|BI|BR|IR|RB|RI|IB)\s+(.*)", s)
        if m:
            mark = "**" if m.group(1).startswith("B") else "*"
            out.append(f"{mark}{m.group(2).strip(chr(34))}{mark}")
            continue
        if s.startswith(".IP") or s.startswith(".TP"):
            arg = s[3:].strip()
            bullet = arg.split()[0] if arg else ""
            if not in_list:
                out.append("")
            out.append("* " if bullet in ("", r"\(bu", "\\\\(bu") else f"* {bullet} ")
            in_list = True
            continue
        if s.startswith("."):
            out.append(s)
            continue
        text_line = _fonts(s)
        if in_list and out and out[-1].startswith("* ") and out[-1].endswith(" "):
            out[-1] += text_line
        elif in_list:
            out.append("  " + text_line)
        else:
            out.append(text_line)
    return re.sub(r"\n{3,}", "\n\n", "\n".join(out)).strip()


def _fonts(s: str) -> str:
    s = s.replace(r"\(bu", "-").replace(r"\-", "-").replace("\\\\", "\\")

    def rep(m: re.Match[str]) -> str:
        body = m.group(2)
        if not body:
            return ""
        if m.group(1) == "B":
            return f"**{body}**"
        if m.group(1) == "I":
            return f"*{body}*"
        return body

    return _FONT.sub(rep, s)


def _synopsis(c: Component) -> str:
    if c.userspace:
        return f"    loadusr {c.name}"
    opts = []
    if not (c.option("singleton") or c.option("count_function")):
        opts.append("[count=N | names=name1[,name2...]]")
    if c.has_personality:
        opts.append("[personality=P1[,P2...]]")
    for m in c.modparams:
        opts.append(f"[{m.name}=...]")
    return f"    loadrt {c.name} " + " ".join(opts)


def _inst(c: Component) -> str:
    p = comp_prefix(c.name)
    return p if c.option("singleton") or c.userspace else f"{p}.N"


def _item_line(c: Component, it: Item) -> str:
    name = hal_name(it.name)
    if it.is_array:
        first = re.sub(r"#+", lambda m: "0" * len(m.group(0)), name)
        last = re.sub(r"#+", lambda m: str(it.size - 1).rjust(len(m.group(0)), "0"), name)
        name = f"{first} ... {last}" if it.size > 1 else first
        if it.condsize:
            name += f" (count: {it.condsize}, at most {it.size})"
    line = f"* **{_inst(c)}.{name}** {it.type} {it.dir.upper()}"
    if it.default is not None:
        line += f" (default: {it.default})"
    if it.cond:
        line += f" (only if {it.cond})"
    if it.doc:
        line += " - " + groff_to_md(it.doc).replace("\n", "\n  ")
    return line


def document(c: Component) -> str:
    sec = 1 if c.userspace else 9
    L = ["<!-- SPDX-License-Identifier: GPL-2.0-or-later -->", f"# {c.name}({sec})", ""]
    L += ["## NAME", f"{c.name}" + (f" - {groff_to_md(c.doc)}" if c.doc else ""), ""]
    L += ["## SYNOPSIS", _synopsis(c), ""]
    if c.description:
        L += ["## DESCRIPTION", groff_to_md(c.description), ""]
    if c.functions:
        L.append("## FUNCTIONS")
        for f in c.functions:
            hn = hal_name(f.name)
            name = _inst(c) + (f".{hn}" if hn else "")
            fp = "floating point" if f.fp else "no floating point"
            line = f"* **{name}** ({fp})"
            if f.doc:
                line += " - " + groff_to_md(f.doc)
            L.append(line)
        L.append("")
    for kind, title in (("pin", "PINS"), ("param", "PARAMETERS")):
        items = [it for it in c.items if it.kind == kind]
        if items:
            L.append(f"## {title}")
            L += [_item_line(c, it) for it in items]
            L.append("")
    if c.modparams:
        L.append("## MODULE PARAMETERS")
        for m in c.modparams:
            line = f"* **{m.name}**" + (f" ({m.ctype})" if m.ctype != "dummy" else "")
            if m.default is not None:
                line += f" (default: {m.default})"
            if m.doc:
                line += " - " + groff_to_md(m.doc)
            L.append(line)
        L.append("")
    for title, texts in (("EXAMPLES", c.examples), ("NOTES", c.notes)):
        if texts:
            L += [f"## {title}", "\n\n".join(groff_to_md(t) for t in texts), ""]
    if c.authors:
        L += ["## AUTHOR", ", ".join(c.authors), ""]
    L += ["## LICENSE", c.license, ""]
    if c.see_also:
        L += ["## SEE ALSO", "\n\n".join(groff_to_md(t) for t in c.see_also), ""]
    return "\n".join(L)
