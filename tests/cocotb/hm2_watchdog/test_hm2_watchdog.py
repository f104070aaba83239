# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_watchdog against a clock-by-clock Python model of spec/hostmot2.md
section 9.2: every bus access is logged with the clock that took it, the bite
pin is sampled every clock, and the model replays the same accesses and must
produce the same bites on the same clocks and the same read data.  Direct
checks of the spec formulas (the counter passes below zero (V+1) clocks after
a Timer write, pet cookie 0x5A, bit 31 = disabled, sticky status) come on
top, and the facts seen on Mesa's firmware (issue 13): Status reads 1 right
after power-up (the power-up Timer value 0 bites at once), and the bite pulse
that releases the pins comes one clock after the underflow is registered."""

from __future__ import annotations

from typing import Any

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge
from cocotb.utils import get_sim_time

from common.hm2bus import Hm2Bus
from common.runner import SIMULATORS, hdl, run

PERIOD = 20
TIMER, STATUS, PET = 0x0C00, 0x0D00, 0x0E00


class WatchdogModel:
    def __init__(self) -> None:
        self.timer = 0
        self.reload = 0
        self.status = 0
        self.under = False  # underflow registered on the previous clock

    def step(self, writes: list[tuple[int, int]], read: int | None) -> tuple[bool, int | None]:
        """One clock: apply the writes taken on it; return (bite, read data)."""
        rd = None
        if read is not None:
            rd = {TIMER: self.timer, STATUS: self.status}.get(read, 0)
        wr_timer = [d for a, d in writes if a == TIMER]
        wr_pet = any(a == PET and d >> 24 == 0x5A for a, d in writes)
        counting = not self.timer >> 31
        under = not wr_timer and not wr_pet and counting and self.timer == 0
        bite, self.under = self.under, under
        if wr_timer:
            self.timer = self.reload = wr_timer[-1]
        elif wr_pet:
            self.timer = self.reload
        elif counting:
            self.timer = (self.timer - 1) & 0xFFFFFFFF
        if under:
            self.status = 1
        else:
            for a, d in writes:
                if a == STATUS:
                    self.status = d & 1
        return bite, rd


class Harness:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.bus = Hm2Bus(dut)
        self.writes: dict[int, list[tuple[int, int]]] = {}
        self.reads: dict[int, tuple[int, int]] = {}
        self.bites: list[int] = []
        self.t0 = 0.0

    def cyc(self, t: float) -> int:
        return int(round((t - self.t0) / PERIOD))

    async def start(self) -> None:
        cocotb.start_soon(Clock(self.dut.clk, PERIOD, unit="ns").start())
        self.dut.rst.value = 1
        await ClockCycles(self.dut.clk, 3)
        await FallingEdge(self.dut.clk)
        self.dut.rst.value = 0
        await RisingEdge(self.dut.clk)
        self.t0 = get_sim_time("ns")
        cocotb.start_soon(self._watch())

    async def _watch(self) -> None:
        while True:
            await FallingEdge(self.dut.clk)
            if int(self.dut.bite.value):
                # registered on the rising edge just before this falling edge
                self.bites.append(self.cyc(get_sim_time("ns") - PERIOD / 2))

    async def write(self, addr: int, data: int) -> int:
        c = self.cyc(await self.bus.write(addr, data))
        self.writes.setdefault(c, []).append((addr, data))
        return c

    async def read(self, addr: int) -> int:
        v, t = await self.bus.read_timed(addr)
        self.reads[self.cyc(t)] = (addr, v)
        return v

    def replay(self) -> None:
        m = WatchdogModel()
        last = max([*self.writes, *self.reads, *self.bites, 0]) + 1
        want = []
        for c in range(last + 1):
            rd_addr = self.reads[c][0] if c in self.reads else None
            bite, rd = m.step(self.writes.get(c, []), rd_addr)
            if bite:
                want.append(c)
            if c in self.reads:
                assert (
                    rd == self.reads[c][1]
                ), f"clock {c}: read {rd_addr:#06x} = {self.reads[c][1]:#x}, model {rd:#x}"
        assert self.bites == want, f"bites at {self.bites}, model {want}"


@cocotb.test()
async def watchdog_spec(dut: Any) -> None:
    h = Harness(dut)
    await h.start()
    # power-up: Timer 0 passes below zero on the first clock, so the dog has
    # bitten once (pins released on clock 1) and Status reads 1 until cleared
    assert await h.read(TIMER) == 0xFFFFFFFF
    assert await h.read(STATUS) == 1
    await ClockCycles(dut.clk, 50)
    assert h.bites == [1]
    # the driver's load sequence: Timer = disabled, then clear the status
    await h.write(TIMER, 0x80000000)
    await h.write(STATUS, 0)
    assert await h.read(STATUS) == 0
    # Timer = V passes below zero (V+1) clocks after the write; the bite
    # pulse follows one clock later, once
    for v in (0, 1, 5, 40):
        await h.write(STATUS, 0)
        c = await h.write(TIMER, v)
        await ClockCycles(dut.clk, v + 10)
        assert h.bites and h.bites[-1] == c + v + 2, (v, c, h.bites)
        assert await h.read(STATUS) == 1
        assert await h.read(TIMER) == 0xFFFFFFFF  # passed below zero, now stopped
        n = len(h.bites)
        await ClockCycles(dut.clk, 30)
        assert len(h.bites) == n, "bit twice"
    # status: a write replaces bit 0, other bits read 0
    await h.write(STATUS, 0xFFFFFFFE)
    assert await h.read(STATUS) == 0
    await h.write(STATUS, 0xFFFFFFFF)
    assert await h.read(STATUS) == 1
    await h.write(STATUS, 0)
    # petting with the cookie keeps it from biting; other values do not pet
    n = len(h.bites)
    await h.write(TIMER, 60)
    for _ in range(8):
        await ClockCycles(dut.clk, 35)
        await h.write(PET, 0x5A000000 | random.getrandbits(24))
    assert len(h.bites) == n
    c = await h.write(PET, 0x5B000000)
    await ClockCycles(dut.clk, 80)
    assert len(h.bites) == n + 1
    # bit 31 set: disabled, the value is kept, never bites
    await h.write(TIMER, 0x80000005)
    await ClockCycles(dut.clk, 40)
    assert await h.read(TIMER) == 0x80000005
    assert len(h.bites) == n + 1
    # write-only cookie and unaddressed words read 0
    for a in (PET, 0x0C04, 0x0D04, 0x0F00, 0x0B00, 0x1000):
        await h.bus.read_expect_zero(a)
    assert await h.bus.check_hold() == 0
    # random traffic, all compared with the model
    rng = random.Random(4)
    for _ in range(150):
        op = rng.random()
        if op < 0.3:
            await h.write(TIMER, rng.choice([rng.randrange(0, 40), rng.getrandbits(32)]))
        elif op < 0.5:
            await h.write(PET, rng.choice([0x5A000000, rng.getrandbits(32)]))
        elif op < 0.6:
            await h.write(STATUS, rng.getrandbits(32))
        elif op < 0.9:
            await h.read(rng.choice([TIMER, STATUS, PET]))
        else:
            await ClockCycles(dut.clk, rng.randrange(1, 30))
    await ClockCycles(dut.clk, 5)
    h.replay()


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_watchdog(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_watchdog",
        sources=[hdl("hostmot2", "hm2_watchdog.v")],
        test_module="test_hm2_watchdog",
        test_dir=Path(__file__).parent,
    )
