# SPDX-License-Identifier: GPL-2.0-or-later
"""Each .comp feature, compiled by our halcompile and run in a real halrun
session: every pin/param type and direction with defaults (incl. s64/u64),
arrays with '#' numbering and both subscript spellings, several functions,
fp/nofp, variables, singleton, default_count, count_function, extra_setup /
extra_cleanup (with hal_* calls and comp_id), option data, modparam,
include, personality (condsize, if, set in EXTRA_SETUP), option rtapi_app no
with export(), userspace with userinit and count=/names= arguments.

Expected values come from the rules in docs/halcompile.md and the seed
chapter, worked out here by hand/Python, not from running the code."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from hcomp_util import COMPS, compile_ok, hal_env, halcompile, halrun, pins

TYPES = r"""
component types "every type and direction";
pin in bit b_in = 1;
pin in float f_in = 2.5;
pin in s32 s_in = -7;
pin in u32 u_in = 0xffffffff;
pin in s64 ls_in = -9000000000;
pin in u64 lu_in = 18000000000000000000ULL;
pin out bit b_out;
pin out float f_out;
pin out s32 s_out;
pin out u32 u_out;
pin out s64 ls_out;
pin out u64 lu_out;
pin io float f_io = 1.5 "incremented by each call of the _ function";
param rw bit pb = 1;
param r float pf = 0.25;
param rw signed ps = -3;
param r unsigned pu = 3;
param rw s64 pls = -5000000000;
param rw u64 plu = 5000000000;
pin out s32 idx#[3] = 4;
pin out float arr-##[12];
param rw u32 gains.#[2] = 10;
variable int hist[3] = 2;
variable double *unused_ptr;
function go nofp "integer work";
function _ fp;
license "GPL";
;;
FUNCTION(go) {
    int i;
    b_out = !b_in;
    s_out = s_in * 2;
    u_out = u_in - 1;
    ls_out = ls_in * 2;
    lu_out = lu_in + 1;
    for (i = 0; i < 3; i++)
        idx[i] = idx(i) + i + hist[i];
    gains(1) = gains[0] + 1;
    ps = pls / 1000000000;
    (void)unused_ptr;
}

FUNCTION(_) {
    int i;
    f_out = f_in * 2 + pf;
    f_io = f_io + 1;
    for (i = 0; i < 12; i++)
        arr[i] = i * 0.5;
}
"""


def test_types_arrays_functions(tmp_path: Path) -> None:
    (tmp_path / "types.comp").write_text(TYPES)
    compile_ok(Path("types.comp"), tmp_path)
    hal = """
