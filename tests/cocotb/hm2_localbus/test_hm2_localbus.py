# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_localbus with the shared local bus master (common/localbus.py) on the
host side and a Python register target on the internal bus: every host
access must become exactly one internal access (same address, data, one
bus_re per read) one clock later, read data must come back with lb_rvalid
two clocks after lb_rd, also back to back (bursts), and random traffic must
read back what a dictionary model holds."""

from __future__ import annotations

from typing import Any

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.localbus import LocalBus, LocalBusError
from common.runner import SIMULATORS, hdl, run


class Target:
    """Internal-bus target: the data for a bus_re seen before rising edge E
    is put on bus_rdata half a clock before E+1, i.e. it is there after E
    like a register's output (README rule: valid the cycle after bus_re)."""

    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.mem: dict[int, int] = {}
        self.ops: list[tuple[str, int, int]] = []
        dut.bus_rdata.value = 0

    async def run(self) -> None:
        while True:
            await FallingEdge(self.dut.clk)
            a = int(self.dut.bus_addr.value)
            if int(self.dut.bus_re.value):
                v = self.mem.get(a, a ^ 0xA5A50000)
                self.dut.bus_rdata.value = v
                self.ops.append(("R", a, v))
            if int(self.dut.bus_we.value):
                d = int(self.dut.bus_wdata.value)
                self.mem[a] = d
                self.ops.append(("W", a, d))


async def setup(dut: Any) -> tuple[LocalBus, Target]:
    cocotb.start_soon(Clock(dut.clk, 30, unit="ns").start())
    dut.rst.value = 1
    lb = LocalBus(dut, dut.clk)
    tgt = Target(dut)
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    cocotb.start_soon(tgt.run())
    return lb, tgt


@cocotb.test()
async def localbus_transfers(dut: Any) -> None:
    lb, tgt = await setup(dut)
    await lb.write(0x1000, 0x12345678)
    assert tgt.ops == [("W", 0x1000, 0x12345678)]
    assert await lb.read(0x1000) == 0x12345678
    assert tgt.ops[-1] == ("R", 0x1000, 0x12345678) and len(tgt.ops) == 2
    # bursts: one access per clock, in order, each read exactly once
    tgt.ops.clear()
    data = [random.getrandbits(32) for _ in range(16)]
    await lb.write_burst(0x2000, data)
    assert tgt.ops == [("W", 0x2000 + 4 * i, d) for i, d in enumerate(data)]
    tgt.ops.clear()
    assert await lb.read_burst(0x2000, 16) == data
    assert tgt.ops == [("R", 0x2000 + 4 * i, d) for i, d in enumerate(data)]
    assert await lb.read_burst(0x0400, 3) == [a ^ 0xA5A50000 for a in (0x400, 0x404, 0x408)]
    # the data stays on lb_rdata after the read
    await ClockCycles(dut.clk, 5)
    assert int(dut.lb_rdata.value) == 0x408 ^ 0xA5A50000
    # bad addresses are refused by the master, not sent
    n = len(tgt.ops)
    for bad in (0x1002, 0x10000, -4):
        with pytest.raises(ValueError):
            await lb.read(bad)
    assert len(tgt.ops) == n


@cocotb.test()
async def localbus_random(dut: Any) -> None:
    lb, tgt = await setup(dut)
    rng = random.Random(3)
    model: dict[int, int] = {}
    for _ in range(200):
        a = rng.randrange(0, 64) * 4
        if rng.random() < 0.5:
            d = rng.getrandbits(32)
            await lb.write(a, d)
            model[a] = d
        else:
            assert await lb.read(a) == model.get(a, a ^ 0xA5A50000)
    assert sum(1 for o in tgt.ops if o[0] == "R") == lb.reads


@cocotb.test()
async def localbus_checks_latency(dut: Any) -> None:
    """The master's timing check itself: expecting a 3-clock latency from a
    2-clock target must fail (so the check in the top tests can fail)."""
    lb, _ = await setup(dut)
    lb.latency = 3
    with pytest.raises(LocalBusError):
        await lb.read(0x100)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_localbus(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_localbus",
        sources=[hdl("hostmot2", "hm2_localbus.v")],
        test_module="test_hm2_localbus",
        test_dir=Path(__file__).parent,
    )
