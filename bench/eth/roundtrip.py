# SPDX-License-Identifier: GPL-2.0-or-later
"""Servo-cycle round trip over loopback UDP against the virtual 7i96S
(`vboard --udp`, free-running): per cycle one read datagram (the hm2
reads hm2_eth queues for a 7i96s_d config with 1 encoder, 5 stepgens, 1
pwmgen, plus the sequence-number tail; one reply) and one write datagram
(no reply), as hm2_eth sends them.  Prints the time from sending the read
to having sent the write, per cycle: median, 90th and 99th percentile.
Anchor: hm2_eth on real hardware ~104 us per cycle; goal <= 50 us here.

    python bench/eth/roundtrip.py [CYCLES]   (after `make build`)
"""

from __future__ import annotations

import os
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "common"))
import lbp16  # noqa: E402

BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))


def read_packet(seq: int) -> bytes:
    reads = [(0x1000, 3), (0x0D00, 1), (0x3300, 1), (0x3000, 1), (0x3100, 1), (0x2100, 5)]
    pkt = b"".join(lbp16.read(0, 4, a, n) for a, n in reads)
    pkt += lbp16.read(6, 2, 0x08, 1)
    pkt += lbp16.write(4, 2, 0x10, [seq & 0xFFFF, seq >> 16])
    return pkt + lbp16.read(4, 2, 0x10, 4)


def write_packet(seq: int) -> bytes:
    writes = [(0x1000, [0] * 3), (0x2000, [0] * 5), (0x0C00, [0]), (0x4000, [0])]
    pkt = b"".join(lbp16.write(0, 4, a, w) for a, w in writes)
    return pkt + lbp16.write(4, 2, 0x14, [seq & 0xFFFF, seq >> 16])


def main() -> int:
    cycles = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    ip = lbp16.unique_loopback()
    vb = subprocess.Popen(
        [str(BUILD / "bin" / "vboard"), "--board", "7i96s", "--firmware", "7i96s_d", "--udp", ip],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert vb.stdout is not None and "ready" in vb.stdout.readline()
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        s.connect((ip, lbp16.PORT))
        s.settimeout(1.0)
        times = []
        lost = 0
        for seq in range(1, cycles + 1):
            t0 = time.perf_counter()
            s.send(read_packet(seq))
            try:
                reply = s.recv(2048)
                assert struct.unpack_from("<I", reply, len(reply) - 8)[0] == seq
            except socket.timeout:
                lost += 1
            s.send(write_packet(seq))
            times.append((time.perf_counter() - t0) * 1e6)
            time.sleep(0.0005)
        times.sort()
        n = len(times)
        print(f"eth servo round trip over loopback UDP, {n} cycles, 2 datagrams per cycle:")
        print(
            f"  median {times[n // 2]:.0f} us, p90 {times[n * 9 // 10]:.0f} us, "
            f"p99 {times[n * 99 // 100]:.0f} us, lost {lost} (anchor hm2_eth ~104 us, goal <= 50)"
        )
    finally:
        vb.terminate()
        vb.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
