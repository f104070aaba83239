# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope's bad input: a clear message, exit status 1, HAL unchanged
(scope_rt not loaded, no function added, the signals' values intact)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from hvutil import BIN, BUILT, env, halrun

pytestmark = pytest.mark.requires_build(*BUILT)

SETUP = """\
loadrt threads name1=fast period1=100000
loadrt siggen
addf siggen.0.update fast
loadusr -w halscope {args}
show comp
show thread
"""


@pytest.mark.parametrize(
    "args,message",
    [
        ("-c nope --thread fast --out x.csv", "halscope: no pin, signal or parameter named 'nope'"),
        ("-c pin:siggen.0.nope --thread fast --out x.csv", "pin 'siggen.0.nope' does not exist"),
        (
            "-c siggen.0.sine --thread nothread --out x.csv",
            "halscope: thread 'nothread' does not exist (threads: fast)",
        ),
        (
            "-c siggen.0.sine --thread fast --out /nonexistent/dir/x.csv",
            "halscope: cannot write the capture to /nonexistent/dir/x.csv: No such file or "
            "directory",
        ),
        ("-c siggen.0.sine --thread fast --out x.txt", "unknown capture format '.txt'"),
        (
            "-c siggen.0.sine --thread fast --samples 20000 --out x.csv",
            "record length 20000 with 1 channels: scope_rt holds 16000 (num_samples=16000)",
        ),
        (
            "-c siggen.0.sine --thread fast --trigger siggen.0.sine --position 150 --out x.csv",
            "trigger position 150.0%: must be 0 to 100",
        ),
        ("-c siggen.0.sine --thread fast --out x.csv num_samples=x", "num_samples=N"),
        ("-c siggen.0.sine --out x.csv", "scope_rt is not loaded: name the thread"),
    ],
)
def test_bad_input_changes_nothing(tmp_path: Path, args: str, message: str) -> None:
    r = halrun(tmp_path, SETUP.format(args=args))
    assert message in r.stderr
    assert "scope_rt" not in r.stdout and "scope.sample" not in r.stdout
    assert not (tmp_path / "x.csv").exists()


def test_no_session() -> None:
    r = subprocess.run(
        [str(BIN / "halscope"), "-c", "x", "--out", "/tmp/x.csv"],
        env=env(),
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert r.returncode == 1
    assert "halscope: no HAL session is running (HAL_INSTANCE=hv-" in r.stderr


def test_no_trigger_times_out(tmp_path: Path) -> None:
    """A level never crossed: normal mode gives up after --timeout; the
    threads were running, so the message does not blame scope.sample."""
    r = halrun(
        tmp_path,
        """\
        loadrt threads name1=fast period1=100000
        loadrt siggen
        addf siggen.0.update fast
        loadrt scope_rt
        addf scope.sample fast
        start
        loadusr -w halscope -c siggen.0.sine --trigger siggen.0.sine --level 5 --timeout 1 --out x.csv
        stop
        """,
    )
    assert "halscope: no trigger within 1 s\n" in r.stderr
    assert not (tmp_path / "x.csv").exists()


def test_sample_not_called(tmp_path: Path) -> None:
    r = halrun(
        tmp_path,
        """\
        loadrt threads name1=fast period1=100000
        loadrt siggen
        addf siggen.0.update fast
        loadrt scope_rt
        addf scope.sample fast
        loadusr -w halscope -c siggen.0.sine --timeout 0.5 --out x.csv
        """,
    )
    assert "scope.sample was not called (is it in a thread, and are the threads started?)" in (
        r.stderr
    )


def test_scope_rt_bad_num_samples(tmp_path: Path) -> None:
    r = halrun(tmp_path, "loadrt scope_rt num_samples=3\nshow comp\n")
    assert "SCOPE_RT: ERROR: num_samples=3 is out of range (16 to 134217728)" in r.stderr
    assert "scope_rt" not in r.stdout


@pytest.mark.parametrize(
    "text,message",
    [
        ("samples x\n", "s.halscope:1: 'x' is not a number"),
        ("thread fast\nbogus 1\n", "s.halscope:2: cannot understand 'bogus 1'"),
        ("mode sometimes\n", "s.halscope:1: mode 'sometimes': one of normal, auto, single, roll"),
        ("trigger a upward 1\n", "s.halscope:1: edge 'upward': rising or falling"),
        ("chan wire x\n", "s.halscope:1: 'wire': pin, sig, param or auto"),
        ("chan pin x scale\n", "s.halscope:1: options go in pairs (NAME VALUE)"),
        ("chan pin x gain 2\n", "s.halscope:1: unknown option 'gain' (expected scale, offset)"),
        ("chan pin x\n" * 17, "s.halscope: 17 channels, the scope has 16"),
    ],
)
def test_bad_setup_file(tmp_path: Path, text: str, message: str) -> None:
    (tmp_path / "s.halscope").write_text(text)
    r = halrun(tmp_path, SETUP.format(args="-i s.halscope --thread fast --out x.csv"))
    assert f"halscope: {message}" in r.stderr
    assert "scope_rt" not in r.stdout


def test_setup_round_trip(tmp_path: Path) -> None:
    """--save-setup writes what -i reads back: the same file again."""
    r = halrun(
        tmp_path,
        SETUP.format(
            args="-c pin:siggen.0.sine,sig:x --trigger siggen.0.sine --edge falling --level 0.25 "
            "--position 10 --samples 123 --mult 3 --mode auto --thread fast --save-setup a.txt"
        ),
    )
    assert r.returncode == 0, r.stderr
    r = halrun(tmp_path, SETUP.format(args="-i a.txt --save-setup b.txt"))
    a, b = (tmp_path / "a.txt").read_text(), (tmp_path / "b.txt").read_text()
    assert a == b
    assert "chan pin siggen.0.sine scale 1.0 offset 0.0\nchan sig x scale 1.0 offset 0.0\n" in a
    assert "trigger siggen.0.sine falling 0.25 position 10.0\n" in a
    assert "mult 3\nsamples 123\nmode auto\n" in a
