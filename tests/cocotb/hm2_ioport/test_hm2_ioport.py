# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_ioport_bank at pin level against a Python model of spec/hostmot2.md
section 9.1.  The test plays the board: every pin is pulled up, an external
driver may drive it, and the level seen on the pin (io_in) is computed from
the firmware's io_out/io_oe like a real wire.  After every change the model's
idea of each pin (driven 0 / driven 1 / floating) must match the firmware's,
Data reads must return the pin levels and DDR must read back.  Covers open
drain, output invert, alternate source, the watchdog bite (DDR and
OpenDrain cleared, the rest kept) and register bits above the port width."""

from __future__ import annotations

from typing import Any

import random
from dataclasses import dataclass, field
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, ReadWrite

from common.hm2bus import Hm2Bus
from common.runner import SIMULATORS, hdl, run

PERIOD = 30
NPORTS, PW = 2, 17  # a 5i25-like bank: width not a power of two
IOW = NPORTS * PW
MASK = (1 << PW) - 1
DATA, DDR, ALT, OD, INV = range(5)


def addr(reg: int, port: int) -> int:
    return 0x1000 + reg * 0x100 + port * 4


@dataclass
class IoportModel:
    regs: list[list[int]] = field(default_factory=lambda: [[0] * NPORTS for _ in range(5)])

    def write(self, reg: int, port: int, value: int) -> None:
        self.regs[reg][port] = value & MASK

    def bite(self) -> None:
        for p in range(NPORTS):
            self.regs[DDR][p] = 0
            self.regs[OD][p] = 0

    def _bits(self, reg: int) -> int:
        return sum(self.regs[reg][p] << (p * PW) for p in range(NPORTS))

    def drive(self, alt_out: int) -> tuple[int, int]:
        """(oe, out) over all pins: the spec's per-bit formula."""
        alt, data, inv = self._bits(ALT), self._bits(DATA), self._bits(INV)
        od, ddr = self._bits(OD), self._bits(DDR)
        full = (1 << IOW) - 1
        d = ((alt & alt_out) | (~alt & data)) ^ inv
        oe = (od & ~d | ~od & ddr) & full
        out = d & ~od & full
        return oe, out


class Board:
    """Pull-ups plus an optional external driver per pin."""

    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.ext_en = 0
        self.ext_val = 0
        self.contention = 0

    def level(self) -> int:
        oe = int(self.dut.io_oe.value)
        out = int(self.dut.io_out.value)
        full = (1 << IOW) - 1
        self.contention |= oe & self.ext_en & (out ^ self.ext_val)
        return ((oe & out) | (~oe & self.ext_en & self.ext_val) | (~oe & ~self.ext_en)) & full

    async def run(self) -> None:
        while True:
            await ReadWrite()
            self.dut.io_in.value = self.level()
            await FallingEdge(self.dut.clk)


async def setup(dut: Any) -> tuple[Hm2Bus, IoportModel, Board]:
    cocotb.start_soon(Clock(dut.clk, PERIOD, unit="ns").start())
    dut.rst.value = 1
    dut.bite.value = 0
    dut.alt_out.value = 0
    dut.io_in.value = (1 << IOW) - 1
    bus = Hm2Bus(dut)
    board = Board(dut)
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    cocotb.start_soon(board.run())
    return bus, IoportModel(), board


async def check(dut: Any, bus: Hm2Bus, m: IoportModel, board: Board, alt_out: int) -> None:
    dut.alt_out.value = alt_out
    await ClockCycles(dut.clk, 4)  # through the 2-FF synchronizer
    await FallingEdge(dut.clk)
    oe, out = m.drive(alt_out)
    assert int(dut.io_oe.value) == oe, f"io_oe {int(dut.io_oe.value):#x}, model {oe:#x}"
    assert int(dut.io_out.value) & oe == out & oe, "driven levels differ from the model"
    lvl = board.level()
    for p in range(NPORTS):
        assert await bus.read(addr(DATA, p)) == (lvl >> (p * PW)) & MASK, f"Data read port {p}"
        assert await bus.read(addr(DDR, p)) == m.regs[DDR][p], f"DDR read port {p}"
        for reg in (ALT, OD, INV):  # write-only
            await bus.read_expect_zero(addr(reg, p))


