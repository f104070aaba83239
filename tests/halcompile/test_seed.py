# SPDX-License-Identifier: GPL-2.0-or-later
"""The seed chapter's example components, compiled by our halcompile and run
in a real halrun session: pin/param/function listings against LinuxCNC 2.9
(data/*.expected, recorded with lcnc-halrun, see data/README) and each
example's documented behaviour."""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from hcomp_util import (
    BUILD,
    COMPS,
    DATA,
    HALRUN,
    ROOT,
    compile_ok,
    hal_env,
    halrun,
    normalize,
    pins,
)


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("seed")
    for src in COMPS.glob("*.comp"):
        shutil.copy(src, out)
    names = sorted(p.name for p in out.glob("*.comp"))
    compile_ok(Path(names[0]), out, *names[1:])
    return out


def _run_recorded(name: str, built: Path, tmp_path: Path) -> tuple[str, int]:
    """Run data/NAME.hal from a copy in tmp_path (relative file name, as
    recorded), our logic.so first on the module path."""
    shutil.copy(DATA / f"{name}.hal", tmp_path)
    env = hal_env([built])
    try:
        p = subprocess.run(
            [str(HALRUN), "-f", f"{name}.hal"],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=60,
        )
    finally:
        subprocess.run([str(HALRUN), "-U"], env=env, capture_output=True, timeout=30)
    return normalize(p.stdout + p.stderr), p.returncode


@pytest.mark.parametrize("name,rc", [("logic", 0), ("arrays", 0), ("sizeerr", 1)])
def test_logic_like_linuxcnc(built: Path, tmp_path: Path, name: str, rc: int) -> None:
    """The seed's logic.comp gives LinuxCNC 2.9's logic interface: the seed's
    load line, names= with personality, and a size beyond the maximum."""
    got, code = _run_recorded(name, built, tmp_path)
    want = normalize((DATA / f"{name}.expected").read_text())
    assert got == want
    assert code == rc


