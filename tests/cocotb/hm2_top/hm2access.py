# SPDX-License-Identifier: GPL-2.0-or-later
"""Register access to a firmware top through its real host bus: the local
bus master for PCI-style boards, pin-level EPP cycles (the hm2_7i43 driver's
transactions, spec/hostmot2.md section 17.2) for the 7i43."""

from __future__ import annotations

from typing import Any

from common.epp import EppHost
from common.localbus import LocalBus


class Hm2Access:
    async def read(self, addr: int) -> int:
        return (await self.read_block(addr, 1))[0]

    async def write(self, addr: int, data: int) -> None:
        await self.write_block(addr, [data])

    async def read_block(self, addr: int, n: int) -> list[int]:
        raise NotImplementedError

    async def write_block(self, addr: int, data: list[int]) -> None:
        raise NotImplementedError


class LocalBusAccess(Hm2Access):
    def __init__(self, dut: Any) -> None:
        self.lb = LocalBus(dut, dut.clk_low)

    async def read_block(self, addr: int, n: int) -> list[int]:
        return await self.lb.read_burst(addr, n)

    async def write_block(self, addr: int, data: list[int]) -> None:
        await self.lb.write_burst(addr, data)


class EppAccess(Hm2Access):
    """hm2_7i43's read/write: address low and high byte with the
    auto-increment flag, then 4 data cycles per word, LSB first, then the
    timeout check."""

    def __init__(self, dut: Any) -> None:
        self.host = EppHost(
            d_in=dut.epp_d_i,
            d_out=dut.epp_d_o,
            d_oe=dut.epp_d_oe,
            nwrite=dut.epp_nwrite,
            ndatastr=dut.epp_ndatastr,
            naddrstr=dut.epp_naddrstr,
            nwait=dut.epp_nwait,
        )
        self.host.start()

    async def _address(self, addr: int) -> None:
        if not 0 <= addr <= 0x7FFF or addr % 4:
            raise ValueError(f"EPP hm2 address {addr:#x} out of range or unaligned")
        await self.host.write_addr((addr | 0x8000) & 0xFF)
        await self.host.write_addr((addr | 0x8000) >> 8)

    def _check(self, what: str, addr: int, n: int) -> None:
        if self.host.timed_out:
            raise AssertionError(
                f"EPP timeout on data cycle of {what}(addr=0x{addr:04x}, " f"size={4 * n})"
            )

    async def read_block(self, addr: int, n: int) -> list[int]:
        await self._address(addr)
        out = []
        for _ in range(n):
            out.append(await self.host.inl())
        self._check("read", addr, n)
        return out

    async def write_block(self, addr: int, data: list[int]) -> None:
        await self._address(addr)
        for w in data:
            await self.host.outl(w)
        self._check("write", addr, len(data))