loadrt types
loadrt threads name1=t period1=1000000
addf types.0.go t
addf types.0 t
show pin types
show param types
show funct types
simrun 2ms
show pin types
show param types
"""
    p = halrun(hal, tmp_path, hal_env([tmp_path]), "-S")
    assert p.returncode == 0, p.stderr
    before, after = p.stdout.split("Exported Functions:")
    v0, v1 = pins(before), pins(after)
    assert v0["types.0.b_in".replace("_", "-")] == ("bit", "IN", "TRUE")
    assert v0["types.0.f-in"] == ("float", "IN", "2.5")
    assert v0["types.0.s-in"] == ("s32", "IN", "-7")
    assert v0["types.0.u-in"] == ("u32", "IN", "0xFFFFFFFF")
    assert v0["types.0.ls-in"] == ("s64", "IN", "-9000000000")
    assert v0["types.0.lu-in"][:2] == ("u64", "IN")
    assert int(v0["types.0.lu-in"][2], 16) == 18000000000000000000
    assert v0["types.0.f-io"] == ("float", "I/O", "1.5")
    assert v0["types.0.pb"] == ("bit", "RW", "TRUE")
    assert v0["types.0.pf"] == ("float", "RO", "0.25")
    assert v0["types.0.ps"] == ("s32", "RW", "-3")
    assert v0["types.0.pu"] == ("u32", "RO", "0x00000003")
    assert v0["types.0.pls"] == ("s64", "RW", "-5000000000")
    assert v0["types.0.plu"][:2] == ("u64", "RW")
    assert int(v0["types.0.plu"][2], 16) == 5000000000
    assert [n for n in v0 if "idx" in n] == ["types.0.idx0", "types.0.idx1", "types.0.idx2"]
    assert all(v0[f"types.0.idx{i}"] == ("s32", "OUT", "4") for i in range(3))
    arr = sorted(n for n in v0 if ".arr-" in n)
    assert arr == [f"types.0.arr-{i:02d}" for i in range(12)]
    assert v0["types.0.gains.0"] == ("u32", "RW", "0x0000000A")
    assert v0["types.0.gains.1"] == ("u32", "RW", "0x0000000A")
    assert re.search(r"NO +1 +types\.0\.go$", p.stdout, re.M)
    assert re.search(r"YES +1 +types\.0$", p.stdout, re.M)
    # two periods of: go (integer), then _ (float)
    assert v1["types.0.b-out"][2] == "FALSE"
    assert v1["types.0.s-out"][2] == "-14"
    assert int(v1["types.0.u-out"][2], 16) == 4294967294
    assert v1["types.0.ls-out"][2] == "-18000000000"
    assert int(v1["types.0.lu-out"][2], 16) == 18000000000000000001
    assert [v1[f"types.0.idx{i}"][2] for i in range(3)] == [str(4 + 2 * (i + 2)) for i in range(3)]
    assert int(v1["types.0.gains.1"][2], 16) == 11
    assert v1["types.0.ps"][2] == "-5"
    assert v1["types.0.f-out"][2] == "5.25"
    assert v1["types.0.f-io"][2] == "3.5"
    assert [float(v1[f"types.0.arr-{i:02d}"][2]) for i in range(12)] == [i * 0.5 for i in range(12)]


OPTS = r"""
component opts "singleton, extra_setup/cleanup, data, modparam, include";
option singleton yes;
option extra_setup yes;
option extra_cleanup yes;
option data opts_data;
modparam int level = 3 "a level";
modparam string label = "hello" "a label";
include "opts_types.h";
pin out s32 lvl;
pin out u32 len;
variable hal_s32_t *extra;
variable opts_count_t seen;
function _ nofp;
license "GPL";
author "nobody";
;;
EXTRA_SETUP() {
    data.calls = 100;
    seen = 7;
    rtapi_print_msg(RTAPI_MSG_ERR, "opts: setup %s arg %ld\n", prefix, extra_arg);
    return hal_pin_s32_newf(HAL_OUT, &extra, comp_id, "%s.extra", prefix);
}

EXTRA_CLEANUP() {
    rtapi_print_msg(RTAPI_MSG_ERR, "opts: cleanup\n");
}

FUNCTION(_) {
    data.calls++;
    lvl = level + data.calls;
    len = strlen(label);
    *extra = seen;
}
"""


def test_options_singleton_setup_cleanup_data_modparam(tmp_path: Path) -> None:
    (tmp_path / "opts.comp").write_text(OPTS)
    (tmp_path / "opts_types.h").write_text(
        "typedef int opts_count_t;\ntypedef struct { int calls; } opts_data;\n"
    )
    compile_ok(Path("opts.comp"), tmp_path)  # opts_types.h found next to opts.comp
    hal = """
