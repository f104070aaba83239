# SPDX-License-Identifier: GPL-2.0-or-later
"""Parse a .comp file: the declarations, ``;;``, then C.

Grammar (the seed chapter "Comp HAL Component Generator", LinuxCNC 2.9):

    component HALNAME [DOC];
    pin DIR TYPE HALNAME [[SIZE] | [MAXSIZE : CONDSIZE]] [if COND] [= DEFAULT] [DOC];
    param DIR TYPE HALNAME ... (as pin);
    function HALNAME [fp | nofp] [DOC];
    option NAME [VALUE];
    variable CTYPE STARREDNAME [[SIZE]] [= DEFAULT];
    modparam CTYPE NAME [= DEFAULT] [DOC];
    description DOC;  notes DOC;  see_also DOC;  examples DOC;
    license STRING;  author STRING;  include <HEADER> | "HEADER";
    ;;
"""

from __future__ import annotations

import re
from pathlib import Path

from .model import (
    HAL_TYPES,
    PARAM_DIRS,
    PIN_DIRS,
    Component,
    Function,
    Item,
    ModParam,
    Pos,
    Variable,
)
from .scanner import CompError, Scanner

DOC_KEYWORDS = ("description", "notes", "see_also", "examples")
KEYWORDS = (
    "component",
    "pin",
    "param",
    "function",
    "option",
    "variable",
    "modparam",
    "license",
    "author",
    "include",
) + DOC_KEYWORDS
_CTYPE_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_STARRED = re.compile(r"\**[A-Za-z_][A-Za-z0-9_]*")
_OPTION_VALUE = re.compile(r'"(?:[^"\\\n]|\\.)*"|[^;\s]+')


def parse_file(path: Path) -> Component:
    try:
        text = path.read_text()
    except UnicodeDecodeError as e:
        raise CompError(Pos(str(path), 1, 1), f"not a text file: {e}") from None
    return parse_text(text, str(path))


def parse_text(text: str, filename: str) -> Component:
    return _Parser(Scanner(text, filename)).parse()


