# SPDX-License-Identifier: GPL-2.0-or-later
"""A virtual Ethernet board (vboard --udp on a loopback address of its own)
with its configuration flash in a file, for the hm2flash tests."""

from __future__ import annotations

from pathlib import Path

from flashhelpers import ROOT, vboard

import lbp16  # noqa: E402  (tests/common, put on the path by flashhelpers)

RECORDED = ROOT / "tests" / "data" / "eth" / "mesaflash"
# mesaflash --readhmid against this build's firmwares (tests/flash/data/record.sh)
RECORDED_HMID = ROOT / "tests" / "flash" / "data"
# Where mesaflash writes the user configuration (tests/data/eth/mesaflash,
# *-write.txt): 7i92 (Spartan-6, 16 Mbit) 0x100000 after a boot block and
# the fallback at 0x10000; 7i96S (Efinix T20, 32 Mbit) 0x200000, fallback at 0.
LAYOUT = {
    "7i92": {"size": 2 << 20, "user": 0x100000, "fallback": 0x10000},
    "7i96s": {"size": 4 << 20, "user": 0x200000, "fallback": 0x0},
}
FIRMWARE = {"7i92": "7I76x2", "7i96s": "7i96s_d"}


def start_eth(
    sockdir: Path, board: str, firmware: str | None = None
) -> tuple[vboard.VBoardProcess, str]:
    """The board and its IP address; its flash is sockdir/flash-BOARD.bin."""
    fw = firmware or FIRMWARE[board]
    last = ""
    for _ in range(5):  # another test may hold that address: take another
        ip = lbp16.unique_loopback()
        try:
            p = vboard.VBoardProcess(
                sockdir / f"{board}.sock",
                board,
                fw,
                args=["--udp", ip, "--flash", str(sockdir / f"flash-{board}.bin")],
            )
            return p, ip
        except RuntimeError as e:
            last = str(e)
            if "Address already in use" not in last:
                raise
    raise RuntimeError(last)


def recorded_output(name: str, where: Path = RECORDED) -> str:
    """A mesaflash recording without its command line and exit status."""
    lines = (where / f"{name}.txt").read_text().splitlines(keepends=True)
    assert lines[0].startswith("$ mesaflash") and lines[-1].startswith("[exit status")
    return "".join(lines[1:-1])
