# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_stepgen tick by tick against StepgenModel, and the step waveform
checked against the spec on its own: STEP high exactly steptime+1 ticks, low
at least 1 tick, DIR changes only with STEP low, at least dirtime+1 ticks
after the last fall and before the next rise, net steps equal to the
position's whole-step movement, top rate 1 step per 2 ticks (312.5 kHz)
at |velocity| = 1024, timing fields at 0 and at their maximum."""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run
from pluto_common.models import StepgenModel

TICK_CLOCKS = 2  # module level: a tick every 2 clocks keeps the tests short


@dataclass
class Wave:
    step: list[int] = field(default_factory=list)
    dir: list[int] = field(default_factory=list)
    pos: list[int] = field(default_factory=list)


class Bench:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.model = StepgenModel()
        self.wave = Wave()
        self.steptime = self.dirtime = self.tap = 0

    async def start(self) -> None:
        d = self.dut
        Clock(d.clk, 25, unit="ns").start()
        d.tick.value = 0
        d.vel.value = 0
        d.steptime.value = 0
        d.dirtime.value = 0
        d.tap.value = 0
        d.rst.value = 1
        await ClockCycles(d.clk, 2)
        await FallingEdge(d.clk)
        d.rst.value = 0

    def timing(self, steptime: int, dirtime: int, tap: int = 0) -> None:
        self.steptime, self.dirtime, self.tap = steptime, dirtime, tap
        self.dut.steptime.value = steptime
        self.dut.dirtime.value = dirtime
        self.dut.tap.value = tap

    async def run(self, vel: int, ticks: int) -> None:
        d = self.dut
        d.vel.value = vel & 0xFFF
        for _ in range(ticks):
            d.tick.value = 1
            await RisingEdge(d.clk)
            self.model.tick(vel, self.steptime, self.dirtime, self.tap)
            await FallingEdge(d.clk)
            d.tick.value = 0
            got = (int(d.pos.value), int(d.step_q.value), int(d.dir_q.value))
            m = self.model
            want = (m.pos, m.step, m.dir)
            assert got == want, f"vel {vel}: dut {got} model {want}"
            self.wave.step.append(got[1])
            self.wave.dir.append(got[2])
            self.wave.pos.append(got[0])
            await ClockCycles(d.clk, TICK_CLOCKS - 1, rising=False)


def check_waveform(w: Wave, steptime: int, dirtime: int) -> tuple[int, int]:
    """Spec checks on a per-tick STEP/DIR record; returns (net steps, rises)."""
    net = rises = 0
    high = low = 0
    since_fall = since_dir = 10**9
    for i in range(1, len(w.step)):
        s0, s1 = w.step[i - 1], w.step[i]
        if w.dir[i] != w.dir[i - 1]:
            assert s0 == 0 and s1 == 0, f"tick {i}: DIR changed with STEP high"
            assert since_fall >= dirtime + 1, f"tick {i}: dir hold {since_fall} < {dirtime + 1}"
            since_dir = 0
        if s1 and not s0:
            assert low >= 1, f"tick {i}: no low time between steps"
            assert since_dir >= dirtime + 1, f"tick {i}: dir setup {since_dir} < {dirtime + 1}"
            rises += 1
            net += -1 if w.dir[i] else 1
            high = 0
        if not s1 and s0:
            assert high == steptime + 1, f"tick {i}: step high {high} ticks, want {steptime + 1}"
            low = 0
            since_fall = 0
        if s1:
            high += 1
        else:
            low += 1
        since_fall += 1
        since_dir += 1
    return net, rises


def whole_steps(pos: int) -> int:
    """Signed position (21-bit wrapping, 11 fractional bits) in whole steps."""
    if pos >= 1 << 20:
        pos -= 1 << 21
    return pos >> 11


@cocotb.test()
async def top_rate_is_one_step_per_two_ticks(dut: Any) -> None:
    b = Bench(dut)
    await b.start()
    b.timing(0, 0)
    await b.run(1024, 400)
    net, rises = check_waveform(b.wave, 0, 0)
    # 1024/2048 step per tick: 200 steps in 400 ticks (the first at tick 2).
    assert 199 <= rises <= 200, rises
    assert net == rises
    # Every second tick, i.e. 625 kHz / 2 = 312.5 kHz.
    ups = [i for i in range(1, len(b.wave.step)) if b.wave.step[i] and not b.wave.step[i - 1]]
    assert {ups[i + 1] - ups[i] for i in range(len(ups) - 1)} == {2}


@cocotb.test()
async def reversal_timing_min_and_max(dut: Any) -> None:
    for steptime, dirtime in ((0, 0), (15, 15), (3, 7), (15, 0), (0, 15)):
        b = Bench(dut)
        await b.start()
        b.timing(steptime, dirtime)
        # Within the rate the step timing allows (1 step per steptime+2 ticks);
        # faster commands lose steps by design (the driver limits the rate).
        cap = 2048 // (steptime + 2)
        for vel in (300, -300, 100, -1, 0, 700, -1024, 5):
            await b.run(max(-cap, min(cap, vel)), 150)
        await b.run(0, 80)
        net, rises = check_waveform(b.wave, steptime, dirtime)
        assert rises > 10
        assert net == whole_steps(b.wave.pos[-1]), (steptime, dirtime, net, b.wave.pos[-1])


@cocotb.test()
async def taps_divide_the_step_rate(dut: Any) -> None:
    for tap in range(4):
        b = Bench(dut)
        await b.start()
        b.timing(0, 0, tap)
        await b.run(-1024, 256)
        _, rises = check_waveform(b.wave, 0, 0)
        assert abs(rises - 128 / (1 << tap)) <= 1, (tap, rises)


@cocotb.test()
async def random_against_model(dut: Any) -> None:
    b = Bench(dut)
    await b.start()
    rng = random.Random(9)
    for _ in range(40):
        b.timing(rng.randrange(16), rng.randrange(16), 0)
        await b.run(rng.randrange(-2048, 2048), rng.randrange(5, 60))


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_stepgen(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_stepgen",
        sources=[hdl("pluto", "pluto_stepgen.v")],
        test_module="test_pluto_stepgen",
        test_dir=Path(__file__).parent,
    )
