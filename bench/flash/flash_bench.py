# SPDX-License-Identifier: GPL-2.0-or-later
"""bench/flash: hm2flash on a virtual 5i25 with the M25P16's own timing
(--flash-speedup 1): the board time each phase takes (what a real 5i25
would take with this tool's access pattern: 1 us per register access, two
accesses per SPI byte) and the wall time the simulation needs.

Images: the virtual firmware (68 bytes) and a full-size Spartan-6 LX9
bitstream (2,742,528 bits = 342,816 bytes, UG380's figure; random data
behind a sync word: the flash does not care).  Anchors: the part's typical
times (sector erase 0.6 s, page program 0.64 ms): 6 sectors + 1340 pages =
4.46 s of flash busy time for the full image."""

from __future__ import annotations

import os
import random
import re
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BUILD = Path(sys.argv[1])
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "common"))
import vboard  # noqa: E402

LX9_BYTES = 2_742_528 // 8


def make_bit(payload: bytes) -> bytes:
    def small(tag: bytes, text: str) -> bytes:
        body = text.encode() + b"\0"
        return tag + struct.pack(">H", len(body)) + body

    return (
        bytes.fromhex("00090FF00FF00FF00FF0000001")
        + small(b"a", "bench.ncd")
        + small(b"b", "6slx9tqg144")
        + small(b"c", "2026/01/01")
        + small(b"d", "00:00:00")
        + b"e"
        + struct.pack(">I", len(payload))
        + payload
    )


def bench(name: str, bit: Path, d: Path) -> None:
    flash = d / f"{name}.bin"
    with vboard.VBoardProcess(
        d / "b.sock", "5i25", "7I76x2", args=["--flash", str(flash), "--flash-speedup", "1"]
    ):
        t0 = time.monotonic()
        p = subprocess.run(
            [
                str(BUILD / "bin" / "hm2flash"),
                "--device",
                "5i25",
                "--addr",
                f"sim:{d / 'b.sock'}",
                "--write",
                str(bit),
            ],
            capture_output=True,
            text=True,
            timeout=3600,
        )
        wall = time.monotonic() - t0
    if p.returncode != 0:
        raise SystemExit(f"hm2flash failed: {p.stderr}")
    total = 0.0
    for m in re.finditer(r"^\s+(\w+)\s+\[#+\] 100% (\d+) bytes in ([\d.]+) s", p.stdout, re.M):
        total += float(m.group(3))
        print(
            f"  {name:10} {m.group(1):12} {int(m.group(2)):8} bytes  {float(m.group(3)):7.2f} s board time"
        )
    print(f"  {name:10} {'total':12} {'':8}        {total:7.2f} s board time, {wall:7.1f} s wall")


def bench_backup(d: Path) -> None:
    """--backup-flash of the whole M25P16 (2 MiB, byte by byte); the file
    must equal the board's flash file."""
    flash = d / "backup-src.bin"
    out = d / "backup.bin"
    with vboard.VBoardProcess(d / "b.sock", "5i25", "7I76x2", args=["--flash", str(flash)]):
        t0 = time.monotonic()
        p = subprocess.run(
            [
                str(BUILD / "bin" / "hm2flash"),
                "--device",
                "5i25",
                "--addr",
                f"sim:{d / 'b.sock'}",
                "--backup-flash",
                str(out),
            ],
            capture_output=True,
            text=True,
            timeout=3600,
        )
        wall = time.monotonic() - t0
    if p.returncode != 0:
        raise SystemExit(f"hm2flash --backup-flash failed: {p.stderr}")
    if out.read_bytes() != flash.read_bytes():
        raise SystemExit("hm2flash --backup-flash: the backup differs from the board's flash")
    m = re.search(r"100% (\d+) bytes in ([\d.]+) s", p.stdout)
    assert m, p.stdout
    print(
        f"  backup     {'Reading':12} {int(m.group(1)):8} bytes  {float(m.group(2)):7.2f} s board"
        f" time, {wall:7.1f} s wall (file equal to the flash)"
    )


def main() -> None:
    d = Path(tempfile.mkdtemp(prefix="flb"))
    small = vboard.firmware_file("5i25", "7I76x2")
    rnd = random.Random(1)
    payload = (
        b"\xff" * 16
        + b"\xaa\x99\x55\x66"
        + bytes(rnd.getrandbits(8) for _ in range(LX9_BYTES - 20))
    )
    big = d / "lx9.bit"
    big.write_bytes(make_bit(payload))
    print(
        "hm2flash --write on a virtual 5i25, M25P16 timing (anchor: full image 6 x 0.6 s erase"
        " + 1340 x 0.64 ms program = 4.46 s of flash busy time)"
    )
    bench("7I76x2", small, d)
    if os.environ.get("BENCH_FLASH_FULL", "1") != "0":
        bench("LX9-size", big, d)
        bench_backup(d)


if __name__ == "__main__":
    main()