class _Parser:
    def __init__(self, sc: Scanner) -> None:
        self.sc = sc
        self.comp: Component | None = None

    def parse(self) -> Component:
        sc = self.sc
        while True:
            sc.skip()
            if sc.at_end():
                raise sc.error(
                    "missing ';;': the declarations must be followed by a line "
                    "holding only ';;' and then the C code"
                )
            if sc.at(";;"):
                self._code_start()
                break
            if sc.at(";"):
                sc.i += 1  # empty declaration
                continue
            start = sc.i
            word = sc.match(re.compile(r"[A-Za-z_][A-Za-z0-9_]*"))
            if word is None or word not in KEYWORDS:
                raise sc.error(
                    f"unknown declaration {sc.describe_next() if word is None else repr(word)}"
                    f" (expected one of: {', '.join(KEYWORDS)}, or ';;')",
                    start,
                )
            if self.comp is None and word != "component":
                raise sc.error(f"expected 'component NAME;' first, found '{word}'", start)
            getattr(self, f"_decl_{word}")(sc.pos(start))
            sc.expect(";", f"';' to end the {word} declaration")
        assert self.comp is not None
        return self.comp

    def _code_start(self) -> None:
        sc, comp = self.sc, self.comp
        if comp is None:
            raise sc.error("';;' before the 'component NAME;' declaration")
        p = sc.pos()
        nl = sc.text.find("\n", sc.i)
        rest = sc.text[sc.i + 2 : nl if nl >= 0 else len(sc.text)]
        if rest.strip() and not rest.strip().startswith("//"):
            comp.code = sc.text[sc.i + 2 :]
            comp.code_line = p.line
        else:
            comp.code = "" if nl < 0 else sc.text[nl + 1 :]
            comp.code_line = p.line + 1

    # ---- declarations -------------------------------------------------------

    def _doc(self) -> str:
        return self.sc.string("documentation") if self.sc.at_string() else ""

    def _decl_component(self, pos: Pos) -> None:
        if self.comp is not None:
            raise CompError(pos, f"second 'component' declaration (first at {self.comp.pos})")
        name = self.sc.ident("the component name (a C identifier)")
        self.comp = Component(name=name, pos=pos, doc=self._doc())

    def _item(self, kind: str, pos: Pos) -> None:
        sc = self.sc
        dirs = PIN_DIRS if kind == "pin" else PARAM_DIRS
        dpos = sc.here()
        d = sc.match(re.compile(r"[A-Za-z]+"))
        if d not in dirs:
            raise CompError(
                dpos,
                f"bad {kind} direction {repr(d) if d else sc.describe_next()} "
                f"(expected {' or '.join(dirs)})",
            )
        tpos = sc.here()
        t = sc.match(re.compile(r"[A-Za-z0-9_]+"))
        if t not in HAL_TYPES:
            raise CompError(
                tpos,
                f"bad {kind} type {repr(t) if t else sc.describe_next()} "
                f"(expected one of: {', '.join(HAL_TYPES)})",
            )
        npos = sc.here()
        name = sc.halname(f"the {kind} name")
        assert d is not None and t is not None
        item = Item(kind=kind, dir=d, type=HAL_TYPES[t], name=name, pos=npos)
        sc.skip()
        if sc.at("["):
            sc.i += 1
            item.size = sc.number("the array size")
            if item.size <= 0:
                raise sc.error(f"array size of {kind} '{name}' must be at least 1")
            sc.skip()
            if sc.at(":"):
                sc.i += 1
                item.condsize = sc.expr("array size expression", "]")
            sc.expect("]", "']' to close the array size")
        sc.skip()
        if sc.at_word("if"):
            sc.i += 2
            item.cond = sc.expr("condition", ";", stop_at_assign=True)
        sc.skip()
        if sc.at("=") and not sc.at("=="):
            sc.i += 1
            item.default = sc.expr("default value", ";", stop_at_assign=True)
        item.doc = self._doc()
        assert self.comp is not None
        self.comp.items.append(item)

    def _decl_pin(self, pos: Pos) -> None:
        self._item("pin", pos)

    def _decl_param(self, pos: Pos) -> None:
        self._item("param", pos)

    def _decl_function(self, pos: Pos) -> None:
        sc = self.sc
        npos = sc.here()
        name = sc.halname("the function name")
        f = Function(name=name, pos=npos)
        sc.skip()
        if sc.at_word("fp"):
            sc.i += 2
        elif sc.at_word("nofp"):
            sc.i += 4
            f.fp = False
        f.doc = self._doc()
        assert self.comp is not None
        self.comp.functions.append(f)

    def _decl_option(self, pos: Pos) -> None:
        sc = self.sc
        npos = sc.here()
        name = sc.ident("the option name")
        sc.skip()
        value = "yes"
        if not sc.at(";"):
            v = sc.match(_OPTION_VALUE)
            if v is None:
                raise sc.error(f"bad value for option {name}")
            value = v[1:-1] if v.startswith('"') else v
        assert self.comp is not None
        self.comp.options[name] = value
        self.comp.option_pos[name] = npos

    def _decl_variable(self, pos: Pos) -> None:
        sc = self.sc
        words: list[tuple[str, Pos]] = []
        while True:
            sc.skip()
            wpos = sc.pos()
            w = sc.match(_STARRED)
            if w is None:
                break
            words.append((w, wpos))
            sc.skip()
            if w.startswith("*") or sc.at("[") or sc.at("=") or sc.at(";"):
                break
        sc.skip()
        if sc.at("*"):
            raise sc.error("no space allowed between '*' and the variable name")
        if len(words) < 2:
            raise sc.error("expected 'variable CTYPE NAME', found " + sc.describe_next())
        name, npos = words[-1]
        ctype_words = [w for w, _ in words[:-1]]
        for w, wp in words[:-1]:
            if w.startswith("*"):
                raise CompError(wp, "no space allowed between '*' and the variable name")
        stars = name[: len(name) - len(name.lstrip("*"))]
        var = Variable(ctype=" ".join(ctype_words), name=name.lstrip("*"), stars=stars, pos=npos)
        sc.skip()
        if sc.at("["):
            sc.i += 1
            var.size = sc.number("the array size")
            if var.size <= 0:
                raise sc.error(f"array size of variable '{var.name}' must be at least 1")
            sc.expect("]", "']' to close the array size")
        sc.skip()
        if sc.at("="):
            sc.i += 1
            var.default = sc.expr("default value", ";")
        assert self.comp is not None
        self.comp.variables.append(var)

    def _decl_modparam(self, pos: Pos) -> None:
        sc = self.sc
        ctype = sc.ident("the modparam type (int, long, string or dummy)")
        npos = sc.here()
        name = sc.ident("the modparam name")
        mp = ModParam(ctype=ctype, name=name, pos=npos)
        sc.skip()
        if sc.at("="):
            sc.i += 1
            if sc.at_string():  # a string modparam's default: a C string literal
                start = sc.i
                sc.string("the default value")
                mp.default = sc.text[start : sc.i]
            else:
                mp.default = sc.expr("default value", ";", stop_at_assign=True)
        mp.doc = self._doc()
        assert self.comp is not None
        self.comp.modparams.append(mp)

    def _decl_license(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.license = self.sc.string("the license")

    def _decl_author(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.authors.append(self.sc.string("the author"))

    def _decl_description(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.description = self.sc.string("the description")

    def _decl_notes(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.notes.append(self.sc.string("the notes"))

    def _decl_see_also(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.see_also.append(self.sc.string("the see_also text"))

    def _decl_examples(self, pos: Pos) -> None:
        assert self.comp is not None
        self.comp.examples.append(self.sc.string("the examples"))

    def _decl_include(self, pos: Pos) -> None:
        sc = self.sc
        sc.skip()
        m = re.compile(r'<[^>\n]+>|"[^"\n]+"').match(sc.text, sc.i)
        if not m:
            raise sc.error('expected <header.h> or "header.h" after include')
        sc.i = m.end()
        assert self.comp is not None
        self.comp.includes.append(m.group(0))
