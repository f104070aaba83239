# SPDX-License-Identifier: GPL-2.0-or-later
"""The virtual Ethernet boards' LBP16 responder (vboard --udp), checked
with a client built from spec/hostmot2.md 17.3: board information, info
areas, hm2 access with and without increment (against the same registers
read over the vboard socket), the EEPROM and flash write keys, error
counters and datagrams that get no reply."""

from __future__ import annotations

import os
import resource
import socket
import subprocess
import struct
from collections.abc import Iterator
from pathlib import Path

import pytest
from vbhelpers import stop_clean, vboard

import lbp16
from lbp16 import Lbp16Client

# Spec 17.3: (space, info word 1, info word 2, name) of the stock firmware.
INFO_AREAS = [
    (0, 0x8104, 16, b"HostMot2"),
    (1, 0x8102, 8, b"KSZ8851\0"),
    (2, 0x8E02, 7, b"EtherEEP"),
    (3, 0x8F04, 0x8200, b"FPGAFlsh"),
    (4, 0x8202, 4, b"Timers\0\0"),
    (6, 0x8202, 4, b"LBP16RW\0"),
    (7, 0x0202, 4, b"LBP16RO\0"),
]
IDROM_COOKIE = 0x55AACAFE
# Where mesaflash writes the 7i96S's user configuration (32 Mbit flash; its
# --fallback goes to 0): recorded in tests/data/eth/mesaflash/.
USER_96S = 0x200000


def start(sockdir: Path, board: str, fw: str, ip: str, *extra: str) -> vboard.VBoardProcess:
    last = ""
    for _ in range(5):  # another test may hold that address: take another
        try:
            return vboard.VBoardProcess(sockdir / "b.sock", board, fw, args=["--udp", ip, *extra])
        except RuntimeError as e:
            last = str(e)
            if "Address already in use" not in last:
                raise
            ip = lbp16.unique_loopback()
    raise RuntimeError(last)


@pytest.fixture
def eth96(sockdir: Path) -> Iterator[tuple[vboard.VBoardProcess, Lbp16Client]]:
    ip = lbp16.unique_loopback()
    p = start(sockdir, "7i96s", "7i96s_d", ip)
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    c = Lbp16Client(ip)
    try:
        yield p, c
    finally:
        c.close()
        stop_clean(p)


def test_ready_line_names_the_udp_address(sockdir: Path) -> None:
    p = start(sockdir, "7i92", "7I76x2", "127.0.0.1:0")
    try:
        assert "udp 127.0.0.1:" in p.ready_line and "(7i92, 7I76x2)" in p.ready_line
    finally:
        stop_clean(p)


