# SPDX-License-Identifier: GPL-2.0-or-later
"""Examples in the documentation (docs/*.md, README.md, examples/**/README.md),
found and run.

The rules (also in docs/engineering-standards.md, "Docs"):

* A fenced block whose info string is ``hal``, ``sh`` or ``python`` is an
  example and runs as a test:

  - ``hal``: a HAL file, run with ``halrun -S -f FILE`` (simulated clock);
  - ``sh``: a bash script (``set -e``);
  - ``python``: a Python script (the venv's Python; PYTHONPATH has the
    build's ``lib/python``, so ``import hal`` works).

  Each runs from the repository root with the build's ``bin/`` first on
  PATH, in its own HAL_INSTANCE and HOME, and must exit 0.
* A fenced ``output`` block right after an example: the example's stdout
  must be exactly that (trailing blanks ignored; a line ``...`` stands for
  any number of lines).
* ``/tmp/`` in an example, its output or its directives is replaced by a
  directory private to the run (parallel runs do not collide).
* Directives, in an HTML comment before the example (they apply to the next
  example block): ``<!-- test: DIRECTIVE; DIRECTIVE ... -->`` with

  - ``vboard ARGS``: start ``vboard ARGS`` before the example, wait for its
    ready line, stop it afterwards (may be given more than once);
  - ``exit N``: the example must exit with status N;
  - ``halrun ARGS``: halrun options for a ``hal`` example instead of ``-S``;
  - ``env NAME=VALUE``: an environment variable for the example;
  - ``hardware WHAT``: the example needs hardware a test machine does not
    have (a PCI card); the test skips, and that skip must be listed in
    tests/skips.txt like any other.
* Every code block inside a section whose heading says "example" must be an
  example (or its ``output``): what a page shows as an example runs.  The
  one exception is a ``text`` block, an illustration that is not a command
  (bytes on a wire, a diagram).
"""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

RUNNABLE = ("hal", "sh", "python")
FENCE = re.compile(r"^(```+|~~~+)\s*([^\s`]*)\s*(.*)$")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
DIRECTIVE = re.compile(r"^\s*<!--\s*test:\s*(.*?)\s*-->\s*$")
LIST_ITEM = re.compile(r"^\s*([-*+]|\d+[.)])\s")


@dataclass
class Block:
    """A code block of a page: fenced (with its info string) or indented."""

    doc: str
    line: int  # 1-based line of the opening fence or first indented line
    lang: str  # info string word, "" for none, "(indented)" for indented
    text: str
    section: str  # the heading the block is under
    directives: list[str] = field(default_factory=list)


@dataclass
class Example:
    """One runnable example with what it needs and what it must print."""

    doc: str
    line: int
    lang: str
    text: str
    output: str | None = None
    vboards: list[list[str]] = field(default_factory=list)
    exit: int = 0
    halrun: list[str] = field(default_factory=lambda: ["-S"])
    env: dict[str, str] = field(default_factory=dict)
    hardware: str = ""

    @property
    def id(self) -> str:
        return f"{self.doc}:{self.line}"


class DocError(Exception):
    """A page breaks the rules (message names file:line)."""


def blocks(path: Path, name: str | None = None) -> list[Block]:
    """Every code block of a Markdown page, in order, with pending directives."""
    name = name or path.name
    lines = path.read_text().splitlines()
    out: list[Block] = []
    section = ""
    pending: list[str] = []
    i = 0
    prev_blank = True
    prev_para_is_list = False
    while i < len(lines):
        line = lines[i]
        m = FENCE.match(line)
        if m:
            fence, lang = m.group(1), m.group(2)
            start = i
            body: list[str] = []
            i += 1
            while i < len(lines) and not lines[i].startswith(fence):
                body.append(lines[i])
                i += 1
            if i == len(lines):
                raise DocError(f"{name}:{start + 1}: code block not closed")
            out.append(Block(name, start + 1, lang, "\n".join(body) + "\n", section, pending))
            pending = []
            i += 1
            prev_blank = False
            continue
        d = DIRECTIVE.match(line)
        if d:
            pending = pending + [p.strip() for p in d.group(1).split(";") if p.strip()]
            i += 1
            continue
        h = HEADING.match(line)
        if h:
            section = h.group(2)
            prev_blank, prev_para_is_list = False, False
            i += 1
            continue
        if (
            prev_blank
            and not prev_para_is_list
            and (line.startswith("    ") or line.startswith("\t"))
        ):
            start = i
            body = []
            while i < len(lines) and (
                lines[i].startswith("    ") or lines[i].startswith("\t") or not lines[i].strip()
            ):
                body.append(lines[i][4:] if lines[i].startswith("    ") else lines[i].lstrip("\t"))
                i += 1
            while body and not body[-1].strip():
                body.pop()
            out.append(
                Block(name, start + 1, "(indented)", "\n".join(body) + "\n", section, pending)
            )
            pending = []
            prev_blank = True
            continue
        if line.strip():
            indented = line.startswith("    ") or line.startswith("\t")
            if prev_blank and not (indented and prev_para_is_list):
                prev_para_is_list = bool(LIST_ITEM.match(line))
            prev_blank = False
        else:
            prev_blank = True
        i += 1
    return out


def _apply(ex: Example, directive: str) -> None:
    word, _, rest = directive.partition(" ")
    rest = rest.strip()
    if word == "vboard" and rest:
        ex.vboards.append(shlex.split(rest))
    elif word == "exit" and rest.isdigit():
        ex.exit = int(rest)
    elif word == "halrun":
        ex.halrun = shlex.split(rest)
    elif word == "env" and "=" in rest:
        k, v = rest.split("=", 1)
        ex.env[k] = v
    elif word == "hardware" and rest:
        ex.hardware = rest
    else:
        raise DocError(f"{ex.id}: unknown test directive {directive!r}")


def examples(path: Path, name: str | None = None) -> list[Example]:
    """The runnable examples of a page; DocError when the page breaks the rules."""
    bs = blocks(path, name)
    out: list[Example] = []
    for n, b in enumerate(bs):
        if b.lang == "output":
            before = bs[n - 1] if n else None
            if (
                before is None
                or before.lang not in RUNNABLE
                or not out
                or out[-1].line != before.line
            ):
                raise DocError(f"{b.doc}:{b.line}: an output block must follow an example")
            out[-1].output = b.text
            continue
        if b.lang not in RUNNABLE:
            if b.directives:
                raise DocError(f"{b.doc}:{b.line}: test directives before a block that is not run")
            if "example" in b.section.lower() and b.lang != "text":
                raise DocError(
                    f"{b.doc}:{b.line}: a code block in section {b.section!r} is not run:"
                    f" make it a ```hal, ```sh or ```python block (or move it out of the"
                    f" examples)"
                )
            continue
        ex = Example(b.doc, b.line, b.lang, b.text)
        for d in b.directives:
            _apply(ex, d)
        out.append(ex)
    return out


def output_matches(got: str, want: str) -> bool:
    """got equals want line by line (trailing blanks ignored, ``...`` = any lines)."""
    g = [line.rstrip() for line in got.rstrip("\n").split("\n")] if got.strip() else []
    w = [line.rstrip() for line in want.rstrip("\n").split("\n")] if want.strip() else []

    def match(i: int, j: int) -> bool:
        if j == len(w):
            return i == len(g)
        if w[j] == "...":
            return any(match(k, j + 1) for k in range(i, len(g) + 1))
        return i < len(g) and g[i] == w[j] and match(i + 1, j + 1)

    return match(0, 0)
