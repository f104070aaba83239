# SPDX-License-Identifier: GPL-2.0-or-later
"""Per servo cycle of pluto_servo / pluto_step against the virtual Pluto-P:
EPP cycles, simulated EPP bus time (board time the pin-level handshakes
take) and wall time of the round trips, next to LinuxCNC's anchor ("around
100 us" per servo cycle on a real port, ~1 us per EPP cycle).

The op lists are the drivers' per-period transactions (spec/pluto.md 4.1,
6.1, 11): read = A(0), R x4, status, R x16; write = A(0), W x10 (servo) or
W x12 (step).  Requests carry host time 0, so the board clock moves only by
the bus cycles themselves: the board-time delta is the bus time.
Usage: vboard_bench.py BUILD_DIR"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "common"))
import vboard  # noqa: E402

OP_ADDR_WRITE, OP_DATA_WRITE, OP_DATA_READ, OP_STATUS_READ = 1, 3, 4, 5


def cycle_ops(n_write: int) -> tuple[list[vboard.EppOp], list[vboard.EppOp], int]:
    read = [
        vboard.EppOp(OP_ADDR_WRITE, val=0),
        vboard.EppOp(OP_DATA_READ, n=4),
        vboard.EppOp(OP_STATUS_READ),
        vboard.EppOp(OP_DATA_READ, n=16),
    ]
    write = [vboard.EppOp(OP_ADDR_WRITE, val=0), vboard.EppOp(OP_DATA_WRITE, n=n_write, data=bytes(n_write))]
    return read, write, 1 + 20 + 1 + n_write


def bench(build: Path, fw: str, n_write: int, cycles: int = 2000) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        with vboard.VBoardProcess(Path(tmp) / "s", "pluto", fw, binary=build / "bin" / "vboard") as b:
            with b.client() as c:
                read, write, n_epp = cycle_ops(n_write)
                bus, wall = [], []
                for _ in range(cycles):
                    t0 = c.now()
                    w0 = time.perf_counter()
                    c.epp(read)
                    c.epp(write)
                    wall.append((time.perf_counter() - w0) * 1e6)
                    bus.append(c.board_time_ns - t0)
                bus_us = statistics.median(bus) / 1000
                print(f"{fw:12s} EPP cycles/servo cycle {n_epp:3d}   simulated bus time "
                      f"{bus_us:6.2f} us ({bus_us * 1000 / n_epp:4.0f} ns/cycle)   wall (2 round trips) "
                      f"median {statistics.median(wall):6.1f} us")


def main(argv: list[str]) -> int:
    build = Path(argv[1]) if len(argv) > 1 else ROOT / "build"
    print("--- virtual Pluto-P (pin-level EPP against the Verilated firmware)")
    bench(build, "pluto_servo", 10)
    bench(build, "pluto_step", 12)
    print("anchor: LinuxCNC pluto drivers 'around 100 us' per servo cycle on a real port, ~1 us per EPP cycle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
