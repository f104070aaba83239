# SPDX-License-Identifier: GPL-2.0-or-later
"""halmeter --text and halshow --text/--set/--watch against halcmd itself:
the values halcmd getp/gets prints, the errors its setp/sets prints."""

from __future__ import annotations

import os
import pty
import re
import select
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


def test_halmeter_reports_an_unloaded_component(live: LiveHal) -> None:
    """A pin whose component is unloaded is reported, not crashed on, and
    watched again once the component is back (with its new value)."""
    p = live.start(BIN / "halmeter", "--text", "--interval", "0.02", "siggen.0.amplitude")
    assert p.stdout is not None
    assert p.stdout.readline().split()[1:] == ["siggen.0.amplitude", "2.5"]
    assert live.halcmd("unloadrt", "siggen").returncode == 0
    assert p.stdout.readline().split()[1:] == ["siggen.0.amplitude", "removed"]
    assert live.halcmd("loadrt", "siggen").returncode == 0
    assert p.stdout.readline().split()[1:] == [
        "siggen.0.amplitude",
        live.getp("siggen.0.amplitude"),
    ]
    assert p.poll() is None
    p.terminate()
    assert p.wait(timeout=10) == 0


def test_viewers_are_components_that_end_with_the_session(live: LiveHal) -> None:
    """halmeter and the web server are HAL user components named
    PROGRAM-PID (LinuxCNC's halmeter is halmeter-PID): `unload all` at the
    end of a session ends them (exit status 0) instead of leaving them
    watching a session that is gone."""
    meter = live.start(BIN / "halmeter", "--text", "siggen.0.amplitude")
    web, _ = live.start_web(BIN / "halweb")
    names = {f"halmeter-{meter.pid}", f"halweb-{web.pid}"}
    deadline = time.monotonic() + 60
    while True:
        comps = live.halcmd("show", "comp").stdout
        ready = {n for n in names if re.search(rf"\sUser\s+{n}\s+\d+\s+ready$", comps, re.M)}
        if ready == names:
            break
        assert time.monotonic() < deadline, comps
        time.sleep(0.1)
    r = live.halcmd("unload", "all")
    assert r.returncode == 0, r.stderr
    assert meter.wait(timeout=20) == 0 and web.wait(timeout=20) == 0
    assert "siggen" not in live.halcmd("show", "comp").stdout


class Terminal:
    """halmeter on a terminal (a pty)."""

    def __init__(self, live: LiveHal, args: list[str]) -> None:
        self.master, slave = pty.openpty()
        self.p = subprocess.Popen(
            [str(BIN / "halmeter"), "--interval", "0.02", *args],
            env=live.env,
            stdin=slave,
            stdout=slave,
            stderr=subprocess.PIPE,
        )
        os.close(slave)
        self.raw = b""

    def frame(self, until: str, timeout: float = 20) -> str:
        """The last complete frame drawn (escape sequences removed) once it
        shows `until`."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if select.select([self.master], [], [], 0.1)[0]:
                self.raw += os.read(self.master, 65536)
            frames = re.split(rb"\x1b\[\d+F", self.raw)
            for frame in reversed(frames[:-1] if len(frames) > 1 else frames):
                text = re.sub(rb"\x1b\[[0-9;]*[A-Za-z]", b"", frame).decode()
                text = text.replace("\r", "")
                if until in text:
                    return text
        raise AssertionError(f"{until!r} never shown: {self.raw[-500:]!r}")

    def close(self) -> int:
        self.p.terminate()
        rc = self.p.wait(timeout=10)
        os.close(self.master)
        return rc


def test_halmeter_terminal_redraws(live: LiveHal) -> None:
    """On a terminal: one line per item (kind, name, value), redrawn in
    place (cursor back up over the items); -s shows the values only;
    LinuxCNC's -g X Y WIDTH is taken and ignored."""
    t = Terminal(live, ["pin", "siggen.0.amplitude", "sig", "free"])
    try:
        text = t.frame("-7")
        assert [line.split() for line in text.splitlines()] == [
            ["pin", "siggen.0.amplitude", "2.5"],
            ["sig", "free", "-7"],
        ]
        live.halcmd("sets", "free", "1234")
        assert t.frame("1234").splitlines()[1].split() == ["sig", "free", "1234"]
        assert b"\x1b[2F" in t.raw, "redrawn in place: two lines up"
    finally:
        assert t.close() == 0
    t = Terminal(live, ["-s", "-g", "10", "20", "300", "sig", "free"])
    try:
        assert t.frame("1234").splitlines() == ["1234"]
    finally:
        assert t.close() == 0


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


