# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_eth with packet loss and late replies: a UDP proxy between the
driver and the virtual 7i96S drops every Nth reply or delivers it late.
The packet-error pins count exactly the injected faults (checked against
a model of hm2_eth(9)'s level arithmetic), HAL keeps running, the board
recovers when the loss stops, a board that stops answering is reported
once, reaches packet-error-limit and sets io_error, and clearing io_error
resumes the cycle."""

from __future__ import annotations

import socket
import sys
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from hm2e2e import BUILD, halrun, tag, values, vboard

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
import lbp16  # noqa: E402

pytestmark = pytest.mark.requires_build(BUILD / "lib" / "rtlib" / "hm2_eth.so")
PFX = "hm2_7i96s.0"
# A lost reply costs TIMEOUT_NS of wall time.  One board period takes the
# Verilated 7i96S ~35 ms of CPU; with the two cores shared by other tests a
# reply that is only slow took over 400 ms in a loaded run, so the timeout
# is far above that (the late replies come after it).
TIMEOUT_NS = 1_000_000_000


class Proxy:
    """Forwards datagrams between the driver and the board; replies can be
    dropped (every Nth) or held back (every Nth, `late_s` seconds)."""

    def __init__(self, listen_ip: str, board_ip: str) -> None:
        self.front = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.front.bind((listen_ip, lbp16.PORT))
        self.back = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.back.connect((board_ip, lbp16.PORT))
        self.ctl = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.ctl.bind(("127.0.0.1", 0))
        self.ctl.settimeout(0.05)
        self.client: tuple[str, int] | None = None
        self.drop_every = self.late_every = 0
        self.late_s = 2.0  # after TIMEOUT_NS
        self.replies = self.dropped = self.late = 0
        self.stop = False
        self.threads = [
            threading.Thread(target=self._front, daemon=True),
            threading.Thread(target=self._back, daemon=True),
            threading.Thread(target=self._control, daemon=True),
        ]
        for t in self.threads:
            t.start()

    def _front(self) -> None:
        self.front.settimeout(0.05)
        while not self.stop:
            try:
                data, addr = self.front.recvfrom(65536)
            except socket.timeout:
                continue
            self.client = addr
            self.back.send(data)

    def _back(self) -> None:
        self.back.settimeout(0.05)
        while not self.stop:
            try:
                data = self.back.recv(65536)
            except (socket.timeout, ConnectionRefusedError):
                continue
            self.replies += 1
            if self.drop_every and self.replies % self.drop_every == 0:
                self.dropped += 1
                continue
            if self.late_every and self.replies % self.late_every == 0:
                self.late += 1
                threading.Timer(self.late_s, self._send, (data,)).start()
                continue
            self._send(data)

    def _send(self, data: bytes) -> None:
        if self.client:
            self.front.sendto(data, self.client)

    def _control(self) -> None:
        while not self.stop:
            try:
                msg, addr = self.ctl.recvfrom(100)
            except socket.timeout:
                continue
            what, n = msg.decode().split()
            self.replies = 0
            self.drop_every = int(n) if what == "drop" else 0
            self.late_every = int(n) if what == "late" else 0
            self.ctl.sendto(b"ok", addr)

    def close(self) -> None:
        self.stop = True
        for t in self.threads:
            t.join()
        for s in (self.front, self.back, self.ctl):
            s.close()


@pytest.fixture
def rig(tmp_path: Path) -> Iterator[tuple[Proxy, Path]]:
    ip = lbp16.unique_loopback()
    vb = vboard.VBoardProcess(
        tmp_path / "b.sock", "7i96s", "7i96s_d", args=["--udp", ip, "--udp-tick", "1000"]
    )
    proxy = Proxy(lbp16.unique_loopback(), ip)
    ctl = tmp_path / "ctl.py"
    ctl.write_text(
        "import socket, sys\n"
        "s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)\n"
        "s.settimeout(5)\n"
        f"s.sendto(' '.join(sys.argv[1:]).encode(), ('127.0.0.1', {proxy.ctl.getsockname()[1]}))\n"
        "s.recv(10)\n"
    )
    try:
        yield proxy, ctl
    finally:
        proxy.close()
        vb.stop()
        assert "Sanitizer" not in vb.stderr_text


def level_model(events: list[bool], inc: int, dec: int, limit: int) -> tuple[int, int]:
    """hm2_eth(9): +inc per bad cycle (at most limit), -dec per good one (at least 0)."""
    level = total = 0
    for bad in events:
        total += bad
        level = min(limit, level + inc) if bad else max(0, level - dec)
    return level, total


ERR = [
    f"{PFX}.packet-error",
    f"{PFX}.packet-error-level",
    f"{PFX}.packet-error-exceeded",
    f"{PFX}.packet-error-total",
    f"{PFX}.io_error",
]


def test_loss_late_replies_recovery_and_limit(tmp_path: Path, rig: tuple[Proxy, Path]) -> None:
    proxy, ctl = rig
    front = proxy.front.getsockname()[0]
    run = f"loadusr -w {sys.executable} {ctl}"
    script = (
        "loadrt hostmot2\n"
        f'loadrt hm2_eth board_ip={front} config="num_encoders=1 num_stepgens=5"\n'
        f"setp {PFX}.packet-read-timeout {TIMEOUT_NS}\n"
        f"setp {PFX}.packet-error-limit 100\n"
        "loadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read servo\naddf {PFX}.write servo\n"
        "simrun 4ms\n" + tag("clean", *ERR) + f"{run} drop 3\n"
        "simrun 9ms\n" + tag("lossy", *ERR) + f"{run} drop 0\n"
        "simrun 20ms\n" + tag("recovered", *ERR) + f"{run} late 4\n"
        "simrun 8ms\n" + tag("late", *ERR) + f"{run} drop 0\n"
        "simrun 20ms\n"
        f"setp {PFX}.packet-error-limit 6\n" + f"{run} drop 1\n"
        "simrun 6ms\n" + tag("gone", *ERR) + f"{run} drop 0\n"
        f"setp {PFX}.io_error 0\n"
        "simrun 10ms\n" + tag("back", *ERR)
    )
    r = halrun(tmp_path, script, timeout=300)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    assert v["clean"][:5] == ["FALSE", "0", "FALSE", "0", "FALSE"], out
    # 9 cycles, every 3rd reply dropped: bad cycles 3, 6, 9
    lossy = [i % 3 == 2 for i in range(9)]
    lv, tot = level_model(lossy, 2, 1, 100)
    assert v["lossy"][:5] == ["TRUE", str(lv), "FALSE", str(tot), "FALSE"], out
    lv, tot = level_model(lossy + [False] * 20, 2, 1, 100)
    assert v["recovered"][:5] == ["FALSE", "0", "FALSE", str(tot), "FALSE"], out
    # every 4th reply 2 s late (after the 1 s timeout): that cycle is
    # bad, and the late reply, arriving during a later cycle, is not taken
    # for that cycle's reply (its sequence number is old)
    late = [i % 4 == 3 for i in range(8)]
    lv2, tot2 = level_model(lossy + [False] * 20 + late, 2, 1, 100)
    assert v["late"][1] == str(lv2) and v["late"][3] == str(tot2), out
    assert v["late"][4] == "FALSE", out
    # the board stops answering: limit 6 reached after 3 bad cycles (+2 each
    # from 0), io_error set, the driver stops; one message for the streak
    assert v["gone"][2:] == ["TRUE", str(tot2 + 3), "TRUE"], out
    assert out.count("reached packet-error-limit 6") == 1, out
    # io_error cleared: the level starts afresh and the board answers again
    assert v["back"][:5] == ["FALSE", "0", "FALSE", str(tot2 + 3), "FALSE"], out
    assert "the board answers again" in out
    assert proxy.dropped == 3 + 3 and proxy.late == 2
