# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_quad (one 4x quadrature counter with index latch and index
filter) clock by clock against QuadModel, plus spec facts checked on their
own: x4 counting and direction, simultaneous A/B changes ignored, index
pulses shorter than 7 clocks (175 ns) ignored, index latch and read-once
"index seen", 14-bit wrap."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run
from pluto_common.models import QuadModel

GRAY = [(0, 0), (1, 0), (1, 1), (0, 1)]  # A leading B: counting up


class Bench:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.model = QuadModel()
        self.a = self.b = self.z = 0

    async def start(self, a: int = 0, b: int = 0) -> None:
        Clock(self.dut.clk, 25, unit="ns").start()
        self.a, self.b = a, b
        self.drive(a, b, 0, 0)
        self.dut.rst.value = 1
        await RisingEdge(self.dut.clk)
        await RisingEdge(self.dut.clk)
        self.model.reset(a, b)
        await FallingEdge(self.dut.clk)
        self.dut.rst.value = 0

    def drive(self, a: int, b: int, z: int, clr: int) -> None:
        self.dut.a.value, self.dut.b.value, self.dut.z.value = a, b, z
        self.dut.clr_seen.value = clr

    async def clock(self, a: int, b: int, z: int = 0, clr: int = 0) -> None:
        self.a, self.b, self.z = a, b, z
        self.drive(a, b, z, clr)
        await RisingEdge(self.dut.clk)
        self.model.clock(a, b, z, clr)
        await FallingEdge(self.dut.clk)
        got = (
            int(self.dut.count.value),
            int(self.dut.index_count.value),
            int(self.dut.index_seen.value),
        )
        m = self.model
        assert got == (m.count, m.latch, m.seen), f"dut {got} model {(m.count, m.latch, m.seen)}"


@cocotb.test()
async def counts_x4_both_directions(dut: Any) -> None:
    bench = Bench(dut)
    await bench.start()
    rng = random.Random(2)
    phase, expect = 0, 0
    for _ in range(600):
        d = rng.choice((1, 1, 1, -1))
        phase = (phase + d) % 4
        expect += d
        a, b = GRAY[phase]
        for _ in range(rng.randrange(1, 4)):
            await bench.clock(a, b)
    assert int(dut.count.value) == expect % (1 << 14)


@cocotb.test()
async def simultaneous_change_is_ignored(dut: Any) -> None:
    bench = Bench(dut)
    await bench.start()
    phase = 0
    for _ in range(3):
        for d in (1, 1, 1):
            phase = (phase + d) % 4
            await bench.clock(*GRAY[phase])
    before = int(dut.count.value)
    for _ in range(20):
        phase = (phase + 2) % 4  # both lines flip in the same clock
        await bench.clock(*GRAY[phase])
        await bench.clock(*GRAY[phase])
    assert int(dut.count.value) == before


@cocotb.test()
async def wraps_at_14_bits(dut: Any) -> None:
    bench = Bench(dut)
    await bench.start()
    phase = 0
    for _ in range(5):
        phase = (phase - 1) % 4
        await bench.clock(*GRAY[phase])
    assert int(dut.count.value) == (1 << 14) - 5


@cocotb.test()
async def index_filter_and_latch(dut: Any) -> None:
    """Isolated index pulses of 1..12 clocks: latched iff >= 7 clocks."""
    bench = Bench(dut)
    await bench.start()
    phase = 0
    for width in range(1, 13):
        for _ in range(width + 3):  # move the count so each latch differs
            phase = (phase + 1) % 4
            await bench.clock(*GRAY[phase])
        count_at_pulse = int(dut.count.value)
        for _ in range(width):
            await bench.clock(*GRAY[phase], z=1)
        for _ in range(12):
            await bench.clock(*GRAY[phase], z=0)
        seen = int(dut.index_seen.value)
        assert seen == int(width >= 7), f"pulse of {width} clocks: seen={seen}"
        if seen:
            assert int(dut.index_count.value) == count_at_pulse
        await bench.clock(*GRAY[phase], clr=1)  # the host reads the register
        assert int(dut.index_seen.value) == 0


@cocotb.test()
async def noisy_index_and_clear_race(dut: Any) -> None:
    """Random noise on Z and A/B, random clears, clear in the same clock as
    an index (the index wins): DUT and model agree every clock."""
    bench = Bench(dut)
    await bench.start()
    rng = random.Random(7)
    phase, z = 0, 0
    for i in range(4000):
        if rng.random() < 0.3:
            phase = (phase + rng.choice((1, -1, 2))) % 4
        if rng.random() < 0.15:
            z ^= 1
        await bench.clock(*GRAY[phase], z=z, clr=int(rng.random() < 0.05))
    # Forced race: a clean index with clr asserted in every clock.
    for _ in range(10):
        await bench.clock(*GRAY[phase], z=0, clr=1)
    for _ in range(12):
        await bench.clock(*GRAY[phase], z=1, clr=1)
    assert bench.model.latch == int(dut.index_count.value)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_quad(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_quad",
        sources=[hdl("pluto", "pluto_quad.v")],
        test_module="test_pluto_quad",
        test_dir=Path(__file__).parent,
    )
