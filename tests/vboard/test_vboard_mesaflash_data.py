# SPDX-License-Identifier: GPL-2.0-or-later
"""The virtual Ethernet boards against what Debian's stock mesaflash read
from them (tests/data/eth/mesaflash, recorded by its record.sh; mesaflash
itself does not run here): memory-space info areas, board identity, the
7i92 boot block, the reload datagrams mesaflash sends."""

from __future__ import annotations

import re
import struct
from pathlib import Path

import pytest
from test_vboard_lbp16 import IDROM_COOKIE, USER_96S, start
from vbhelpers import stop_clean, vboard

import lbp16
from lbp16 import Lbp16Client

DATA = Path(__file__).resolve().parents[1] / "data" / "eth" / "mesaflash"
KIND = {0x01: "registers", 0x02: "memory", 0x0E: "EEPROM", 0x0F: "flash"}
SIZE = {1: "8-bit", 2: "16-bit", 4: "32-bit", 8: "64-bit"}


def spaces_line(space: int, w: list[int]) -> str:
    """mesaflash's 'memory spaces' line, computed from an info area."""
    name = struct.pack("<4H", *w[4:]).rstrip(b"\0").decode()
    kind = KIND[(w[1] >> 8) & 0x7F]
    rw = "RW" if w[1] & 0x8000 else "RO"
    size = [s for bit, s in SIZE.items() if w[1] & bit][0]
    n = 1 << (w[2] & 0x3F)
    sz = f"{n // 1024}K" if n >= 1024 else str(n)
    return f"{space}: {name} ({kind}, {rw}, {size}) [size={sz}]"


def test_info_areas_as_mesaflash_printed_them(sockdir: Path) -> None:
    text = (DATA / "7i96s-verbose.txt").read_text()
    recorded = re.findall(r"^    (\d: \S+ \(.*?\) \[size=\w+\])", text, re.M)
    assert len(recorded) == 7
    p = start(sockdir, "7i96s", "7i96s_d", lbp16.unique_loopback())
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    try:
        with Lbp16Client(ip) as c:
            got = [spaces_line(s, c.words16(s, 0, 8, info=True)) for s in (0, 1, 2, 3, 4, 6, 7)]
            assert got == recorded
            assert "protocol: LBP16 version 3" in text
            assert c.words16(lbp16.SPACE_INFO, 0x10, 1) == [3]
            assert "Flash size: 32Mb (id: 0x15)" in text
            assert c.words32(lbp16.SPACE_FLASH, 8, 1) == [0x15]
            assert "board name: 7I96S" in text and c.board_name().rstrip(b"\0") == b"7I96S"
    finally:
        stop_clean(p)


def test_7i92_factory_boot_block_is_mesaflash_s(sockdir: Path, tmp_path: Path) -> None:
    want = bytes.fromhex((DATA / "7i92-bootblock.hex").read_text().replace("\n", ""))
    assert len(want) == 256
    flash = tmp_path / "f92.bin"
    p = start(sockdir, "7i92", "7I76x2", lbp16.unique_loopback(), "--flash", str(flash))
    stop_clean(p)
    data = flash.read_bytes()
    assert data[:256] == want
    # the boot block names the user area where mesaflash writes (1 MiB) and the fallback
    assert data[0x100000:0x100004] == bytes.fromhex("00090ff0")
    assert data[0x010000:0x010004] == bytes.fromhex("00090ff0")


@pytest.mark.parametrize(
    "board,fw,log",
    [("7i96s", "7i96s_d", "7i96s-datagrams.log"), ("7i92", "7I76x2", "7i92-datagrams.log")],
)
def test_recorded_reload_datagram_reconfigures(
    sockdir: Path, tmp_path: Path, board: str, fw: str, log: str
) -> None:
    """The first commands of mesaflash's --reload datagram, replayed: the
    FPGA reloads from flash (the user area is overwritten first so that the
    fallback image has to come up: the board really reconfigured)."""
    line = next(
        ln
        for ln in (DATA / log).read_text().splitlines()
        if "[01 d9 1e 00" in ln and "84 bytes" in ln
    )
    raw = bytes.fromhex(line.split("[")[1].split("]")[0].replace(" ...", ""))
    # whole commands only (6 bytes each: 0xD901, address 0x1E, one word)
    cmds = [
        raw[i : i + 6] for i in range(0, len(raw) - 5, 6) if raw[i : i + 4] == b"\x01\xd9\x1e\x00"
    ]
    flash = tmp_path / "f.bin"
    p = start(sockdir, board, fw, lbp16.unique_loopback(), "--flash", str(flash))
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    user = USER_96S if board == "7i96s" else 0x100000
    try:
        with Lbp16Client(ip) as c:
            key = lbp16.write(lbp16.SPACE_STATUS, 2, 0x1A, [0x5A03])
            c.no_reply(key + lbp16.write(3, 4, 0, [user]) + lbp16.write(3, 4, 0xC, [0]))
            if board == "7i92":  # the rest of the ICAP sequence is beyond the 24 logged bytes
                tail = [0x30A1, 0x000E]
                cmds += [struct.pack("<HHH", 0xD901, 0x1E, w) for w in tail]
            assert c.no_reply(b"".join(cmds))
            assert c.words32(0, 0x0100, 1) == [IDROM_COOKIE]
            # a reconfigured board restarts its Ethernet engine: it has counted
            # the cookie read and this status read only
            assert c.status()["rx"] == 2
    finally:
        stop_clean(p)