loadrt opts level=40 label=abcdef
loadrt threads name1=t period1=1000000
addf opts t
simrun 3ms
show pin opts
unloadrt opts
"""
    p = halrun(hal, tmp_path, hal_env([tmp_path]), "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert v["opts.lvl"] == ("s32", "OUT", str(40 + 103))
    assert v["opts.len"] == ("u32", "OUT", "0x00000006")
    assert v["opts.extra"] == ("s32", "OUT", "7")
    assert "opts: setup opts arg 0" in p.stderr
    assert p.stderr.index("opts: setup") < p.stderr.index("opts: cleanup")
    # no count=/names= on a singleton
    p = halrun("loadrt opts count=2\n", tmp_path, hal_env([tmp_path]))
    assert p.returncode != 0
    assert "count" in p.stderr


COUNTED = r"""
component counted "default_count";
option default_count 3;
option extra_setup;
pin out s32 id;
variable int n;
function _ nofp;
license "GPL";
;;
EXTRA_SETUP() { n = extra_arg; return 0; }
FUNCTION(_) { id = n * 10; }
"""

COUNTFN = r"""
component countfn "count_function";
option count_function;
pin out s32 x = 5;
function _ nofp;
license "GPL";
;;
int get_count(void) { return 2; }
FUNCTION(_) { x = 6; }
"""


def test_default_count_and_count_function(tmp_path: Path) -> None:
    (tmp_path / "counted.comp").write_text(COUNTED)
    (tmp_path / "countfn.comp").write_text(COUNTFN)
    compile_ok(Path("counted.comp"), tmp_path, "countfn.comp")
    env = hal_env([tmp_path])
    p = halrun("loadrt counted\nloadrt countfn\nshow pin\n", tmp_path, env)
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert sorted(n for n in v if n.endswith(".id")) == [f"counted.{i}.id" for i in range(3)]
    assert sorted(n for n in v if n.endswith(".x")) == ["countfn.0.x", "countfn.1.x"]
    assert v["countfn.1.x"] == ("s32", "OUT", "5")
    p = halrun(
        "loadrt counted names=a,b\nloadrt threads name1=t period1=1000000\naddf b t\n"
        "simrun 1ms\nshow pin\n",
        tmp_path,
        env,
        "-S",
    )
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert sorted(n for n in v if n.endswith(".id")) == ["a.id", "b.id"]
    assert v["b.id"][2] == "10"  # extra_arg is the instance number
    p = halrun("loadrt counted count=1\nshow pin\n", tmp_path, env)
    assert [n for n in pins(p.stdout) if n.endswith(".id")] == ["counted.0.id"]
    p = halrun("loadrt countfn count=1\n", tmp_path, env)
    assert p.returncode != 0 and "count" in p.stderr


PERS = r"""
component pers "personality: sizes, conditions, set in EXTRA_SETUP";
pin in float x-#[8 : personality];
param rw float k if personality > 2 = 0.5;
pin out float sum;
option extra_setup;
function _;
license "GPL";
;;
EXTRA_SETUP() {
    if (personality == 0)
        personality = 2;
    return 0;
}
FUNCTION(_) {
    int i;
    double s = 0;
    for (i = 0; i < personality; i++)
        s += x(i);
    sum = s * (personality > 2 ? k : 1.0);
}
"""


def test_personality(tmp_path: Path) -> None:
    (tmp_path / "pers.comp").write_text(PERS)
    compile_ok(Path("pers.comp"), tmp_path)
    env = hal_env([tmp_path])
    hal = """
loadrt pers count=3 personality=4,0
loadrt threads name1=t period1=1000000
addf pers.0 t
setp pers.0.x-0 1
setp pers.0.x-3 2
simrun 1ms
show pin pers
show param pers
"""
    p = halrun(hal, tmp_path, env, "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    xs = sorted(n for n in v if ".x-" in n)
    want = [f"pers.0.x-{i}" for i in range(4)] + [f"pers.{j}.x-{i}" for j in (1, 2) for i in (0, 1)]
    assert xs == sorted(want)
    assert "pers.0.k" in v and "pers.1.k" not in v and "pers.2.k" not in v
    assert v["pers.0.k"] == ("float", "RW", "0.5")
    assert v["pers.0.sum"][2] == "1.5"  # (1 + 2) * 0.5
    p = halrun("loadrt pers personality=9\nshow pin\n", tmp_path, env)
    assert p.returncode != 0
    assert "Pin x-#: Requested size 9 exceeds max size 8" in p.stderr
    assert "pers." not in p.stdout  # nothing left behind


OWN = r"""
component own "option rtapi_app no";
option rtapi_app no;
option extra_setup;
pin out s32 v;
variable int arg;
function _ nofp;
license "GPL";
;;
EXTRA_SETUP() { arg = extra_arg; return 0; }
FUNCTION(_) { v = arg; }

