# SPDX-License-Identifier: GPL-2.0-or-later
"""Master for the hm2 internal register bus (hdl/hostmot2/README.md).

The bus is synchronous to ClockLow: ``bus_addr`` (byte address),
``bus_wdata``, one-cycle ``bus_we`` / ``bus_re`` strobes and a registered
``bus_rdata`` that is valid the cycle after ``bus_re`` and 0 when the read was
not addressed to the module.  This master drives the signals on the falling
edge, so every access is sampled cleanly on the next rising edge, and it
returns the simulation time of that rising edge so a cycle-accurate reference
model can apply the access at exactly the same clock.

Besides plain reads and writes it checks the two bus rules a module can break
on its own: read data must be 0 outside a read that hit the module
(:meth:`read` with ``expect_zero``) and must be held until the next read
(:meth:`check_hold`)."""

from __future__ import annotations

from cocotb.handle import SimHandleBase
from cocotb.triggers import FallingEdge, Lock, RisingEdge
from cocotb.utils import get_sim_time


class BusError(AssertionError):
    """A module broke a bus rule (read data not 0 / not held)."""


class Hm2Bus:
    """Drives ``<prefix>addr/wdata/we/re`` and samples ``<prefix>rdata`` of a
    hm2 module (or the whole core) clocked by ``clk``."""

    def __init__(
        self, dut: SimHandleBase, clk: SimHandleBase | None = None, prefix: str = "bus_"
    ) -> None:
        self.clk = clk if clk is not None else dut.clk
        self.addr = getattr(dut, prefix + "addr")
        self.wdata = getattr(dut, prefix + "wdata")
        self.we = getattr(dut, prefix + "we")
        self.re = getattr(dut, prefix + "re")
        self.rdata = getattr(dut, prefix + "rdata")
        self._lock = Lock()
        self.writes = 0
        self.reads = 0
        self.idle()

    def idle(self) -> None:
        """Put the bus in its idle state (call before reset is released)."""
        self.addr.value = 0
        self.wdata.value = 0
        self.we.value = 0
        self.re.value = 0

    @staticmethod
    def _check_addr(addr: int) -> None:
        if not 0 <= addr <= 0xFFFF or addr % 4:
            raise ValueError(f"hm2 bus address {addr:#x} is not an aligned 16-bit byte address")

    async def write(self, addr: int, data: int) -> float:
        """One 32-bit write; returns the sim time (ns) of the rising edge that
        takes it."""
        self._check_addr(addr)
        if not 0 <= data <= 0xFFFFFFFF:
            raise ValueError(f"hm2 bus write data {data:#x} does not fit in 32 bits")
        async with self._lock:
            await FallingEdge(self.clk)
            self.addr.value = addr
            self.wdata.value = data
            self.we.value = 1
            await RisingEdge(self.clk)
            t = get_sim_time("ns")
            await FallingEdge(self.clk)
            self.we.value = 0
            self.writes += 1
            return t

    async def read(self, addr: int) -> int:
        """One 32-bit read (one ``bus_re`` pulse); returns ``bus_rdata``."""
        value, _ = await self.read_timed(addr)
        return value

    async def read_timed(self, addr: int) -> tuple[int, float]:
        """Like :meth:`read`, also returns the sim time (ns) of the rising
        edge that sampled ``bus_re`` (the data is the state before it)."""
        self._check_addr(addr)
        async with self._lock:
            await FallingEdge(self.clk)
            self.addr.value = addr
            self.re.value = 1
            await RisingEdge(self.clk)
            t = get_sim_time("ns")
            await FallingEdge(self.clk)
            self.re.value = 0
            # Registered data changed on the rising edge; it is stable here.
            value = int(self.rdata.value)
            self.reads += 1
            return value, t

    async def read_expect_zero(self, addr: int) -> None:
        """A read that must not hit the module: the data must be 0."""
        value = await self.read(addr)
        if value != 0:
            raise BusError(
                f"read of {addr:#06x} returned {value:#010x}, expected 0 "
                "(unaddressed or write-only register)"
            )

    async def check_hold(self, cycles: int = 3) -> int:
        """The last read data must stay unchanged while no read is issued."""
        await FallingEdge(self.clk)
        first = int(self.rdata.value)
        for _ in range(cycles):
            await FallingEdge(self.clk)
            now = int(self.rdata.value)
            if now != first:
                raise BusError(f"bus_rdata changed from {first:#x} to {now:#x} without a read")
        return first
