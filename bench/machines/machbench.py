# SPDX-License-Identifier: GPL-2.0-or-later
"""Lockstep cost of a 1 ms servo cycle with and without the machine models.

Each cycle is what hm2_sim sends for the servo mill: one read burst (the
encoders' counts and timestamps, watchdog, GPIO: 23 words) and one write
burst (PWM values, enables, watchdog pet, GPIO: 16 words) stamped with the
next millisecond of host time, so the board simulates 1 ms of firmware per
cycle.  Three PWMGens run at 25 % duty into the three axes' amplifiers
(motors turning, encoders counting) or, without a machine, into nothing.
Rounds alternate between the two boards; the median of each is reported.
"""

from __future__ import annotations

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "common"))
import vboard  # noqa: E402

MACHINE = ROOT / "examples" / "machines" / "servo-mill" / "machine.toml"
PWM_PINS = [7, 9, 11, 6, 8, 10, 19, 21, 23]  # PWMGen 0-2 Out0, Out1, NotEnable


def setup(c: vboard.VBoardClient) -> None:
    mask = sum(1 << p for p in PWM_PINS)
    c.write(0x1100, mask)  # DDR
    c.write(0x1200, mask)  # AltSource: the PWMGens drive their pins
    c.write(0x4200, 53687)  # 20 kHz at 12 bit
    for n in range(3):
        c.write(0x4100 + 4 * n, 0x3 | 1 << 5)
        c.write(0x4000 + 4 * n, 1024 << 16)  # 25 %
    c.write(0x4400, 0x7)  # enables


def cpu_s(pid: int) -> float:
    """User + system CPU time of a process (the board's own work: no
    scheduling noise from other processes on a shared machine)."""
    f = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")


def cycles(c: vboard.VBoardClient, t0: int, n: int) -> tuple[float, int]:
    reads = [(0x3000, 12), (0x3100, 12), (0x0C00, 4), (0x1000, 12), (0x0D00, 4)]
    reads += [(0x3000 + 0x100 * k, 4) for k in range(2, 6)]
    writes = [(0x4000, [1024 << 16] * 3), (0x0E00, [0x5A000000]), (0x1000, [0] * 3)]
    writes += [(0x4400, [7])] + [(0x1400, [0] * 3)] * 3
    start = time.perf_counter()
    t = t0
    for _ in range(n):
        t += 1_000_000
        c.read_bursts(reads, time_ns=t)
        c.write_bursts(writes, time_ns=t)
    return (time.perf_counter() - start) / n, t


def main() -> int:
    n, rounds = 100, 5
    d = Path(tempfile.mkdtemp(prefix="mb"))
    boards = {
        "without machine": vboard.VBoardProcess(d / "a.sock", "5i20", "SVST8_4"),
        "with 3-axis machine": vboard.VBoardProcess(
            d / "b.sock", "5i20", "SVST8_4", args=["--machine", str(MACHINE)]
        ),
    }
    times: dict[str, list[float]] = {k: [] for k in boards}
    cpu: dict[str, list[float]] = {k: [] for k in boards}
    try:
        clients = {k: b.client() for k, b in boards.items()}
        now = {k: 1_000_000 for k in boards}
        for k, c in clients.items():
            c.read32(0x100, time_ns=now[k])
            setup(c)
            _, now[k] = cycles(c, now[k], 20)  # warm up, motors spinning up
        for _ in range(rounds):
            for k, c in clients.items():
                c0 = cpu_s(boards[k].proc.pid)
                dt, now[k] = cycles(c, now[k], n)
                cpu[k].append((cpu_s(boards[k].proc.pid) - c0) / n)
                times[k].append(dt)
        clients["with 3-axis machine"].plant("status")  # the machine is there
        for c in clients.values():
            c.close()
    finally:
        for b in boards.values():
            b.stop()
    base = statistics.median(cpu["without machine"])
    mach = statistics.median(cpu["with 3-axis machine"])
    print(f"1 ms servo cycle, 5i20 SVST8_4, 3 PWMGens at 20 kHz, lockstep ({rounds} x {n} cycles):")
    for k, v in times.items():
        print(
            f"  {k:<22s} board CPU {statistics.median(cpu[k]) * 1e3:6.2f} ms, wall "
            f"{statistics.median(v) * 1e3:6.2f} ms per cycle (medians; CPU per round: "
            f"{' '.join(f'{x * 1e3:.2f}' for x in cpu[k])})"
        )
    over = (mach - base) / base * 100
    verdict = "ok" if over <= 5 else "OVER the anchor"
    print(f"  models add {over:+.1f} % of the board's CPU time (anchor: <= 5 %): {verdict}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