@cocotb.test()
async def ioport_semantics(dut: Any) -> None:
    bus, m, board = await setup(dut)
    # power-up: everything input, pins read the pull-ups
    await check(dut, bus, m, board, 0)
    assert await bus.read(addr(DATA, 0)) == MASK
    # GPIO outputs, then inputs driven from outside
    for reg, port, val in (
        (DDR, 0, 0x0F0F),
        (DATA, 0, 0x1F00F),
        (DDR, 1, 0x1FFFF),
        (DATA, 1, 0x12345),
    ):
        await bus.write(addr(reg, port), val)
        m.write(reg, port, val)
        await check(dut, bus, m, board, 0)
    board.ext_en, board.ext_val = 0xF0F0, 0x5050  # external drive on port-0 inputs
    await check(dut, bus, m, board, 0)
    # invert applies to outputs only: an input still reads the true level
    await bus.write(addr(INV, 0), 0x1FFFF)
    m.write(INV, 0, 0x1FFFF)
    await check(dut, bus, m, board, 0)
    assert (await bus.read(addr(DATA, 0))) & 0xF0F0 == 0x5050
    # open drain: 0 drives low, 1 floats (reads the pull-up), DDR ignored
    board.ext_en = 0
    await bus.write(addr(INV, 0), 0)
    m.write(INV, 0, 0)
    await bus.write(addr(OD, 1), 0x000FF)
    m.write(OD, 1, 0x000FF)
    await bus.write(addr(DDR, 1), 0)
    m.write(DDR, 1, 0)
    await check(dut, bus, m, board, 0)
    lvl = await bus.read(addr(DATA, 1))
    assert lvl & 0xFF == (0x12345 & 0xFF), "open drain: pin = data (0 low, 1 pulled up)"
    # alternate source: module outputs reach the pins, with invert/open drain
    await bus.write(addr(ALT, 0), 0x000FF)
    m.write(ALT, 0, 0x000FF)
    await bus.write(addr(DDR, 0), 0x1FFFF)
    m.write(DDR, 0, 0x1FFFF)
    for alt in (0, (1 << IOW) - 1, 0x0A5A5, 0x3_0000_0055):
        await check(dut, bus, m, board, alt)
    # bits above the port width: ignored on write, 0 on read
    await bus.write(addr(DDR, 0), 0xFFFFFFFF)
    m.write(DDR, 0, 0xFFFFFFFF)
    await check(dut, bus, m, board, 0)
    assert await bus.read(addr(DDR, 0)) == MASK
    # instances that do not exist and other pages read 0, writes there do nothing
    await bus.write(addr(DDR, NPORTS), 0x1234)
    for a in (addr(DDR, NPORTS), addr(DATA, 63), 0x1500, 0x0F00):
        await bus.read_expect_zero(a)
    assert board.contention == 0


@cocotb.test()
async def ioport_bite_and_restore(dut: Any) -> None:
    bus, m, board = await setup(dut)
    cfg = {
        (DATA, 0): 0x0AAAA,
        (INV, 0): 0x00F00,
        (ALT, 0): 0x000F0,
        (DDR, 0): 0x0FFF0,
        (OD, 0): 0x0000F,
        (DATA, 1): 0x1F0F0,
        (DDR, 1): 0x1FFFF,
        (OD, 1): 0x10000,
    }
    for (reg, port), val in cfg.items():
        await bus.write(addr(reg, port), val)
        m.write(reg, port, val)
    alt = 0x0005A
    await check(dut, bus, m, board, alt)
    # bite: all pins become inputs and read the pull-ups, modules keep going
    await FallingEdge(dut.clk)
    dut.bite.value = 1
    await FallingEdge(dut.clk)
    dut.bite.value = 0
    m.bite()
    await check(dut, bus, m, board, alt)
    assert int(dut.io_oe.value) == 0
    assert await bus.read(addr(DATA, 0)) == MASK and await bus.read(addr(DATA, 1)) == MASK
    # Data/AltSource/Invert were kept: rewriting DDR and OpenDrain (what the
    # driver does on recovery) restores the configured pin state exactly.
    for reg in (DDR, OD):
        for p in range(NPORTS):
            v = cfg.get((reg, p), 0)
            await bus.write(addr(reg, p), v)
            m.write(reg, p, v)
    await check(dut, bus, m, board, alt)
    m2 = IoportModel()
    for (reg, port), val in cfg.items():
        m2.write(reg, port, val)
    assert m.drive(alt) == m2.drive(alt)
    # a bite in the same clock as a DDR write wins
    await FallingEdge(dut.clk)
    dut.bus_addr.value = addr(DDR, 1)
    dut.bus_wdata.value = 0x1FFFF
    dut.bus_we.value = 1
    dut.bite.value = 1
    await FallingEdge(dut.clk)
    dut.bus_we.value = 0
    dut.bite.value = 0
    m.bite()
    await check(dut, bus, m, board, alt)


@cocotb.test()
async def ioport_random(dut: Any) -> None:
    bus, m, board = await setup(dut)
    rng = random.Random(7)
    alt = 0
    for i in range(60):
        reg, port = rng.randrange(5), rng.randrange(NPORTS)
        val = rng.getrandbits(32)
        await bus.write(addr(reg, port), val)
        m.write(reg, port, val)
        board.ext_en = rng.getrandbits(IOW) & ~int(m.drive(alt)[0])  # no contention
        board.ext_val = rng.getrandbits(IOW)
        if rng.random() < 0.1:
            await FallingEdge(dut.clk)
            dut.bite.value = 1
            await FallingEdge(dut.clk)
            dut.bite.value = 0
            m.bite()
        alt = rng.getrandbits(IOW)
        board.ext_en &= ~m.drive(alt)[0]
        await check(dut, bus, m, board, alt)
    assert board.contention == 0


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_ioport(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_ioport_bank",
        sources=[hdl("common", "sync_ff.v"), hdl("hostmot2", "hm2_ioport_bank.v")],
        parameters={"NPORTS": NPORTS, "PORTWIDTH": PW},
        test_module="test_hm2_ioport",
        test_dir=Path(__file__).parent,
    )
