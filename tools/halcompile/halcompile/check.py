# SPDX-License-Identifier: GPL-2.0-or-later
"""Semantic checks of a parsed component: everything that parses but cannot
make a working module fails here, with the place of the offending
declaration."""

from __future__ import annotations

import re
import sys
from pathlib import Path

from .model import KNOWN_OPTIONS, Component, Pos
from .cbody import blank_comments_and_strings
from .names import c_name, hal_name, hash_blocks
from .scanner import CompError

RESERVED = {
    "comp_id",
    "fperiod",
    "period",
    "rtapi_app_main",
    "rtapi_app_exit",
    "extra_setup",
    "extra_cleanup",
    "personality",
    "export",
    "prefix",
    "extra_arg",
}
C_KEYWORDS = set(
    "auto break case char const continue default do double else enum extern float for goto "
    "if inline int long register restrict return short signed sizeof static struct switch "
    "typedef union unsigned void volatile while _Bool".split()
)


def warn(pos: Pos, message: str) -> None:
    print(f"{pos}: warning: {message}", file=sys.stderr)


def check(comp: Component, expect_name: str | None = None) -> None:
    if expect_name is not None and comp.name != expect_name:
        raise CompError(
            comp.pos,
            f"component name '{comp.name}' does not match the file name '{expect_name}'",
        )
    if not comp.license:
        raise CompError(comp.pos, "no license: add e.g. 'license \"GPL\";'")
    _check_options(comp)
    _check_names(comp)
    _check_functions(comp)


def _check_options(comp: Component) -> None:
    for name, value in comp.options.items():
        pos = comp.option_pos[name]
        if name not in KNOWN_OPTIONS:
            warn(pos, f"unknown option '{name}' ignored")
        if name == "default_count":
            if not re.fullmatch(r"[0-9]+", value):
                raise CompError(pos, f"option default_count needs a number, not '{value}'")
        if name == "data" and not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", value):
            raise CompError(pos, f"option data needs a type name, not '{value}'")
    if comp.option("singleton") and comp.option("count_function"):
        raise CompError(
            comp.option_pos["count_function"], "option count_function with option singleton"
        )
    if comp.option("userinit") and not comp.userspace:
        warn(comp.option_pos["userinit"], "option userinit ignored without option userspace")


def _check_names(comp: Component) -> None:
    c_seen: dict[str, tuple[str, Pos]] = {}
    hal_seen: dict[str, tuple[str, Pos]] = {}

    def claim_c(cname: str, what: str, pos: Pos) -> None:
        if cname == "data" and "data" in comp.options:
            raise CompError(pos, f"{what}: 'data' is the instance data of option data")
        if cname in RESERVED or cname.startswith("_comp") or cname in C_KEYWORDS:
            raise CompError(pos, f"{what}: the C name '{cname}' is reserved")
        if cname in c_seen:
            other, opos = c_seen[cname]
            raise CompError(pos, f"{what}: C name '{cname}' already used by {other} at {opos}")
        c_seen[cname] = (what, pos)

    def claim_hal(hname: str, what: str, pos: Pos) -> None:
        if hname in hal_seen:
            other, opos = hal_seen[hname]
            raise CompError(pos, f"{what}: HAL name '{hname}' already used by {other} at {opos}")
        hal_seen[hname] = (what, pos)

    # Claims in source order, so a clash is reported at the later declaration.
    claims: list[tuple[Pos, str, str | None, str | None]] = []  # pos, what, C, HAL
    for it in comp.items:
        what = f"{it.kind} '{it.name}'"
        blocks = hash_blocks(it.name)
        if it.is_array and blocks == 0:
            raise CompError(it.pos, f"{what} is an array but its name has no '#'")
        if blocks > 1:
            raise CompError(it.pos, f"{what}: more than one block of '#' in the name")
        if not it.is_array and blocks:
            raise CompError(it.pos, f"{what} has '#' in its name but no [SIZE]")
        if not hal_name(it.name):
            raise CompError(it.pos, f"{what}: empty HAL name")
        claims.append((it.pos, what, c_name(it.name), hal_name(it.name)))
    for v in comp.variables:
        claims.append((v.pos, f"variable '{v.name}'", v.name, None))
    for f in comp.functions:
        what = f"function '{f.name}'"
        if "#" in f.name:
            raise CompError(f.pos, f"{what}: '#' is not allowed in function names")
        claims.append((f.pos, what, c_name(f.name), hal_name(f.name) or "(the instance name)"))
    for m in comp.modparams:
        if m.ctype not in ("int", "long", "string", "dummy"):
            raise CompError(m.pos, f"modparam '{m.name}': type must be int, long, string or dummy")
        if m.ctype != "dummy":
            claims.append((m.pos, f"modparam '{m.name}'", m.name, None))
    claims.sort(key=lambda c: (c[0].line, c[0].col))
    for pos, what, cname, hname in claims:
        if cname == "_" and "_" in c_seen:
            raise CompError(pos, "function '_' declared twice")
        if cname is not None and cname != "_":
            claim_c(cname, what, pos)
        elif cname == "_":
            c_seen["_"] = (what, pos)
        if hname is not None:
            claim_hal(hname, what, pos)


def _code_pos(comp: Component, offset: int) -> Pos:
    line = comp.code_line + comp.code.count("\n", 0, offset)
    col = offset - (comp.code.rfind("\n", 0, offset) + 1) + 1
    return Pos(comp.pos.file, line, col)


def _check_macros(comp: Component) -> None:
    """FUNCTION(x) for each declared function and none other; EXTRA_SETUP()
    / EXTRA_CLEANUP() exactly when their option is given (else the C
    compiler reports it in generated code, far from the cause)."""
    code = blank_comments_and_strings(comp.code)
    defined: dict[str, int] = {}
    for m in re.finditer(r"\bFUNCTION\s*\(\s*([A-Za-z_][A-Za-z0-9_]*)\s*\)", code):
        defined.setdefault(m.group(1), m.start())
    uses_macro = "FUNCTION" in comp.code
    declared = {c_name(f.name): f for f in comp.functions}
    if uses_macro and not comp.userspace:
        for cn, f in declared.items():
            if cn not in defined:
                raise CompError(
                    f.pos, f"function '{f.name}' is declared but the C code has no FUNCTION({cn})"
                )
    for cn, off in defined.items():
        if cn not in declared:
            raise CompError(
                _code_pos(comp, off), f"FUNCTION({cn}) but no 'function {cn};' is declared"
            )
    for macro, opt in (("EXTRA_SETUP", "extra_setup"), ("EXTRA_CLEANUP", "extra_cleanup")):
        mm = re.search(rf"\b{macro}\s*\(\s*\)", code)
        if comp.option(opt) and mm is None:
            raise CompError(
                comp.option_pos[opt], f"option {opt} but the C code has no {macro}() {{ ... }}"
            )
        if mm is not None and not comp.option(opt):
            raise CompError(_code_pos(comp, mm.start()), f"{macro}() without 'option {opt};'")


def _check_functions(comp: Component) -> None:
    _check_macros(comp)
    if comp.userspace:
        if comp.functions:
            raise CompError(
                comp.functions[0].pos, "a userspace component (option userspace) has no functions"
            )
        return
    if len(comp.functions) > 1 and "FUNCTION" not in comp.code:
        raise CompError(
            comp.functions[1].pos,
            "several functions are declared, so the C code must define each with FUNCTION(name)",
        )


def stem(path: Path) -> str:
    return path.name[: -len(path.suffix)] if path.suffix else path.name
