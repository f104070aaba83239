# SPDX-License-Identifier: GPL-2.0-or-later
"""Bad .comp files: each error names FILE:LINE:COLUMN and the problem; the
command fails and leaves nothing behind (no .c, no half-installed module)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from hcomp_util import COMPS, halcompile

from halcompile.check import check
from halcompile.parser import parse_text
from halcompile.scanner import CompError

HEAD = 'component t;\nlicense "GPL";\n'

# (declarations before ";;" (after HEAD), line, column, message fragment)
BAD = [
    ("pin in flaot x;\n", 3, 8, "bad pin type 'flaot'"),
    ("pin up float x;\n", 3, 5, "bad pin direction 'up'"),
    ("param in float x;\n", 3, 7, "bad param direction 'in'"),
    ("pin in float x\nfunction _;\n", 4, 1, "expected ';' to end the pin declaration"),
    ("pin in float x;\npin out bit x;\n", 4, 13, "C name 'x' already used by pin 'x' at"),
    ("pin in float a_b;\npin out bit a-b;\n", 4, 13, "C name 'a_b' already used"),
    ("pin in float x-#;\n", 3, 14, "has '#' in its name but no [SIZE]"),
    ("pin in float x[4];\n", 3, 14, "is an array but its name has no '#'"),
    ("pin in float x-#.y-#[4];\n", 3, 14, "more than one block of '#'"),
    ("pin in float x-#[0];\n", 3, 19, "array size of pin 'x-#' must be at least 1"),
    ("pin in float x-#[4 : personality;\n", 3, 33, "expected ']' to end the array size"),
    ("pin in float x-#[4 : (personality];\n", 3, 34, "unbalanced ']'"),
    ("pinn in float x;\n", 3, 1, "unknown declaration 'pinn'"),
    ("variable int * p;\n", 3, 14, "no space allowed between '*' and the variable name"),
    ("variable int* p;\n", 3, 13, "no space allowed between '*' and the variable name"),
    ("variable double old;\npin in float old;\n", 4, 14, "C name 'old' already used by"),
    ("pin out float comp_id;\n", 3, 15, "the C name 'comp_id' is reserved"),
    ("pin out float period;\n", 3, 15, "the C name 'period' is reserved"),
    ("pin out float _comp_x;\n", 3, 15, "the C name '_comp_x' is reserved"),
    ("pin out float int;\n", 3, 15, "the C name 'int' is reserved"),
    ("function _;\nfunction _;\n", 4, 10, "function '_' declared twice"),
    ("function a;\nfunction b;\n", 4, 10, "must define each with FUNCTION(name)"),
    ("option userspace;\nfunction _;\n", 4, 10, "userspace component (option userspace) has no fu"),
    ("option default_count many;\n", 3, 8, "option default_count needs a number"),
    ('description "unterminated;\n', 3, 13, "unterminated string (a"),
    ('description """never closed;\n', 3, 13, 'unterminated """ string'),
    ("/* never closed\n", 3, 1, "unterminated /* comment"),
    ("modparam float x;\n", 3, 16, "modparam 'x': type must be int, long, string or dummy"),
    ("pin in float x = ;\n", 3, 18, "empty default value"),
    ("pin in float x-#[4] if ;\n", 3, 24, "empty condition"),
]


@pytest.mark.parametrize("decls,line,col,msg", BAD, ids=[b[3][:40] for b in BAD])
def test_declaration_errors(decls: str, line: int, col: int, msg: str) -> None:
    text = HEAD + decls + ";;\n"
    with pytest.raises(CompError) as e:
        check(parse_text(text, "t.comp"), expect_name="t")
    assert str(e.value).startswith(f"t.comp:{line}:{col}: error: "), str(e.value)
    assert msg in str(e.value)


def test_missing_double_semicolon() -> None:
    with pytest.raises(CompError) as e:
        parse_text(HEAD + "pin in float x;\nfunction _;\n", "t.comp")
    assert str(e.value).startswith("t.comp:5:1: error: missing ';;'"), str(e.value)


def test_component_first_and_once() -> None:
    with pytest.raises(CompError) as e:
        parse_text('license "GPL";\ncomponent t;\n;;\n', "t.comp")
    assert str(e.value).startswith("t.comp:1:1: error: expected 'component NAME;' first")
    with pytest.raises(CompError) as e:
        parse_text("component t;\ncomponent u;\n;;\n", "t.comp")
    assert str(e.value).startswith("t.comp:2:1: error: second 'component' declaration")


def test_license_required_and_name_matches_file() -> None:
    with pytest.raises(CompError) as e:
        check(parse_text("component t;\n;;\n", "t.comp"), expect_name="t")
    assert str(e.value).startswith("t.comp:1:1: error: no license")
    with pytest.raises(CompError) as e:
        check(parse_text(HEAD + ";;\n", "u.comp"), expect_name="u")
    assert "component name 't' does not match the file name 'u'" in str(e.value)


def test_cli_error_writes_nothing(tmp_path: Path) -> None:
    src = tmp_path / "t.comp"
    src.write_text(HEAD + "pin in flaot x;\n;;\n")
    p = halcompile(src.name, cwd=tmp_path)
    assert p.returncode == 1
    assert p.stderr.startswith("t.comp:3:8: error: bad pin type 'flaot'"), p.stderr
    assert not (tmp_path / "t.c").exists()
    assert sorted(x.name for x in tmp_path.iterdir()) == ["t.comp"]


def test_c_error_points_into_comp_file(tmp_path: Path) -> None:
    src = tmp_path / "t.comp"
    src.write_text(HEAD + "pin out float x;\nfunction _;\n;;\nx = undeclared_thing;\n")
    p = halcompile("--compile", src.name, cwd=tmp_path)
    assert p.returncode == 1
    assert f"{src}:6:" in p.stderr or "t.comp:6:" in p.stderr, p.stderr
    assert "undeclared_thing" in p.stderr
    assert not (tmp_path / "t.so").exists()


def test_failed_install_keeps_old_version(tmp_path: Path) -> None:
    """--install of a broken component leaves the installed one untouched
    and no temporary file behind."""
    rtlib = tmp_path / "rtlib"
    env = dict(os.environ, HALCOMPILE_RTLIB=str(rtlib))
    good = (COMPS / "constant.comp").read_text()
    (tmp_path / "constant.comp").write_text(good)
    p = halcompile("--install", "constant.comp", cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr
    before = (rtlib / "constant.so").read_bytes()
    (tmp_path / "constant.comp").write_text(good.replace("out = value;", "out = value +;"))
    p = halcompile("--install", "constant.comp", cwd=tmp_path, env=env)
    assert p.returncode == 1
    assert (rtlib / "constant.so").read_bytes() == before
    assert sorted(x.name for x in rtlib.iterdir()) == ["constant.so"]


def test_several_files_report_each(tmp_path: Path) -> None:
    (tmp_path / "a.comp").write_text(HEAD.replace("t;", "a;") + "pin in bad x;\n;;\n")
    (tmp_path / "b.comp").write_text(HEAD.replace("t;", "b;") + "pin out float y;\n;;\n")
    p = halcompile("a.comp", "b.comp", cwd=tmp_path)
    assert p.returncode == 1
    assert "a.comp:3:8: error: bad pin type 'bad'" in p.stderr
    assert (tmp_path / "b.c").exists()


# (C part after ";;" on line 6, line, column, message fragment)
MACRO_BAD = [
    ("function a;\nfunction b;\n", "FUNCTION(a) {}\n", 4, 10, "no FUNCTION(b)"),
    ("function a;\n", "FUNCTION(a) {}\nFUNCTION(c) {}\n", 6, 1, "FUNCTION(c) but no 'function c;'"),
    ("function _;\noption extra_setup;\n", "FUNCTION(_) {}\n", 4, 8, "no EXTRA_SETUP()"),
    ("function _;\n", "FUNCTION(_) {}\n  EXTRA_CLEANUP() {}\n", 6, 3, "without 'option extra_cl"),
]


@pytest.mark.parametrize("decls,code,line,col,msg", MACRO_BAD, ids=[m[4] for m in MACRO_BAD])
def test_function_macro_errors(decls: str, code: str, line: int, col: int, msg: str) -> None:
    text = HEAD + decls + ";;\n" + code
    with pytest.raises(CompError) as e:
        check(parse_text(text, "t.comp"), expect_name="t")
    assert str(e.value).startswith(f"t.comp:{line}:{col}: error: "), str(e.value)
    assert msg in str(e.value)


def test_macros_in_comments_do_not_count() -> None:
    text = (
        HEAD
        + 'function _;\n;;\n// EXTRA_SETUP() is not used\nFUNCTION(_) { (void)"FUNCTION(x)"; }\n'
    )
    check(parse_text(text, "t.comp"), expect_name="t")


def test_binary_file(tmp_path: Path) -> None:
    (tmp_path / "b.comp").write_bytes(b"component b;\n\xff\xfe\x00;;\n")
    p = halcompile("b.comp", cwd=tmp_path)
    assert p.returncode == 1
    assert p.stderr.startswith("b.comp:1:1: error: not a text file"), p.stderr
