# SPDX-License-Identifier: GPL-2.0-or-later
"""halcompile's modes besides --compile/--install (test_features.py): the
default (preprocess), -o, --document, --print-modinfo, the `comp` name,
usage errors, and the generated C's #line mapping."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

from hcomp_util import BUILD, COMPS, halcompile


def test_default_mode_writes_c_in_cwd(tmp_path: Path) -> None:
    shutil.copy(COMPS / "constant.comp", tmp_path)
    p = halcompile("constant.comp", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    c = (tmp_path / "constant.c").read_text()
    assert 'MODULE_LICENSE("GPL");' in c
    # the C part keeps its .comp line numbers: line 8 is "FUNCTION(_) ..."
    assert '#line 8 "constant.comp"\nFUNCTION(_) { out = value; }' in c
    p = halcompile("-o", "sub/x.c", "constant.comp", cwd=tmp_path)
    assert p.returncode == 0 and (tmp_path / "sub" / "x.c").exists()


def test_comp_is_the_same_program(tmp_path: Path) -> None:
    shutil.copy(COMPS / "constant.comp", tmp_path)
    assert (BUILD / "bin" / "comp").exists()
    import subprocess

    p = subprocess.run(
        [str(BUILD / "bin" / "comp"), "--print-modinfo", "constant.comp"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    q = halcompile("--print-modinfo", "constant.comp", cwd=tmp_path)
    assert p.returncode == 0 and p.stdout == q.stdout


def test_usage_errors(tmp_path: Path) -> None:
    p = halcompile(cwd=tmp_path)
    assert p.returncode == 2 and "usage: halcompile" in p.stderr
    p = halcompile("--compile", "--document", "x.comp", cwd=tmp_path)
    assert p.returncode == 2 and "not allowed with argument" in p.stderr
    p = halcompile("--user", "x.comp", cwd=tmp_path)
    assert p.returncode == 2 and "--user goes with --install" in p.stderr
    p = halcompile("-o", "a.c", "x.comp", "y.comp", cwd=tmp_path)
    assert p.returncode == 2 and "-o needs exactly one input file" in p.stderr
    p = halcompile("missing.comp", cwd=tmp_path)
    assert p.returncode == 1 and "missing.comp: no such file" in p.stderr


def test_print_modinfo(tmp_path: Path) -> None:
    shutil.copy(COMPS / "logic.comp", tmp_path)
    p = halcompile("--print-modinfo", "logic.comp", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines() == [
        "name: logic",
        "kind: realtime",
        "prefix: logic",
        "license: GPL",
        "description: Machinekit HAL component providing experimental logic functions",
        "parm: count:number of instances (int)",
        "parm: names:names of instances (array of charp)",
        "parm: personality:personality of each instance (array of int)",
        "pin: in-##[16] bit in",
        "pin: and bit out",
        "pin: or bit out",
        "pin: xor bit out",
        "function: _ nofp",
    ]


DOCUMENTED = r'''
component docd "A \\fBdocumented\\fR component";
pin in float in-#[2] = 1.5 "the inputs";
pin out float out "the \\fIsum\\fR";
param rw s32 mode if personality & 1 "only with an odd personality";
function update nofp "does the work";
modparam int debug = 0 "more messages";
option personality;
description """
First paragraph.
.PP
Second paragraph with \\fBbold\\fR.""";
notes "A note.";
examples "loadrt docd count=2";
see_also "sum2(9)";
author "A. Person";
license "GPL";
;;
FUNCTION(update) { out = in(0) + in(1); }
'''


def test_document(tmp_path: Path) -> None:
    """Doc strings are groff (backslash escapes interpreted, so \\fB in the
    file is the font change \\fB, as the seed says)."""
    (tmp_path / "docd.comp").write_text(DOCUMENTED)
    p = halcompile("--document", "docd.comp", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    md = (tmp_path / "docd.md").read_text()
    assert md.startswith("<!-- SPDX-License-Identifier: GPL-2.0-or-later -->\n# docd(9)\n")
    sections = re.findall(r"^## (.+)$", md, re.M)
    assert sections == [
        "NAME",
        "SYNOPSIS",
        "DESCRIPTION",
        "FUNCTIONS",
        "PINS",
        "PARAMETERS",
        "MODULE PARAMETERS",
        "EXAMPLES",
        "NOTES",
        "AUTHOR",
        "LICENSE",
        "SEE ALSO",
    ]
    assert "docd - A **documented** component" in md
    assert "    loadrt docd [count=N | names=name1[,name2...]] [personality=P1[,P2...]]" in md
    assert "First paragraph.\n\nSecond paragraph with **bold**." in md
    assert "* **docd.N.update** (no floating point) - does the work" in md
    assert "* **docd.N.in-0 ... in-1** float IN (default: 1.5) - the inputs" in md
    assert "* **docd.N.out** float OUT - the *sum*" in md
    assert "* **docd.N.mode** s32 RW (only if personality & 1) - only with an odd" in md
    assert "* **debug** (int) (default: 0) - more messages" in md
    p = halcompile("--document", "-o", "man/x.md", "docd.comp", cwd=tmp_path)
    assert p.returncode == 0 and (tmp_path / "man" / "x.md").read_text() == md


def test_document_userspace(tmp_path: Path) -> None:
    shutil.copy(COMPS / "rand.comp", tmp_path)
    p = halcompile("--document", "rand.comp", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    md = (tmp_path / "rand.md").read_text()
    assert "# rand(1)" in md and "    loadusr rand" in md
    assert "* **rand.out** float OUT" in md


def test_in_pins_are_read_only(tmp_path: Path) -> None:
    """Assigning to an `in` pin is a compile error at the .comp line (the
    accessor is an rvalue, as LinuxCNC's)."""
    (tmp_path / "ro.comp").write_text(
        'component ro;\npin in float x;\nfunction _;\nlicense "GPL";\n;;\nx = 1;\n'
    )
    p = halcompile("--compile", "ro.comp", cwd=tmp_path)
    assert p.returncode == 1
    assert re.search(r"ro\.comp:6:\d+: error: lvalue required", p.stderr), p.stderr


PASSTHROUGH = """#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
import time
import hal

h = hal.component("passthrough")
h.newpin("in", hal.HAL_FLOAT, hal.HAL_IN)
h.newpin("out", hal.HAL_FLOAT, hal.HAL_OUT)
h.ready()
try:
    while 1:
        time.sleep(0.01)
        h["out"] = h["in"]
except KeyboardInterrupt:
    raise SystemExit
"""


def test_install_python_userspace(tmp_path: Path) -> None:
    """The seed's passthrough Python component installed as a program."""
    from hcomp_util import hal_env, halrun, pins, python_sanitizer_env

    (tmp_path / "passthrough.py").write_text(PASSTHROUGH)
    env = hal_env()
    env["HALCOMPILE_BINDIR"] = str(tmp_path / "bin")
    p = halcompile("--install", "passthrough.py", cwd=tmp_path, env=env)
    assert p.returncode == 1 and "only be installed with --userspace" in p.stderr
    p = halcompile("--install", "--userspace", "passthrough.py", cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr
    prog = tmp_path / "bin" / "passthrough"
    assert prog.stat().st_mode & 0o111
    hal = f"loadusr -Wn passthrough {prog}\nsetp passthrough.in 3.14\nloadusr -w sleep 0.2\nshow pin\n"
    p = halrun(hal, tmp_path, python_sanitizer_env(env))
    assert p.returncode == 0, p.stderr
    assert pins(p.stdout)["passthrough.out"] == ("float", "OUT", "3.14")


USER_C = r"""
/* SPDX-License-Identifier: GPL-2.0-or-later */
#include <signal.h>
#include <unistd.h>
#include "hal.h"

static volatile sig_atomic_t done;
static void stop(int sig) { (void)sig; done = 1; }

int main(void)
{
    hal_s32_t **p;
    int id = hal_init("userc");
    if (id < 0)
        return 1;
    p = hal_malloc(sizeof(*p));
    if (p == NULL || hal_pin_s32_new("userc.out", HAL_OUT, p, id) < 0) {
        hal_exit(id);
        return 1;
    }
    **p = 11;
    signal(SIGTERM, stop);
    hal_ready(id);
    while (!done)
        usleep(1000);
    hal_exit(id);
    return 0;
}
"""


def test_compile_userspace_c(tmp_path: Path) -> None:
    from hcomp_util import hal_env, halrun, pins

    (tmp_path / "userc.c").write_text(USER_C)
    p = halcompile("--compile", "--userspace", "userc.c", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "userc").is_file() and not (tmp_path / "userc.so").exists()
    p = halrun(f"loadusr -Wn userc {tmp_path / 'userc'}\nshow pin\n", tmp_path, hal_env())
    assert p.returncode == 0, p.stderr
    assert pins(p.stdout)["userc.out"] == ("s32", "OUT", "11")


def test_document_groff_lists(tmp_path: Path) -> None:
    """The seed's logic.comp description (.IP \\(bu items) becomes a list."""
    shutil.copy(COMPS / "logic.comp", tmp_path)
    assert halcompile("--document", "logic.comp", cwd=tmp_path).returncode == 0
    md = (tmp_path / "logic.md").read_text()
    assert (
        "by adding:\n\n* The number of input pins, usually from 2 to 16\n"
        "* 256 (0x100)  if the 'and' output is desired\n"
        "* 512 (0x200)  if the 'or' output is desired\n"
        "* 1024 (0x400)  if the 'xor' (exclusive or) output is desired\n\n## FUNCTIONS"
    ) in md