int rtapi_app_main(void) {
    int r;
    comp_id = hal_init("own");
    if (comp_id < 0)
        return comp_id;
    r = export("own.a", 5);
    if (r == 0)
        r = export("own.b", 6, 0);
    if (r != 0) {
        hal_exit(comp_id);
        return r;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
"""


def test_rtapi_app_no_and_export(tmp_path: Path) -> None:
    (tmp_path / "own.comp").write_text(OWN)
    compile_ok(Path("own.comp"), tmp_path)
    hal = """
loadrt own
loadrt threads name1=t period1=1000000
addf own.a t
addf own.b t
simrun 1ms
show pin own
"""
    p = halrun(hal, tmp_path, hal_env([tmp_path]), "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert v["own.a.v"][2] == "5" and v["own.b.v"][2] == "6"


USR = r"""
component usr "userspace with userinit";
option userspace yes;
option userinit yes;
pin out s32 argn;
pin in float in;
pin out float out;
license "GPL";
;;
#include <unistd.h>
static int nargs;
void userinit(int argc_, char **argv_) { (void)argv_; nargs = argc_; }
void user_mainloop(void) {
    for (;;) {
        FOR_ALL_INSTS() {
            argn = nargs;
            out = in * 2;
        }
        usleep(1000);
    }
}
"""


def test_userspace_userinit_and_args(tmp_path: Path) -> None:
    (tmp_path / "usr.comp").write_text(USR)
    compile_ok(Path("usr.comp"), tmp_path)
    assert (tmp_path / "usr").is_file() and not (tmp_path / "usr.so").exists()
    hal = f"""
loadusr -Wn usr {tmp_path / 'usr'} names=p,q
setp q.in 1.25
loadusr -w sleep 0.1
show pin
show comp usr
"""
    p = halrun(hal, tmp_path, hal_env())
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert v["p.argn"] == ("s32", "OUT", "2")  # userinit sees argv before names= is taken
    assert v["q.out"] == ("float", "OUT", "2.5")
    assert re.search(r"User +usr +PID ready|User +usr +\d+ ready", p.stdout)
    p = halrun(f"loadusr -Wn usr {tmp_path / 'usr'} count=2 names=a\n", tmp_path, hal_env())
    assert p.returncode != 0
    assert "count= and names= are mutually exclusive" in p.stderr


def test_user_install(tmp_path: Path) -> None:
    """--install --user puts the module into ~/.local/lib/hm2stack/rtlib and a
    userspace program into ~/.local/bin, no root needed."""
    home = tmp_path / "home"
    home.mkdir()
    (tmp_path / "counted.comp").write_text(COUNTED)
    (tmp_path / "usr.comp").write_text(USR)
    env = hal_env(home=home)
    p = halcompile("--install", "--user", "counted.comp", "usr.comp", cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr
    so = home / ".local" / "lib" / "hm2stack" / "rtlib" / "counted.so"
    prog = home / ".local" / "bin" / "usr"
    assert so.is_file() and prog.is_file()
    assert prog.stat().st_mode & 0o111
    assert f"installed {so}" in p.stdout
    p = halrun("loadrt counted count=1\nshow pin\n", tmp_path, hal_env([so.parent], home=home))
    assert p.returncode == 0, p.stderr
    assert "counted.0.id" in pins(p.stdout)


def test_plain_c_file_install(tmp_path: Path) -> None:
    rtlib = tmp_path / "rtlib"
    shutil.copy(COMPS / "rtexample2.c", tmp_path)
    env = hal_env()
    env["HALCOMPILE_RTLIB"] = str(rtlib)
    p = halcompile("--install", "rtexample2.c", cwd=tmp_path, env=env)
    assert p.returncode == 0, p.stderr
    assert (rtlib / "rtexample2.so").is_file()
    p = halrun("loadrt rtexample2 value=7\nshow pin\n", tmp_path, hal_env([rtlib]))
    assert p.returncode == 0, p.stderr
    assert pins(p.stdout)["rtexample2.out"] == ("s32", "OUT", "7")
    p = halcompile("rtexample2.c", cwd=tmp_path)
    assert p.returncode == 1 and "can only be compiled or installed" in p.stderr


@pytest.mark.parametrize("comp", ["types", "counted", "pers"])
def test_preprocess_is_deterministic(tmp_path: Path, comp: str) -> None:
    (tmp_path / f"{comp}.comp").write_text({"types": TYPES, "counted": COUNTED, "pers": PERS}[comp])
    assert halcompile(f"{comp}.comp", cwd=tmp_path).returncode == 0
    first = (tmp_path / f"{comp}.c").read_text()
    assert halcompile("--preprocess", "-o", "again.c", f"{comp}.comp", cwd=tmp_path).returncode == 0
    again = (tmp_path / "again.c").read_text()
    assert first.replace(f'"{comp}.c"', "X") == again.replace('"again.c"', "X")
    assert f'#line 2 "{comp}.comp"' not in first  # the C part starts after ";;"


API = r"""
component api "the LinuxCNC component API .comp authors include";
pin out float pi;
pin out u32 q;
pin out u32 rem;
pin out s32 len;
pin out bit digit;
pin out s64 now;
pin out s32 trunc_err;
variable char *buf;
option extra_setup;
option extra_cleanup;
function _;
license "GPL";
;;
#include <rtapi_math.h>
#include <rtapi_math64.h>
#include <rtapi_string.h>
#include <rtapi_errno.h>
#include <rtapi_ctype.h>
#include <rtapi_stdint.h>
#include <rtapi_bool.h>
#include <rtapi_slab.h>
#include <rtapi_app.h>

static char *bufs[8];

EXTRA_SETUP() {
    buf = rtapi_kzalloc(16, RTAPI_GFP_KERNEL);
    if (buf == NULL)
        return -ENOMEM;
    bufs[extra_arg % 8] = buf;
    rtapi_snprintf(buf, 16, "%s!", prefix);
    return 0;
}

EXTRA_CLEANUP() {
    for (int i = 0; i < 8; i++)
        rtapi_kfree(bufs[i]);
}

FUNCTION(_) {
    char small[4];
    rtapi_u32 r;
    pi = M_PI;
    q = (rtapi_u32)rtapi_div_u64_rem(10000000007ULL, 10u, &r);
    rem = r;
    len = (rtapi_s32)strlen(buf);
    digit = isdigit((unsigned char)buf[4]) != 0;
    now = rtapi_get_time();
    trunc_err = rtapi_strxcpy(small, "toolong");
    if (trunc_err != -E2BIG)
        rtapi_print_msg(RTAPI_MSG_ERR, "api: strxcpy did not report truncation\n");
}
"""


def test_linuxcnc_api_headers(tmp_path: Path) -> None:
    (tmp_path / "api.comp").write_text(API)
    compile_ok(Path("api.comp"), tmp_path)
    hal = """
loadrt api
loadrt threads name1=t period1=1000000
addf api.0 t
simrun 3ms
show pin api
"""
    p = halrun(hal, tmp_path, hal_env([tmp_path]), "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert float(v["api.0.pi"][2]) == pytest.approx(3.1415927)
    assert int(v["api.0.q"][2], 16) == 1000000000 % 2**32  # 10000000007 // 10, as u32
    assert int(v["api.0.rem"][2], 16) == 7
    assert v["api.0.len"][2] == "6"  # "api.0!"
    assert v["api.0.digit"][2] == "TRUE"  # buf[4] is '0'
    assert int(v["api.0.now"][2]) >= 3_000_000  # virtual time after 3 ms
    assert v["api.0.trunc-err"][2] == "-7"  # -E2BIG
    assert "did not report" not in p.stderr
