# SPDX-License-Identifier: GPL-2.0-or-later
"""halmeter --text and halshow --text/--set/--watch against halcmd itself:
the values halcmd getp/gets prints, the errors its setp/sets prints."""

from __future__ import annotations

import re
import subprocess
import time
from pathlib import Path

import pytest

from hvutil import BIN, BUILT, LiveHal, env, halrun

pytestmark = pytest.mark.requires_build(*BUILT)

LIVE = """\
loadrt threads name1=fast period1=1000000
loadrt siggen
addf siggen.0.update fast
net sq siggen.0.square
newsig free s32
sets free -7
setp siggen.0.amplitude 2.5
"""


@pytest.fixture
def live(tmp_path: Path) -> LiveHal:
    hal = LiveHal(tmp_path, LIVE)
    yield hal
    hal.stop()


def test_halmeter_text_prints_changes(live: LiveHal) -> None:
    p = live.start(
        BIN / "halmeter",
        "--text",
        "--interval",
        "0.02",
        "pin",
        "siggen.0.amplitude",
        "sig",
        "free",
        "param",
        "fast.tmax",
    )
    assert p.stdout is not None
    first = [p.stdout.readline().split() for _ in range(3)]
    assert [f[1:] for f in first] == [
        ["siggen.0.amplitude", live.getp("siggen.0.amplitude")],
        ["free", "-7"],
        ["fast.tmax", live.getp("fast.tmax")],
    ]
    assert re.fullmatch(r"\d+\.\d{9}", first[0][0])
    live.halcmd("setp", "siggen.0.amplitude", "0.125")
    assert p.stdout.readline().split()[1:] == ["siggen.0.amplitude", "0.125"]
    live.halcmd("sets", "free", "42")
    assert p.stdout.readline().split()[1:] == ["free", "42"]
    live.halcmd("delsig", "free")
    assert p.stdout.readline().split()[1:] == ["free", "removed"]
    live.halcmd("newsig", "free", "s32")
    assert p.stdout.readline().split()[1:] == ["free", "0"]
    p.terminate()
    assert p.wait(timeout=10) == 0


def test_halmeter_small_and_count(live: LiveHal) -> None:
    r = live.run(
        BIN / "halmeter",
        "-s",
        "--text",
        "--count",
        "1",
        "pin",
        "siggen.0.amplitude",
        "-g",
        "100",
        "500",
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.split()[1:] == ["siggen.0.amplitude", "2.5"]


@pytest.mark.parametrize(
    "args,message",
    [
        (["pin", "nope"], "halmeter: pin 'nope' does not exist"),
        (["nope"], "halmeter: no pin, signal or parameter named 'nope'"),
        (["pin"], "halmeter: 'pin' needs a name"),
        ([], "halmeter: nothing to watch"),
    ],
)
def test_halmeter_bad_input(live: LiveHal, args: list[str], message: str) -> None:
    r = live.run(BIN / "halmeter", "--text", *args)
    assert r.returncode == 1 and message in r.stderr


def test_halshow_text_tree(tmp_path: Path) -> None:
    r = halrun(
        tmp_path,
        """\
        loadrt threads name1=fast period1=100000
        loadrt siggen
        addf siggen.0.update fast
        net sq siggen.0.square
        simrun 1ms
        loadusr -w halshow --text siggen
        show pin siggen
        """,
    )
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == "Components (1)" and lines[1].startswith("  siggen = RT id ")
    assert "Pins (11)" in lines and "Parameters (2)" in lines and "Signals (0)" in lines
    # every pin of halcmd's show, with its value, type, direction and link
    shown = {}
    for line in lines:
        m = re.match(r"\s+(\w+) = (\w+) (IN|OUT|I/O) (\S+)(?:  ==> (\S+))?$", line)
        if m:
            shown[m.group(1)] = m.groups()[1:]
    table = [l.split() for l in lines if re.match(r"\s+\d+\s+(float|bit|s32)\s", l)]
    assert table, r.stdout
    for row in table:
        name = row[-1] if not row[-2] in ("==>", "<==") else row[-3]
        short = name.split(".")[-1]
        if name.startswith("siggen.0.update"):
            continue
        typ, d, val, link = shown[short]
        assert (typ, d) == (row[1], row[2])
        assert float(val) == float(row[3]) if typ == "float" else val == row[3]
        if row[-2] == "==>":
            assert link == row[-1]


def test_halshow_set_and_watch_like_halcmd(live: LiveHal, tmp_path: Path) -> None:
    watch = tmp_path / "watch.txt"
    watch.write_text("pin+siggen.0.amplitude sig+free\nparam+fast.tmax\n")
    r = live.run(
        BIN / "halshow", str(watch), "--set", "siggen.0.amplitude", "0.75", "--fformat", "%.3f"
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[:2] == ["pin+siggen.0.amplitude = 0.750", "sig+free = -7"]
    assert live.getp("siggen.0.amplitude") == "0.75"
    for name, value, halcmd_args in [
        ("siggen.0.square", "1", ["setp", "siggen.0.square", "1"]),
        ("siggen.0.amplitude", "abc", ["setp", "siggen.0.amplitude", "abc"]),
        ("sig+sq", "1", ["sets", "sq", "1"]),
        ("param+nope", "1", ["setp", "nope", "1"]),
    ]:
        ours = live.run(BIN / "halshow", "--set", name, value)
        theirs = live.halcmd(*halcmd_args)
        assert ours.returncode == 1 and theirs.returncode != 0
        reason = theirs.stderr.strip().splitlines()[0].split(": ", 1)[-1]
        assert reason in ours.stderr, (ours.stderr, theirs.stderr)
    assert live.getp("siggen.0.amplitude") == "0.75", "failed sets changed nothing"


def test_halshow_no_session() -> None:
    r = subprocess.run(
        [str(BIN / "halshow"), "--text"], env=env(), capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 1 and "halshow: no HAL session is running" in r.stderr


def test_halshow_bad_format(live: LiveHal) -> None:
    r = live.run(BIN / "halshow", "--text", "--fformat", "%s%s")
    assert r.returncode == 1 and "does not format a number" in r.stderr
