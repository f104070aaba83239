# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_epp_bridge driven at pin level by the shared EPP host model
(common/epp.py, which checks the handshake) against a byte-level Python
model of the 7i43 EPP protocol (spec/hostmot2.md section 17.2).  A Python
register target on the internal bus side logs every 32-bit access, so the
test checks both what the host reads and exactly which hm2 reads/writes
(address, data, one bus_re per 32-bit read) the bridge makes."""

from __future__ import annotations

from typing import Any

import random
from dataclasses import dataclass, field
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.epp import EppHost, EppStats, EppTiming
from common.runner import SIMULATORS, hdl, run

PERIOD = 20  # 50 MHz, the 7i43 ClockLow


@dataclass
class EppBridgeModel:
    """What the host should see, and which hm2 accesses should happen."""

    addr: int = 0
    hi: bool = False
    wlatch: list[int] = field(default_factory=lambda: [0, 0, 0])
    rlatch: int = 0
    mem: dict[int, int] = field(default_factory=dict)
    ops: list[tuple[str, int, int]] = field(default_factory=list)
    reconfigs: int = 0

    def addr_write(self, b: int) -> None:
        if self.hi:
            self.addr = (self.addr & 0x00FF) | (b << 8)
        else:
            self.addr = (self.addr & 0xFF00) | b
        self.hi = not self.hi

    def addr_read(self) -> int:
        b = (self.addr >> 8) if self.hi else (self.addr & 0xFF)
        self.hi = not self.hi
        return b

    def _after_data(self) -> None:
        self.hi = False
        if self.addr & 0x8000:
            self.addr = 0x8000 | ((self.addr + 1) & 0x7FFF)

    def data_write(self, b: int) -> None:
        lane = self.addr & 3
        if self.addr == 0x7F7F and b == 0x5A:
            self.reconfigs += 1
        if lane < 3:
            self.wlatch[lane] = b
        else:
            a = self.addr & 0x7FFC
            d = self.wlatch[0] | self.wlatch[1] << 8 | self.wlatch[2] << 16 | b << 24
            self.mem[a] = d
            self.ops.append(("W", a, d))
        self._after_data()

    def data_read(self) -> int:
        lane = self.addr & 3
        if lane == 0:
            a = self.addr & 0x7FFC
            self.rlatch = self.mem.get(a, target_default(a))
            self.ops.append(("R", a, self.rlatch))
        b = (self.rlatch >> (8 * lane)) & 0xFF
        self._after_data()
        return b


def target_default(a: int) -> int:
    return (a * 0x01010101 + 0x5A) & 0xFFFFFFFF


class Target:
    """Internal-bus register target: answers bus_re one clock later, like
    every hm2 module, and logs the accesses."""

    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.mem: dict[int, int] = {}
        self.ops: list[tuple[str, int, int]] = []
        self.reconfigs = 0
        dut.bus_rdata.value = 0

    async def run(self) -> None:
        pending: int | None = None
        while True:
            await FallingEdge(self.dut.clk)
            if pending is not None:
                self.dut.bus_rdata.value = pending
                pending = None
            if int(self.dut.reconfig.value):
                self.reconfigs += 1
            a = int(self.dut.bus_addr.value)
            if int(self.dut.bus_we.value):
                d = int(self.dut.bus_wdata.value)
                self.mem[a] = d
                self.ops.append(("W", a, d))
            if int(self.dut.bus_re.value):
                pending = self.mem.get(a, target_default(a))
                self.ops.append(("R", a, pending))


async def setup(
    dut: Any, timing: EppTiming | None = None
) -> tuple[EppHost, Target, EppBridgeModel]:
    cocotb.start_soon(Clock(dut.clk, PERIOD, unit="ns").start())
    dut.rst.value = 1
    host = EppHost(
        d_in=dut.epp_d_i,
        d_out=dut.epp_d_o,
        d_oe=dut.epp_d_oe,
        nwrite=dut.epp_nwrite,
        ndatastr=dut.epp_ndatastr,
        naddrstr=dut.epp_naddrstr,
        nwait=dut.epp_nwait,
        timing=timing,
    )
    host.start()
    tgt = Target(dut)
    await ClockCycles(dut.clk, 4)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    cocotb.start_soon(tgt.run())
    await ClockCycles(dut.clk, 4)
    return host, tgt, EppBridgeModel()


class Both:
    """Runs every host cycle on the design and on the model."""

    def __init__(self, host: EppHost, m: EppBridgeModel) -> None:
        self.host, self.m = host, m

    async def aw(self, b: int) -> None:
        await self.host.write_addr(b)
        self.m.addr_write(b)

    async def ar(self) -> None:
        got = await self.host.read_addr()
        want = self.m.addr_read()
        assert got == want, f"address read {got}, model {want:#04x}"

    async def dw(self, b: int) -> None:
        await self.host.write_data(b)
        self.m.data_write(b)

    async def dr(self) -> int:
        got = (await self.host.read_data(1))[0]
        want = self.m.data_read()
        assert got == want, f"data read {got}, model {want:#04x} (addr {self.m.addr:#06x})"
        return got

    # the driver's transactions (spec 17.2)
    async def hm2_write(self, addr: int, words: list[int]) -> None:
        await self.aw((addr | 0x8000) & 0xFF)
        await self.aw((addr | 0x8000) >> 8)
        for w in words:
            for k in range(4):
                await self.dw((w >> (8 * k)) & 0xFF)

    async def hm2_read(self, addr: int, n: int) -> list[int]:
        await self.aw((addr | 0x8000) & 0xFF)
        await self.aw((addr | 0x8000) >> 8)
        out = []
        for _ in range(n):
            b = [await self.dr() for _ in range(4)]
            out.append(b[0] | b[1] << 8 | b[2] << 16 | b[3] << 24)
        return out


@cocotb.test()
async def epp_driver_transactions(dut: Any) -> None:
    host, tgt, m = await setup(dut)
    t = Both(host, m)
    words = [0x11223344, 0xA5A5F00F, 0, 0xFFFFFFFF]
    await t.hm2_write(0x1000, words)
    assert tgt.ops == [("W", 0x1000 + 4 * i, w) for i, w in enumerate(words)]
    tgt.ops.clear()
    m.ops.clear()
    got = await t.hm2_read(0x1000, 4)
    assert got == words
    assert tgt.ops == [("R", 0x1000 + 4 * i, w) for i, w in enumerate(words)], tgt.ops
    got = await t.hm2_read(0x0400, 2)  # 15-bit hm2 address space
    assert got == [target_default(0x400), target_default(0x404)]
    assert not host.timed_out and not host.violations
    st = EppStats.of(host.cycles)
    lat = sorted(st.ack_latency_ns)
    dut._log.info(
        f"EPP: {st.cycles} cycles, ack latency {lat[0]:.0f}..{lat[-1]:.0f} ns, "
        f"{st.bus_ns / st.cycles:.0f} ns/cycle"
    )
    assert lat[-1] < 400.0  # at least as fast as the stock firmware's ~400 ns


@cocotb.test()
async def epp_random_cycles(dut: Any) -> None:
    """Any order of address/data cycles, with and without auto-increment,
    unaligned starts, address reads: bytes and hm2 accesses as the model."""
    host, tgt, m = await setup(dut)
    t = Both(host, m)
    rng = random.Random(17)
    for _ in range(160):
        op = rng.random()
        if op < 0.2:
            await t.aw(rng.choice([rng.getrandbits(8), 0x80, 0x00, 0x10, 0x04]))
        elif op < 0.3:
            await t.ar()
        elif op < 0.65:
            await t.dw(rng.getrandbits(8))
        else:
            await t.dr()
    assert tgt.ops == m.ops
    assert tgt.reconfigs == m.reconfigs
    assert not host.violations


@cocotb.test()
async def epp_reconfig(dut: Any) -> None:
    host, tgt, m = await setup(dut)
    t = Both(host, m)
    await t.aw(0x7F)
    await t.aw(0x7F)
    await t.dw(0x12)  # wrong data: no reconfig
    await ClockCycles(dut.clk, 4)
    assert tgt.reconfigs == 0
    await t.dw(0x5A)
    await ClockCycles(dut.clk, 4)
    assert tgt.reconfigs == 1
    await t.aw(0x7F)
    await t.aw(0xFF)  # auto-increment flag set: not the reconfigure address
    await t.dw(0x5A)
    await ClockCycles(dut.clk, 4)
    assert tgt.reconfigs == 1 == m.reconfigs


@cocotb.test()
async def epp_glitch_and_abort(dut: Any) -> None:
    """A strobe glitch shorter than the filter does nothing; a host that
    gives up before the acknowledge (EPP timeout) leaves the bridge ready."""
    host, tgt, m = await setup(dut)
    t = Both(host, m)
    await t.hm2_write(0x2000, [0x01020304])
    tgt.ops.clear()
    m.ops.clear()
    await t.aw(0x00)  # address 0x2000 | 0x8000 -> low byte 0x00
    for width in (10.0, 30.0):  # < 2 clocks: always filtered out
        await host.strobe_glitch(width, addr=False, value=0xEE)
        await host.strobe_glitch(width, addr=True, value=0xEE)
    assert not tgt.ops
    await t.aw(0xA0)  # still the high byte: the glitches were ignored
    assert await t.hm2_read(0x2000, 1) == [0x01020304]
    # abort: strobe held 120 ns: long enough to count, shorter than the acknowledge
    await host.abandoned_strobe(addr=True, write=True, value=0x55, hold_ns=120.0)
    m.addr_write(0x55)  # the bridge still completes that address cycle
    await host.abandoned_strobe(addr=False, write=False, hold_ns=120.0)
    m.data_read()
    host.violations.clear()
    await t.ar()  # low byte, then the high byte: the pointer is back on low
    await t.ar()
    got = await t.hm2_read(0x0010, 1)
    assert got == [target_default(0x10)]
    assert tgt.ops == m.ops


@cocotb.test()
async def epp_pc_pace(dut: Any) -> None:
    """The same driver transactions at a PC port's pace (~1 us per cycle)."""
    host, tgt, m = await setup(dut, EppTiming.pc_isa())
    t = Both(host, m)
    await t.hm2_write(0x0C00, [0x00FFFFFF])
    assert await t.hm2_read(0x0C00, 1) == [0x00FFFFFF]
    assert not host.timed_out and not host.violations


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_epp_bridge(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_epp_bridge",
        sources=[hdl("common", "sync_ff.v"), hdl("hostmot2", "hm2_epp_bridge.v")],
        test_module="test_hm2_epp",
        test_dir=Path(__file__).parent,
    )
