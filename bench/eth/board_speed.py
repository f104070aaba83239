# SPDX-License-Identifier: GPL-2.0-or-later
"""How fast the virtual 7i96S runs (not part of `make test`): the numbers
behind docs/hm2_eth.md "A full LinuxCNC session".

1. Free-running (`vboard --udp`): board time per wall time over 5 s.
2. Lockstep (`--udp-tick 1000`): 200 servo-cycle read datagrams, each
   running 1 ms of board time; wall time until each reply and the board
   process's CPU time per period.

    python bench/eth/board_speed.py   (after `make build`)
"""

from __future__ import annotations

import os
import socket
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "common"))
sys.path.insert(0, str(ROOT / "bench" / "eth"))
import lbp16  # noqa: E402
import vboard  # noqa: E402
from roundtrip import read_packet  # noqa: E402


def cpu_s(pid: int) -> float:
    f = Path(f"/proc/{pid}/stat").read_text().split(")")[1].split()
    return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")


def free_running(tmp: Path) -> None:
    ip = lbp16.unique_loopback()
    with vboard.VBoardProcess(tmp / "a.sock", "7i96s", "7i96s_d", args=["--udp", ip]) as p:
        with p.client() as c:
            b0, w0, c0 = c.now(), time.monotonic(), cpu_s(p.proc.pid)
            time.sleep(5)
            b1, w1, c1 = c.now(), time.monotonic(), cpu_s(p.proc.pid)
    ratio = (w1 - w0) * 1e9 / (b1 - b0)
    print(
        f"free-running 7i96S: {(b1 - b0) / 1e6:.2f} ms board time in {w1 - w0:.2f} s wall "
        f"(1/{ratio:.0f} of real time), board CPU {c1 - c0:.2f} s"
    )


def lockstep(tmp: Path, periods: int = 200) -> None:
    ip = lbp16.unique_loopback()
    args = ["--udp", ip, "--udp-tick", "1000"]
    with vboard.VBoardProcess(tmp / "b.sock", "7i96s", "7i96s_d", args=args) as p:
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        s.settimeout(10)
        lat = []
        c0 = cpu_s(p.proc.pid)
        for seq in range(1, periods + 1):
            t = time.monotonic()
            s.sendto(read_packet(seq), (ip, lbp16.PORT))
            s.recv(2000)
            lat.append((time.monotonic() - t) * 1000)
        c1 = cpu_s(p.proc.pid)
        s.close()
    lat.sort()
    print(
        f"lockstep 7i96S, {periods} servo reads of 1 ms board time each: reply after median "
        f"{lat[periods // 2]:.1f} ms, p90 {lat[periods * 9 // 10]:.1f} ms, max {lat[-1]:.1f} ms "
        f"wall; board CPU {1000 * (c1 - c0) / periods:.1f} ms per 1 ms period"
    )


def main() -> int:
    with tempfile.TemporaryDirectory() as d:
        free_running(Path(d))
        lockstep(Path(d))
    print("load average:", " ".join(Path("/proc/loadavg").read_text().split()[:3]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
