# SPDX-License-Identifier: GPL-2.0-or-later
"""Python is typed (docs/engineering-standards.md): every function of every
Python file of the tree annotates each parameter (``self``/``cls`` aside) and
its return type.  Files written before the check that other areas still
change are listed in scripts/typing-pending.txt; a listed file must exist and
still miss an annotation, so the list only shrinks.
"""

from __future__ import annotations

import ast
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PENDING = ROOT / "scripts" / "typing-pending.txt"


def _pending() -> list[str]:
    lines = PENDING.read_text().splitlines()
    return [line.strip() for line in lines if line.strip() and not line.startswith("#")]


def _python_files() -> list[str]:
    r = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.py"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return [f for f in r.stdout.split() if (ROOT / f).is_file()]


def unannotated(source: str, name: str) -> list[str]:
    """'file:line function: what is missing' for every incompletely typed function."""
    out = []
    for node in ast.walk(ast.parse(source, name)):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        a = node.args
        params = a.posonlyargs + a.args + a.kwonlyargs
        params += [p for p in (a.vararg, a.kwarg) if p is not None]
        missing = [p.arg for p in params if p.arg not in ("self", "cls") and p.annotation is None]
        if node.returns is None:
            missing.append("return")
        if missing:
            out.append(f"{name}:{node.lineno} {node.name}: {', '.join(missing)}")
    return out


def test_functions_are_annotated() -> None:
    pending = set(_pending())
    bad = []
    for f in _python_files():
        if f not in pending:
            bad += unannotated((ROOT / f).read_text(), f)
    assert not bad, "add type annotations:\n" + "\n".join(bad)


def test_pending_list_only_holds_untyped_files() -> None:
    stale = []
    for f in _pending():
        p = ROOT / f
        if not p.is_file():
            stale.append(f"{f}: no such file")
        elif not unannotated(p.read_text(), f):
            stale.append(f"{f}: fully annotated now")
    assert not stale, "remove from scripts/typing-pending.txt:\n" + "\n".join(stale)


def test_the_check_sees_what_is_missing() -> None:
    src = "def f(a, b: int, *c, **d) -> None: ...\nclass K:\n    def g(self, x: int): ...\n"
    assert unannotated(src, "x.py") == ["x.py:1 f: a, c, d", "x.py:3 g: return"]
