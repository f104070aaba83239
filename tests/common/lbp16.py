# SPDX-License-Identifier: GPL-2.0-or-later
"""A small LBP16-over-UDP client for the tests (spec/hostmot2.md 17.3),
written from the spec alone: command words are built here, not taken from
the board or the driver under test."""

from __future__ import annotations

import os
import random
import socket
import struct
from collections.abc import Sequence

PORT = 27181

SPACE_HM2, SPACE_ETHCHIP, SPACE_EEPROM, SPACE_FLASH = 0, 1, 2, 3
SPACE_TIMERS, SPACE_STATUS, SPACE_INFO = 4, 6, 7

SIZE_BITS = {1: 0, 2: 1, 4: 2, 8: 3}


def cmd(
    space: int,
    size: int,
    count: int,
    write: bool = False,
    addr: bool = True,
    inc: bool = True,
    info: bool = False,
) -> int:
    """The 16-bit command word."""
    return (
        (0x8000 if write else 0)
        | (0x4000 if addr else 0)
        | (0x2000 if info else 0)
        | (space << 10)
        | (SIZE_BITS[size] << 8)
        | (0x80 if inc else 0)
        | count
    )


def read(space: int, size: int, a: int, count: int, inc: bool = True, info: bool = False) -> bytes:
    return struct.pack("<HH", cmd(space, size, count, inc=inc, info=info), a)


def write(space: int, size: int, a: int, values: Sequence[int], inc: bool = True) -> bytes:
    fmt = {2: "H", 4: "I"}[size]
    return struct.pack("<HH", cmd(space, size, len(values), True, inc=inc), a) + struct.pack(
        f"<{len(values)}{fmt}", *values
    )


def unique_loopback() -> str:
    """A 127.x.y.z address of its own for one test (several boards, parallel runs)."""
    r = random.Random(os.getpid() ^ random.getrandbits(32))
    return f"127.{r.randint(1, 254)}.{r.randint(0, 255)}.{r.randint(2, 254)}"


class Lbp16Client:
    def __init__(self, ip: str, port: int = PORT, timeout: float = 2.0) -> None:
        self.addr = (ip, port)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.settimeout(timeout)

    def close(self) -> None:
        self.sock.close()

    def __enter__(self) -> Lbp16Client:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def send(self, pkt: bytes) -> None:
        self.sock.sendto(pkt, self.addr)

    def transact(self, pkt: bytes) -> bytes:
        self.send(pkt)
        data, _ = self.sock.recvfrom(65536)
        return data

    def no_reply(self, pkt: bytes, wait: float = 0.3) -> bool:
        """Send pkt; True if nothing comes back within `wait` seconds."""
        self.send(pkt)
        old = self.sock.gettimeout()
        self.sock.settimeout(wait)
        try:
            self.sock.recvfrom(65536)
            return False
        except socket.timeout:
            return True
        finally:
            self.sock.settimeout(old)

    def words16(self, space: int, a: int, count: int, info: bool = False) -> list[int]:
        d = self.transact(read(space, 2, a, count, info=info))
        return list(struct.unpack(f"<{count}H", d))

    def words32(self, space: int, a: int, count: int, inc: bool = True) -> list[int]:
        d = self.transact(read(space, 4, a, count, inc=inc))
        return list(struct.unpack(f"<{count}I", d))

    def board_name(self) -> bytes:
        return self.transact(read(SPACE_INFO, 2, 0, 8))

    def status(self) -> dict[str, int]:
        w = self.words16(SPACE_STATUS, 0, 10)
        keys = ["flags", "parse", "memory", "write", "rx", "rx_udp", "rx_bad", "tx", "tx_udp"]
        return dict(zip(keys, w))
