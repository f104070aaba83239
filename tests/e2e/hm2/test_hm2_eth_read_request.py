# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_<board>.<n>.read-request (hostmot2(9) FUNCTIONS): on two virtual
7i96S boards the thread runs both boards' read-requests, then both reads,
as the man page orders them.  The pins are the same as with the plain read
path (same board inputs, same lockstep board time); a lost reply to a
requested read is a packet error counted as hm2_eth(9) documents
(packet-read-timeout, packet-error-level arithmetic, the limit sets
io_error and the driver stops sending, clearing io_error resumes)."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from hm2e2e import BUILD, PROBE, halrun, num, tag, values, vboard
from test_hm2_eth_loss import ERR, PFX, TIMEOUT_NS, level_model, rig  # noqa: F401

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
import lbp16  # noqa: E402

pytestmark = pytest.mark.requires_build(BUILD / "lib" / "rtlib" / "hm2_eth.so")
ENC0_A, ENC0_B = 27, 28  # 7i96s_d: Encoder #0 A/B on TB2
CONFIG = "num_encoders=1 num_pwmgens=0 num_stepgens=2"
BOARDS = ("hm2_7i96s.0", "hm2_7i96s.1")


@contextmanager
def two_boards(tmp_path: Path, run: str) -> Iterator[list[tuple[Path, str]]]:
    """Two fresh virtual 7i96S boards in lockstep (--udp-tick: each servo
    read runs the board one period)."""
    started: list[vboard.VBoardProcess] = []
    boards: list[tuple[Path, str]] = []
    try:
        for i in range(2):
            sock, ip = tmp_path / f"{run}{i}.sock", lbp16.unique_loopback()
            started.append(
                vboard.VBoardProcess(
                    sock, "7i96s", "7i96s_d", args=["--udp", ip, "--udp-tick", "1000"]
                )
            )
            boards.append((sock, ip))
        yield boards
    finally:
        for p in started:
            p.stop()
            assert "Sanitizer" not in p.stderr_text, p.stderr_text


def observed(pfx: str) -> list[str]:
    return [
        f"{pfx}.stepgen.00.counts",
        f"{pfx}.stepgen.00.position-fb",
        f"{pfx}.stepgen.00.velocity-fb",
        f"{pfx}.stepgen.01.counts",
        f"{pfx}.encoder.00.count",
        f"{pfx}.encoder.00.position",
        f"{pfx}.gpio.000.in",
        f"{pfx}.packet-error-total",
        f"{pfx}.io_error",
    ]


def session(boards: list[tuple[Path, str]], split: bool, rates: tuple[int, int]) -> str:
    ips = ",".join(ip for _, ip in boards)
    s = "loadrt hostmot2\n" f'loadrt hm2_eth board_ip={ips} config="{CONFIG},{CONFIG}"\n'
    s += "loadrt threads name1=servo period1=1000000\n"
    if split:
        s += "".join(f"addf {b}.read-request servo\n" for b in BOARDS)
    s += "".join(f"addf {b}.read servo\n" for b in BOARDS)
    s += "".join(f"addf {b}.write servo\n" for b in BOARDS)
    for b, rate in zip(BOARDS, rates):
        s += f"setp {b}.packet-read-timeout 2000000000\n"
        for sg, vel in (("00", rate / 100), ("01", -rate / 200)):
            s += (
                f"setp {b}.stepgen.{sg}.control-type 1\n"
                f"setp {b}.stepgen.{sg}.position-scale 100\n"
                f"setp {b}.stepgen.{sg}.maxaccel 0\n"
                f"setp {b}.stepgen.{sg}.velocity-cmd {vel}\n"
                f"setp {b}.stepgen.{sg}.enable 1\n"
            )
    for (sock, _), rate in zip(boards, rates):
        s += f"loadusr -w {sys.executable} {PROBE} {sock} quad {ENC0_A} {ENC0_B} {rate * 3}\n"
    s += "simrun 25ms\nshow funct\nloadusr -w echo @@thread\nshow thread servo\n"
    for b in BOARDS:
        s += tag(b, *observed(b))
    return s


def test_read_request_pins_match_the_plain_read(tmp_path: Path) -> None:
    rates = (1000, 2000)
    got = {}
    for split in (False, True):
        with two_boards(tmp_path, "split" if split else "plain") as boards:
            r = halrun(tmp_path, session(boards, split, rates), timeout=300)
        out = r.stdout + r.stderr
        assert r.returncode == 0, out
        v = values(out)
        # exported either way (show funct); in the thread only when added
        in_thread = [f for f in v["thread"] if "hm2_7i96s" in f]
        for b in BOARDS:
            assert f"{b}.read-request" in out, out
            assert any(f"{b}.read-request" in f for f in in_thread) == split, in_thread
        got[split] = {b: v[b] for b in BOARDS}
        for b, rate in zip(BOARDS, rates):
            # something moved: 25 periods of 1 ms at `rate` steps/s, quadrature at 3x
            assert num(v, b, 0) >= rate * 0.025 * 0.7, out
            assert num(v, b, 4) >= rate * 3 * 0.025 * 0.7, out
            assert v[b][7:] == ["0", "FALSE"], out
    assert got[True] == got[False]


def test_read_request_lost_replies(tmp_path: Path, rig: tuple) -> None:  # noqa: F811
    """The loss scenario of test_hm2_eth_loss with read-request before read:
    the same packet-error arithmetic, io_error at the limit, recovery."""
    proxy, ctl = rig
    front = proxy.front.getsockname()[0]
    run = f"loadusr -w {sys.executable} {ctl}"
    script = (
        "loadrt hostmot2\n"
        f'loadrt hm2_eth board_ip={front} config="num_encoders=1 num_stepgens=5"\n'
        f"setp {PFX}.packet-read-timeout {TIMEOUT_NS}\n"
        f"setp {PFX}.packet-error-limit 100\n"
        "loadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read-request servo\naddf {PFX}.read servo\naddf {PFX}.write servo\n"
        "simrun 4ms\n" + tag("clean", *ERR) + f"{run} drop 3\n"
        "simrun 9ms\n" + tag("lossy", *ERR) + f"{run} drop 0\n"
        "simrun 20ms\n" + tag("recovered", *ERR) + f"setp {PFX}.packet-error-limit 6\n"
        f"{run} drop 1\n"
        "simrun 6ms\n" + tag("gone", *ERR) + f"{run} drop 0\n"
        f"setp {PFX}.io_error 0\n"
        "simrun 10ms\n" + tag("back", *ERR)
    )
    r = halrun(tmp_path, script, timeout=300)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    assert v["clean"][:5] == ["FALSE", "0", "FALSE", "0", "FALSE"], out
    lossy = [i % 3 == 2 for i in range(9)]
    lv, tot = level_model(lossy, 2, 1, 100)
    assert v["lossy"][:5] == ["TRUE", str(lv), "FALSE", str(tot), "FALSE"], out
    assert v["recovered"][:5] == ["FALSE", "0", "FALSE", str(tot), "FALSE"], out
    # limit 6 from level 0: three lost replies; then io_error stops the
    # requests (no datagram in the last three periods)
    assert v["gone"][2:] == ["TRUE", str(tot + 3), "TRUE"], out
    assert out.count("reached packet-error-limit 6") == 1, out
    # reported once per streak of lost replies: 3 single losses, then the streak
    assert out.count(f"no reply to the servo-cycle read within {TIMEOUT_NS // 1000} us") == 4, out
    assert v["back"][:5] == ["FALSE", "0", "FALSE", str(tot + 3), "FALSE"], out
    assert "the board answers again" in out
    assert proxy.dropped == 3 + 3