def test_seed_examples_behave(built: Path, tmp_path: Path) -> None:
    hal = """
loadrt constant
loadrt sincos
loadrt hal_loop
loadrt arraydemo
loadrt logic personality=0x305
loadrt threads name1=t period1=1000000
addf constant.0 t
addf sincos.0 t
addf loop.0 t
addf arraydemo.0 t
addf logic.0 t
setp sincos.0.theta 0.5
setp arraydemo.0.in 1
setp logic.0.in-00 1
setp logic.0.in-01 1
setp logic.0.in-02 1
setp logic.0.in-03 1
setp logic.0.in-04 1
simrun 1ms
setp arraydemo.0.in 0
setp logic.0.in-02 0
simrun 2ms
show comp hal_loop
show pin
"""
    env = hal_env([built])
    p = halrun(hal, tmp_path, env, "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert v["constant.0.out"] == ("float", "OUT", "1")  # param value = 1.0 default
    assert math.isclose(float(v["sincos.0.sin"][2]), math.sin(0.5), rel_tol=1e-6)
    assert math.isclose(float(v["sincos.0.cos"][2]), math.cos(0.5), rel_tol=1e-6)
    assert v["sincos.0.theta"][:2] == ("float", "IN")
    assert v["loop.0.example"] == ("float", "OUT", "1")
    assert re.search(r"RT +hal_loop +ready", p.stdout)
    # shift register after in=1 for 1 period, then in=0 for 2 periods
    got = [v[f"arraydemo.0.out-{i}"][2] for i in range(4)]
    assert got == ["FALSE", "FALSE", "TRUE", "FALSE"]
    # personality 0x305: 5 inputs, and + or; in-02 low -> and FALSE, or TRUE
    assert v["logic.0.and"][2] == "FALSE" and v["logic.0.or"][2] == "TRUE"
    assert "logic.0.xor" not in v and "logic.0.in-05" not in v


def test_rand_userspace(built: Path, tmp_path: Path) -> None:
    """The seed's userspace rand: a loadusr program whose pin moves in (0,1)."""
    hal = f"""
loadusr -Wn rand {built / 'rand'}
loadusr -w sleep 0.05
show pin rand
loadusr -w sleep 0.05
show pin rand
"""
    p = halrun(hal, tmp_path, hal_env([built]))
    assert p.returncode == 0, p.stderr
    vals = re.findall(r"float OUT +(\S+)  rand\.0\.out", p.stdout)
    assert len(vals) == 2, p.stdout
    assert all(0 < float(x) < 1 for x in vals) and vals[0] != vals[1]


def test_docs_example_ddt(tmp_path: Path) -> None:
    """The ddt example of docs/halcompile.md: out = (in - previous in) / fperiod."""
    doc = (ROOT / "docs" / "halcompile.md").read_text()
    block = re.search(r"The seed's example, a derivative[^\n]*:\n\n((?:    .*\n|\n)+)", doc)
    assert block
    text = "\n".join(line[4:] for line in block.group(1).splitlines())
    (tmp_path / "ddt.comp").write_text(text)
    mod = tmp_path / "mod"
    mod.mkdir()
    compile_ok(Path("../ddt.comp"), mod)
    hal = """
loadrt ddt
loadrt threads name1=t period1=1000000
addf ddt.0 t
setp ddt.0.in 0.5
simrun 1ms
show pin ddt.0.out
setp ddt.0.in 0.25
simrun 1ms
show pin ddt.0.out
"""
    p = halrun(hal, tmp_path, hal_env([mod]), "-S")
    assert p.returncode == 0, p.stderr
    vals = [float(x) for x in re.findall(r"float OUT +(\S+)  ddt\.0\.out", p.stdout)]
    assert vals == pytest.approx([0.5 / 1e-3, -0.25 / 1e-3])


def test_seed_command_lines(tmp_path: Path) -> None:
    """The seed's command lines, with its program name `comp`: process,
    compile, install and document rtexample.comp (component "example"),
    install rtexample2.c, and the same for usrexample.comp; then the
    installed components load and run."""
    for f in ("rtexample.comp", "rtexample2.c", "usrexample.comp"):
        shutil.copy(COMPS / f, tmp_path)
    env = hal_env()
    env["HALCOMPILE_RTLIB"] = str(tmp_path / "rtlib")
    env["HALCOMPILE_BINDIR"] = str(tmp_path / "bin")
    comp = str(BUILD / "bin" / "comp")
    for args, made in [
        (["rtexample.comp"], "example.c"),
        (["--compile", "rtexample.comp"], "example.so"),
        (["--install", "rtexample.comp"], "rtlib/example.so"),
        (["--install", "rtexample2.c"], "rtlib/rtexample2.so"),
        (["--document", "rtexample.comp"], "example.md"),
        (["usrexample.comp"], "usrexample.c"),
        (["--compile", "usrexample.comp"], "usrexample"),
        (["--install", "usrexample.comp"], "bin/usrexample"),
        (["--document", "usrexample.comp"], "usrexample.md"),
    ]:
        p = subprocess.run([comp, *args], cwd=tmp_path, env=env, capture_output=True, text=True)
        assert p.returncode == 0, f"comp {' '.join(args)}: {p.stderr}"
        assert (tmp_path / made).is_file(), f"comp {' '.join(args)} made no {made}"
    assert "# example(9)" in (tmp_path / "example.md").read_text()
    hal = f"""
loadrt example
loadrt rtexample2
loadusr -Wn usrexample {tmp_path / 'bin' / 'usrexample'}
loadrt threads name1=t period1=1000000
addf example.0 t
setp example.0.in 1.5
simrun 1ms
loadusr -w sleep 0.05
show pin
"""
    p = halrun(hal, tmp_path, hal_env([tmp_path / "rtlib"]), "-S")
    assert p.returncode == 0, p.stderr
    v = pins(p.stdout)
    assert v["example.0.out"] == ("float", "OUT", "3")
    assert v["rtexample2.out"] == ("s32", "OUT", "42")
    assert v["usrexample.0.enable"] == ("bit", "IN", "TRUE")
    assert int(v["usrexample.0.out"][2]) > 0


def test_out8_count_function_and_io(built: Path, tmp_path: Path) -> None:
    """The seed's out8 compiles unchanged (<asm/io.h>, rtapi_request_region,
    option constructable); with no io= it loads with no instances; with an
    address it either gets the port (root/CAP_SYS_RAWIO) and makes one
    instance, or EXTRA_SETUP fails the load with -EBUSY leaving nothing."""
    p = halrun("loadrt out8\nshow comp out8\nshow pin\n", tmp_path, hal_env([built]))
    assert p.returncode == 0, p.stderr
    assert re.search(r"RT +out8 +ready", p.stdout)
    assert "out8." not in p.stdout.split("Component Pins:")[1]
    p = halrun("loadrt out8 io=0x378\nshow param out8\n", tmp_path, hal_env([built]))
    if p.returncode == 0:
        v = pins(p.stdout)
        assert int(v["out8.0.ioaddr"][2], 16) == 0x378
    else:
        assert "out8: rtapi_app_main: Device or resource busy (-16)" in p.stderr
