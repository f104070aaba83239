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
