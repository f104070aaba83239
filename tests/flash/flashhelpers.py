# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers of the configuration-flash tests: .BIT files, the flash layout of
Mesa's Spartan-6 boards (the reference the tests hold the tools to), and a
runner for bin/hm2flash."""

from __future__ import annotations

import struct
import subprocess
import sys
import zlib
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT / "tests" / "common") not in sys.path:
    sys.path.insert(0, str(ROOT / "tests" / "common"))

import vboard  # noqa: E402

FLASH_SIZE = 2 << 20  # M25P16
BOOT, FALLBACK, USER = 0x000000, 0x010000, 0x100000
SECTOR = 0x10000
PAGE_SIZE = 256
# The boot block stock mesaflash writes (tests/data/eth/mesaflash/
# 7i92-bootblock.hex, recorded by the Ethernet tests): sync, GENERAL1/2 =
# user address 0x100000 with read opcode 0x0B, GENERAL3/4 = fallback
# 0x010000, CMD = IPROG, NOOPs.
BOOT_BLOCK = bytes.fromhex(
    "".join(
        (ROOT / "tests" / "data" / "eth" / "mesaflash" / "7i92-bootblock.hex").read_text().split()
    )
)[:64]

BIT_HEADER = bytes.fromhex("00090FF00FF00FF00FF0000001")


def hm2flash_binary() -> Path:
    return vboard.build_dir() / "bin" / "hm2flash"


def firmware_bit(board: str = "5i25", fw: str = "7I76x2") -> bytes:
    return vboard.firmware_file(board, fw).read_bytes()


def make_bit(payload: bytes, part: str = "6slx9tqg144", design: str = "test.ncd") -> bytes:
    """A .BIT container around `payload` (spec: header, a/b/c/d, e)."""

    def small(tag: bytes, text: str) -> bytes:
        body = text.encode() + b"\0"
        return tag + struct.pack(">H", len(body)) + body

    return (
        BIT_HEADER
        + small(b"a", design)
        + small(b"b", part)
        + small(b"c", "2026/01/01")
        + small(b"d", "00:00:00")
        + b"e"
        + struct.pack(">I", len(payload))
        + payload
    )


def vbfw_image(board: str, firmware: str, idrom_crc: int) -> bytes:
    """A virtual-board firmware image (docs/vboard.md, "Firmware files")."""
    head = struct.pack("<4sIII16s32s", b"VBFW", 1, 68, idrom_crc, board.encode(), firmware.encode())
    return head + struct.pack("<I", zlib.crc32(head))


def run(*args: str, check: int | None = 0) -> subprocess.CompletedProcess[str]:
    p = subprocess.run([str(hm2flash_binary()), *args], capture_output=True, text=True, timeout=600)
    if check is not None:
        assert p.returncode == check, (p.returncode, p.stdout, p.stderr)
    return p


# start_board's type (the fixture in conftest.py).  It lives here, not in
# conftest.py: `from conftest import` finds whichever conftest.py pytest
# loaded first when it collects the whole tests/ tree.
StartBoard = Callable[..., vboard.VBoardProcess]
