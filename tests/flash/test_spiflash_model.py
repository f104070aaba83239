# SPDX-License-Identifier: GPL-2.0-or-later
"""The virtual 5i25's SPI flash, driven register by register (0x70 control,
0x74 data, 0x78 ICAP) through the vboard protocol.  The reference is the
M25P16 data sheet: JEDEC ID 20 20 15, signature 0x14, status bits WIP/WEL/BP,
WREN before every write, page program wraps inside its 256-byte page,
typical busy times 0.64 ms (page) and 0.6 s (sector), scaled by
--flash-speedup."""

from __future__ import annotations

from pathlib import Path

from flashhelpers import StartBoard
from flashhelpers import USER, vboard

CTRL, DATA, ICAP = 0x70, 0x74, 0x78
BOOTSTS = 0x7C  # the virtual board's own boot status register
ICAP_COOKIE = 0x1CAB1CAB  # what mesaflash 3.4.6 wants from 0x78 before --reload


class Spi:
    def __init__(self, c: vboard.VBoardClient) -> None:
        self.c = c

    def byte(self, out: int) -> int:
        self.c.write(DATA, out)
        # 8 SCK at ClockLow/2 = 480 ns: not there yet right after the write ...
        assert self.c.read(CTRL)[0] & 4 == 0
        self.c.advance(1000)
        ctrl, data = self.c.read(CTRL, 2)
        assert ctrl & 4, "DAV must be set 1 us after the write"
        return data & 0xFF

    def frame(self, out: list[int], nin: int = 0) -> list[int]:
        self.c.write(CTRL, 0)
        got = [self.byte(b) for b in out] + [self.byte(0) for _ in range(nin)]
        self.c.write(CTRL, 1)
        return got[len(out) :]

    def status(self) -> int:
        return self.frame([0x05], 1)[0]

    def read(self, addr: int, n: int) -> bytes:
        return bytes(self.frame([0x03, addr >> 16 & 0xFF, addr >> 8 & 0xFF, addr & 0xFF], n))


def test_identity_and_status(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board()
    with b.client() as c:
        s = Spi(c)
        assert s.frame([0x9F], 3) == [0x20, 0x20, 0x15]
        assert s.frame([0xAB, 0, 0, 0], 2) == [0x14, 0x14]
        assert s.status() == 0x00
        s.frame([0x06])
        assert s.status() == 0x02  # WEL
        s.frame([0x04])
        assert s.status() == 0x00
        assert c.read(CTRL)[0] & 1 == 1  # /CS deselected


def test_program_needs_wren_and_wraps_in_page(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board(speedup=10)  # 0.64 ms -> 64 us
    with b.client() as c:
        s = Spi(c)
        a = USER + 0x1000  # erased in the factory flash
        s.frame([0x02, a >> 16 & 0xFF, a >> 8 & 0xFF, 0xFE, 0x11, 0x22, 0x33])
        c.advance(100_000)
        assert s.read(a + 0xFE, 2) == b"\xff\xff"  # no WREN: ignored
        s.frame([0x06])
        s.frame([0x02, a >> 16 & 0xFF, a >> 8 & 0xFF, 0xFE, 0x11, 0x22, 0x33])
        assert s.status() & 1  # WIP
        c.advance(50_000)
        assert s.status() & 1
        c.advance(14_000)
        assert s.status() == 0
        assert s.read(a + 0xFE, 2) == b"\x11\x22"
        assert s.read(a, 1) == b"\x33"  # wrapped to the page start
        # programming only clears bits
        s.frame([0x06])
        s.frame([0x02, a >> 16 & 0xFF, a >> 8 & 0xFF, 0xFE, 0xF0])
        c.advance(100_000)
        assert s.read(a + 0xFE, 1) == bytes([0x11 & 0xF0])


def test_sector_erase_timing(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board(speedup=1000)  # 0.6 s -> 600 us of board time
    with b.client() as c:
        s = Spi(c)
        assert s.read(USER, 4) == b"VBFW"
        s.frame([0x06])
        s.frame([0xD8, USER >> 16, 0, 0])
        t0 = c.now()
        while s.status() & 1:
            c.advance(20_000)
        busy = c.now() - t0
        assert 600_000 <= busy < 660_000, busy
        assert s.status() & 2 == 0  # WEL cleared at the end
        assert s.read(USER, 4) == b"\xff" * 4
        assert s.read(USER + 0xFFFC, 4) == b"\xff" * 4


def test_block_protect_refuses_erase(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board(speedup=1000)
    with b.client() as c:
        s = Spi(c)
        s.frame([0x06])
        s.frame([0x01, 5 << 2])  # BP=5: the upper half (0x100000..) protected
        c.advance(100_000)
        assert s.status() == 5 << 2
        top = 0x1F0000
        s.frame([0x06])
        s.frame([0xD8, top >> 16, 0, 0])
        assert s.status() & 3 == 0  # not started, WEL dropped
        s.frame([0x06])
        s.frame([0xD8, 0x08, 0, 0])  # 0x080000 is in the lower half
        assert s.status() & 1


def test_icap_iprog_reconfigures(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board()
    with b.client() as c:
        assert c.read(ICAP)[0] == ICAP_COOKIE
        assert c.read(BOOTSTS)[0] == 0x01
        for w in (0xFFFF, 0xAA99, 0x5566, 0x3261, 0x0000, 0x3281, 0x0B00, 0x30A1, 0x000E):
            c.write(ICAP, w)
        assert c.read(BOOTSTS)[0] == 0x05  # valid, by IPROG
        assert c.read(ICAP)[0] == ICAP_COOKIE
        assert c.hello().firmware == "7I76x2"
        # a cookie read works: the firmware runs again
        assert c.read(0x100)[0] == 0x55AACAFE