def test_board_name_and_identity(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    p, c = eth96
    assert c.board_name() == b"7I96S" + b"\0" * 11  # NUL padded: mesaflash compares 16 bytes
    ver, fw, ipsrc = c.words16(lbp16.SPACE_INFO, 0x10, 3)
    assert ver == 3 and fw > 14 and ipsrc == 1
    mac = c.transact(lbp16.read(lbp16.SPACE_EEPROM, 2, 2, 3))
    ip = c.addr[0].split(".")
    # 00:60:1B (Mesa's OUI) + the IP's low three bytes; the low word comes first.
    assert mac[::-1] == bytes([0x00, 0x60, 0x1B, int(ip[1]), int(ip[2]), int(ip[3])])
    lo, hi = c.words16(lbp16.SPACE_EEPROM, 0x20, 2)
    assert socket.inet_ntoa(struct.pack(">I", hi << 16 | lo)) == c.addr[0]


@pytest.mark.parametrize("space,type_size,rng,name", INFO_AREAS)
def test_info_areas(
    eth96: tuple[vboard.VBoardProcess, Lbp16Client],
    space: int,
    type_size: int,
    rng: int,
    name: bytes,
) -> None:
    _, c = eth96
    w = c.words16(space, 0, 8, info=True)
    assert w[0] == 0x5A00 + space
    assert w[1] == type_size and w[2] == rng
    assert struct.pack("<4H", *w[4:]) == name


def test_hm2_space_matches_the_socket(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    p, c = eth96
    assert c.words32(lbp16.SPACE_HM2, 0x0100, 1) == [IDROM_COOKIE]
    with p.client() as sc:
        want = sc.read(0x0100, 64)
        idrom = sc.read32(0x010C)
        want_idrom = sc.read(idrom, 32)
    # 64 words in two commands of one datagram: one reply, back to back
    pkt = lbp16.read(0, 4, 0x0100, 40) + lbp16.read(0, 4, 0x0100 + 160, 24)
    got = struct.unpack("<64I", c.transact(pkt))
    assert list(got) == want
    assert c.words32(lbp16.SPACE_HM2, idrom, 32) == want_idrom
    # no increment: the same register every time
    assert c.words32(lbp16.SPACE_HM2, 0x0100, 5, inc=False) == [IDROM_COOKIE] * 5


def test_hm2_writes_reach_the_firmware(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    p, c = eth96
    # IOPort 0 DDR (0x1100) and output (0x1000): LBP16 writes, socket reads
    assert c.no_reply(lbp16.write(0, 4, 0x1100, [0x1FFFF]))
    assert c.no_reply(lbp16.write(0, 4, 0x1000, [0x0A5A5]))
    with p.client() as sc:
        assert sc.read32(0x1100) & 0x1FFFF == 0x1FFFF
        pins = [sc.pin(i).level for i in range(17)]
    assert pins == [(0x0A5A5 >> i) & 1 for i in range(17)]
    # without increment the last value stays
    assert c.no_reply(lbp16.write(0, 4, 0x1000, [1, 2, 0x155], inc=False))
    with p.client() as sc:
        assert [sc.pin(i).level for i in range(9)] == [1, 0, 1, 0, 1, 0, 1, 0, 1]


def test_address_pointer_without_address(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    _, c = eth96
    # read 2 words at 0x100 with increment, then 2 more from the saved pointer
    pkt = lbp16.read(0, 4, 0x0100, 2) + struct.pack("<H", lbp16.cmd(0, 4, 2, addr=False))
    w = struct.unpack("<4I", c.transact(pkt))
    assert w[0] == IDROM_COOKIE
    assert list(w) == c.words32(0, 0x0100, 4)
    # the info area shows the pointer
    c.transact(lbp16.read(lbp16.SPACE_TIMERS, 2, 0x10, 3))
    assert c.words16(lbp16.SPACE_TIMERS, 0, 8, info=True)[3] == 0x16


def test_scratch_round_trip_and_timer(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    _, c = eth96
    pkt = lbp16.write(lbp16.SPACE_TIMERS, 2, 0x10, [0x1234, 0x5678]) + lbp16.read(
        lbp16.SPACE_TIMERS, 2, 0x10, 2
    )
    assert struct.unpack("<2H", c.transact(pkt)) == (0x1234, 0x5678)


def test_errors_are_counted_and_get_no_reply(
    eth96: tuple[vboard.VBoardProcess, Lbp16Client],
) -> None:
    _, c = eth96
    s0 = c.status()
    # count 0: parse error
    assert c.no_reply(struct.pack("<HH", lbp16.cmd(0, 4, 1) & ~0x7F, 0x100))
    # space 5 does not exist; 16-bit access to the hm2 space; beyond the range
    assert c.no_reply(lbp16.read(5, 2, 0, 1))
    assert c.no_reply(lbp16.read(0, 2, 0x100, 1))
    assert c.no_reply(lbp16.read(0, 4, 0xFFFC, 2))
    # truncated write data, a lone byte
    assert c.no_reply(lbp16.write(0, 4, 0x1000, [1, 2])[:-3])
    assert c.no_reply(b"\x01")
    # EEPROM and board info are not writable without the key / at all
    assert c.no_reply(lbp16.write(lbp16.SPACE_EEPROM, 2, 0x20, [1]))
    assert c.no_reply(lbp16.write(lbp16.SPACE_INFO, 2, 0x00, [1]))
    s1 = c.status()
    assert s1["parse"] - s0["parse"] == 3
    assert s1["memory"] - s0["memory"] == 3
    assert s1["write"] - s0["write"] == 2
    assert s1["flags"] & 7 == 7
    assert s1["rx"] - s0["rx"] == 9  # the eight above and the status read itself
    assert s1["tx"] - s0["tx"] == 1
    # a reply that fails after a good read sends nothing either
    assert c.no_reply(lbp16.read(0, 4, 0x100, 1) + lbp16.read(5, 2, 0, 1))
    # the board still answers
    assert c.words32(0, 0x0100, 1) == [IDROM_COOKIE]


def test_eeprom_write_needs_the_key(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    _, c = eth96
    key = lbp16.write(lbp16.SPACE_STATUS, 2, 0x1A, [0x5A03])
    assert c.no_reply(key + lbp16.write(lbp16.SPACE_EEPROM, 2, 0x28, [0x0003]))
    assert c.words16(lbp16.SPACE_EEPROM, 0x28, 1) == [3]
    # the key holds for one datagram only
    assert c.no_reply(lbp16.write(lbp16.SPACE_EEPROM, 2, 0x28, [0x0000]))
    assert c.words16(lbp16.SPACE_EEPROM, 0x28, 1) == [3]


def test_flash_id_erase_write_read(eth96: tuple[vboard.VBoardProcess, Lbp16Client]) -> None:
    _, c = eth96
    assert c.words32(lbp16.SPACE_FLASH, 0x8, 1) == [
        0x15
    ]  # 32 Mbit (spec 17.3: 0x10 = 1 Mbit ... 0x15 = 32 Mbit)
    key = lbp16.write(lbp16.SPACE_STATUS, 2, 0x1A, [0x5A03])
    a = 0x3F0000  # the last sector
    # erase without the key: refused
    assert c.no_reply(lbp16.write(3, 4, 0, [a]) + lbp16.write(3, 4, 0xC, [0]))
    assert c.no_reply(key + lbp16.write(3, 4, 0, [a]) + lbp16.write(3, 4, 0xC, [0]))
    c.no_reply(lbp16.write(3, 4, 0, [a]))
    assert c.words32(3, 4, 4, inc=False) == [0xFFFFFFFF] * 4
    data = [0x12345678, 0x9ABCDEF0, 0x0F0F0F0F, 0x00FF00FF]
    assert c.no_reply(key + lbp16.write(3, 4, 0, [a]) + lbp16.write(3, 4, 4, data, inc=False))
    c.no_reply(lbp16.write(3, 4, 0, [a]))
    assert c.words32(3, 4, 4, inc=False) == data
    # programming only clears bits: writing 1s over 0s leaves the 0s
    assert c.no_reply(key + lbp16.write(3, 4, 0, [a]) + lbp16.write(3, 4, 4, [0xFFFF0000]))
    c.no_reply(lbp16.write(3, 4, 0, [a]))
    assert c.words32(3, 4, 1) == [0x12340000]


@pytest.mark.parametrize(
    "args,text",
    [
        (["--board", "7i96s", "--udp", "127.0.0.1:99999"], "bad --udp '127.0.0.1:99999'"),
        (["--board", "7i96s", "--udp", "localhost"], "want an IPv4 address"),
        (["--board", "7i96s", "--udp-tick", "1000"], "--udp-tick needs --udp"),
        (["--board", "7i96s", "--udp", "127.0.0.1:0", "--udp-tick", "0"], "bad --udp-tick '0'"),
        (["--board", "5i20", "--udp", "127.0.0.1:0"], "--udp is for Ethernet boards"),
        (["--board", "7i92"], "--socket and --board are required"),
        (["--board", "7i92", "--udp", "192.0.2.1"], "cannot listen for LBP16 on UDP 192.0.2.1"),
        (
            ["--board", "7i96s", "--udp", "127.0.0.1:0", "--udp-tick", "10", "--udp-rt"],
            "--udp-rt needs --udp and a free-running board (no --udp-tick",
        ),
        (["--board", "7i96s", "--socket", "x.sock", "--udp-rt"], "--udp-rt needs --udp"),
    ],
)
def test_command_line_errors(args: list[str], text: str) -> None:
    r = subprocess.run(
        [str(vboard.vboard_binary()), *args], capture_output=True, text=True, timeout=30
    )
    assert r.returncode != 0
    assert text in r.stderr, r.stderr


def flash_write(c: Lbp16Client, addr: int, data: bytes) -> None:
    """Erase the 64 KiB sectors under [addr, addr+len) and program data (spec 17.3 space 3)."""
    key = lbp16.write(lbp16.SPACE_STATUS, 2, 0x1A, [0x5A03])
    for sector in range(addr & ~0xFFFF, addr + len(data), 0x10000):
        assert c.no_reply(key + lbp16.write(3, 4, 0, [sector]) + lbp16.write(3, 4, 0xC, [0]))
    data += b"\xff" * (-len(data) % 4)
    for off in range(0, len(data), 256):
        chunk = data[off : off + 256]
        words = list(struct.unpack(f"<{len(chunk) // 4}I", chunk))
        pkt = key + lbp16.write(3, 4, 0, [addr + off]) + lbp16.write(3, 4, 4, words, inc=False)
        assert c.no_reply(pkt, wait=0.05)


def flash_read(c: Lbp16Client, addr: int, n: int) -> bytes:
    out = b""
    c.no_reply(lbp16.write(3, 4, 0, [addr]), wait=0.05)
    while len(out) < n:
        out += struct.pack("<64I", *c.words32(3, 4, 64, inc=False))
    return out[:n]


def reload(c: Lbp16Client) -> None:
    """The 7i96S's reconfiguration words as mesaflash --reload writes them to space 6 0x1E."""
    icap = [0x0005, 0x000D]
    assert c.no_reply(lbp16.write(lbp16.SPACE_STATUS, 2, 0x1E, icap, inc=False))


def test_blank_flash_then_firmware_written_over_lbp16(sockdir: Path, tmp_path: Path) -> None:
    """A board with an erased flash stays blank (the hm2 space does not
    answer); the 7i96s_d .BIT written to the user area through space 3 and
    a reload bring it up; the flash file keeps it for the next start."""
    bit = (vboard.build_dir() / "lib" / "firmware" / "hm2" / "7i96s" / "7i96s_d.BIT").read_bytes()
    flash = tmp_path / "flash.bin"
    p = start(sockdir, "7i96s", "", lbp16.unique_loopback(), "--flash", str(flash))
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    try:
        assert "blank" in p.ready_line
        assert flash.stat().st_size == 4 << 20
        with Lbp16Client(ip) as c:
            assert c.board_name()[:5] == b"7I96S"  # the Ethernet engine works while blank
            assert c.no_reply(lbp16.read(0, 4, 0x0100, 1))
            flash_write(c, USER_96S, bit)
            assert flash_read(c, USER_96S, len(bit)) == bit
            reload(c)
            assert c.words32(0, 0x0100, 1) == [IDROM_COOKIE]
    finally:
        stop_clean(p)
    assert flash.read_bytes()[USER_96S : USER_96S + len(bit)] == bit
    p = start(sockdir, "7i96s", "", lbp16.unique_loopback(), "--flash", str(flash))
    try:
        assert "7i96s_d" in p.ready_line
    finally:
        stop_clean(p)


def test_corrupt_user_image_falls_back(sockdir: Path, tmp_path: Path) -> None:
    """--firmware programs a new flash (fallback and user areas); a user
    area overwritten with junk makes the reload use the fallback image."""
    flash = tmp_path / "flash.bin"
    p = start(sockdir, "7i96s", "7i96s_d", lbp16.unique_loopback(), "--flash", str(flash))
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    try:
        with Lbp16Client(ip) as c:
            flash_write(c, USER_96S, b"not a bitfile")
            reload(c)
            assert c.words32(0, 0x0100, 1) == [IDROM_COOKIE]
    finally:
        stop_clean(p)
    # the flash file decides at the next start: --firmware does not rewrite it
    assert flash.read_bytes()[USER_96S : USER_96S + 13] == b"not a bitfile"


def rt_allowed() -> bool:
    return os.geteuid() == 0 or resource.getrlimit(resource.RLIMIT_RTPRIO)[0] >= 1


def test_udp_rt_serves_at_realtime_priority(sockdir: Path) -> None:
    """--udp-rt (stock mesaflash's 2 ms probe window on a loaded machine):
    the serving loop runs SCHED_FIFO 1 and answers; where the process may
    not raise its priority the start fails saying why."""
    ip = lbp16.unique_loopback()
    if not rt_allowed():
        with pytest.raises(RuntimeError, match="cannot switch to SCHED_FIFO priority 1"):
            start(sockdir, "7i96s", "7i96s_d", ip, "--udp-rt")
        return
    p = start(sockdir, "7i96s", "7i96s_d", ip, "--udp-rt")
    ip = p.ready_line.split("udp ")[1].split(":")[0]
    try:
        assert os.sched_getscheduler(p.proc.pid) == os.SCHED_FIFO
        assert os.sched_getparam(p.proc.pid).sched_priority == 1
        with Lbp16Client(ip) as c:
            assert c.words32(lbp16.SPACE_HM2, 0x100, 1) == [IDROM_COOKIE]
            assert c.board_name().rstrip(b"\0") == b"7I96S"
    finally:
        stop_clean(p)
