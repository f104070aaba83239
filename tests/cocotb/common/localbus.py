# SPDX-License-Identifier: GPL-2.0-or-later
"""Master for the PCI-style local bus of the hm2 firmware tops
(hdl/hostmot2/hm2_localbus.v): ``lb_addr``, ``lb_wdata``, one-clock
``lb_wr`` / ``lb_rd`` strobes, ``lb_rdata`` valid while ``lb_rvalid``.

It is what a PCI bridge does on its local side when the host touches the
64 KiB window: aligned 32-bit reads and writes, optionally back to back (one
per clock, as in a burst).  Every read checks the front end's timing: the
data must come with ``lb_rvalid`` exactly ``latency`` clocks after the strobe
and ``lb_rvalid`` must never appear without a read."""

from __future__ import annotations

from collections.abc import Sequence

from cocotb.handle import SimHandleBase
from cocotb.triggers import FallingEdge, Lock


class LocalBusError(AssertionError):
    """The target broke the local bus timing."""


class LocalBus:
    def __init__(
        self,
        dut: SimHandleBase,
        clk: SimHandleBase | None = None,
        prefix: str = "lb_",
        latency: int = 2,
    ) -> None:
        self.clk = clk if clk is not None else dut.clk_low
        self.addr = getattr(dut, prefix + "addr")
        self.wdata = getattr(dut, prefix + "wdata")
        self.wr = getattr(dut, prefix + "wr")
        self.rd = getattr(dut, prefix + "rd")
        self.rdata = getattr(dut, prefix + "rdata")
        self.rvalid = getattr(dut, prefix + "rvalid")
        self.latency = latency
        self._lock = Lock()
        self.reads = 0
        self.writes = 0
        self.idle()

    def idle(self) -> None:
        self.addr.value = 0
        self.wdata.value = 0
        self.wr.value = 0
        self.rd.value = 0

    @staticmethod
    def _check(addr: int, data: int = 0) -> None:
        if not 0 <= addr <= 0xFFFF or addr % 4:
            raise ValueError(f"local bus address {addr:#x} is not an aligned 16-bit byte address")
        if not 0 <= data <= 0xFFFFFFFF:
            raise ValueError(f"local bus data {data:#x} does not fit in 32 bits")

    def _no_rvalid(self, when: str) -> None:
        if int(self.rvalid.value):
            raise LocalBusError(f"lb_rvalid set {when} (no read outstanding)")

    async def write(self, addr: int, data: int) -> None:
        await self.write_burst(addr, [data])

    async def write_burst(self, addr: int, data: Sequence[int], inc: int = 4) -> None:
        """Back-to-back writes, one per clock, to addr, addr+inc, ..."""
        async with self._lock:
            for i, d in enumerate(data):
                self._check(addr + i * inc, d)
                await FallingEdge(self.clk)
                self.addr.value = addr + i * inc
                self.wdata.value = d
                self.wr.value = 1
            await FallingEdge(self.clk)
            self.wr.value = 0
            self.writes += len(data)
            self._no_rvalid("during a write")

    async def read(self, addr: int) -> int:
        return (await self.read_burst(addr, 1))[0]

    async def read_burst(self, addr: int, n: int, inc: int = 4) -> list[int]:
        """n back-to-back reads (one strobe per clock); returns the data in
        order, checking each arrives exactly ``latency`` clocks after its
        strobe."""
        if n < 1:
            raise ValueError(f"read burst length {n} < 1")
        out: list[int] = []
        async with self._lock:
            for i in range(n):
                self._check(addr + i * inc)
            await FallingEdge(self.clk)
            self._no_rvalid("before a read")
            for k in range(n + self.latency):
                await FallingEdge(self.clk)
                if k < n:
                    self.addr.value = addr + k * inc
                    self.rd.value = 1
                else:
                    self.rd.value = 0
                j = k - self.latency  # read j's data is valid now
                if j < 0 and int(self.rvalid.value):
                    raise LocalBusError(
                        f"lb_rvalid set {k} clocks after lb_rd, " f"expected {self.latency}"
                    )
                if 0 <= j < n:
                    if not int(self.rvalid.value):
                        raise LocalBusError(
                            f"read {addr + j * inc:#06x}: lb_rvalid not set "
                            f"{self.latency} clocks after lb_rd"
                        )
                    out.append(int(self.rdata.value))
            await FallingEdge(self.clk)
            self._no_rvalid("one clock after the last read data")
            self.reads += n
        return out