SECTIONS_HAL = """\
loadrt threads name1=fast period1=100000 name2=slow period2=1000000 fp2=0
loadrt siggen num_chan=2
loadrt and2 count=1
addf siggen.0.update fast
addf and2.0 slow
addf siggen.1.update fast 1
net sq siggen.0.clock and2.0.in0
net out and2.0.out
newsig lone s32
sets lone -3
simrun 1ms
loadusr -w halshow --text
show funct
show thread
show sig
"""


def section(lines: list[str], title: str) -> list[str]:
    start = next(i for i, line in enumerate(lines) if line.startswith(title + " ("))
    end = next(
        (i for i in range(start + 1, len(lines)) if not lines[i].startswith(" ")), len(lines)
    )
    return lines[start + 1 : end]


def test_halshow_text_signals_functions_threads(tmp_path: Path) -> None:
    """The tree's signals, functions and threads say what halcmd's show
    says: type, value and pins of each signal; each function's owner, fp
    flag and users; each thread's period, fp flag and functions in order."""
    r = halrun(tmp_path, SECTIONS_HAL)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    ours = {}
    for line in section(lines, "Signals"):
        m = re.fullmatch(r"  (\S+) = (\w+) (\S+)(?:  \[(.*)\])?", line)
        assert m, line
        ours[m.group(1)] = (m.group(2), m.group(3), sorted((m.group(4) or "").split()))
    theirs = {}
    at = lines.index("Signals:") + 2
    while at < len(lines) and lines[at].strip():
        typ, val, name = lines[at].split()
        at += 1
        pins = []
        while at < len(lines) and lines[at].split()[:1] in (["<=="], ["==>"], ["<=>"]):
            pins.append(lines[at].split()[1])
            at += 1
        theirs[name] = (typ, val, sorted(pins))
    assert ours == theirs and set(ours) == {"out", "sq", "lone"}

    functs = {}
    for line in section(lines, "Functions"):
        m = re.fullmatch(r"  (\S+) = owner (\d+), (fp|no fp), in (\d+) thread\(s\)", line)
        assert m, line
        functs[m.group(1)] = (int(m.group(2)), "NO" if m.group(3) == "no fp" else "YES", m.group(4))
    at = lines.index("Exported Functions:") + 2
    table = {}
    while lines[at].strip():
        owner, _, _, fp, users, name = lines[at].split()
        table[name] = (int(owner), fp, users)
        at += 1
    assert functs == table and len(table) == 3

    def threads(rows: list[str], head: str) -> list[tuple[str, ...]]:
        """(name, period, fp) per thread, each followed by (function,) in order."""
        out: list[tuple[str, ...]] = []
        for row in rows:
            m, w = re.fullmatch(head, row), row.split()
            if m:
                out.append(m.groups())
            elif len(w) == 2 and w[0].isdigit():
                out.append((w[1],))
        return out

    ours_t = threads(section(lines, "Threads"), r"  (\S+) = period (\d+) ns, (fp|no fp)")
    ours_t = [
        (t[0], t[1], "NO" if t[2] == "no fp" else "YES") if len(t) == 3 else t for t in ours_t
    ]
    start = lines.index("Realtime Threads:") + 2
    end = lines.index("Signals:")
    theirs_t = threads(lines[start:end], r"\s+(\d+)\s+(YES|NO)\s+(\S+) \(.*\)")
    theirs_t = [(t[2], t[0], t[1]) if len(t) == 3 else t for t in theirs_t]
    assert ours_t == theirs_t
    assert ours_t == [
        ("slow", "1000000", "NO"),
        ("and2.0",),
        ("fast", "100000", "YES"),
        ("siggen.1.update",),
        ("siggen.0.update",),
    ]


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
