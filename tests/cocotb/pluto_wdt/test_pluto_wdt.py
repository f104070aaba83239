# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_wdt against WdtModel and the spec (section 3.3): off after reset
whatever the ticks, trips exactly 127 ticks after the last pet, stays
tripped, recovers on the next pet, a pet beats a simultaneous tick."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run
from pluto_common.models import WdtModel


async def start(dut: Any) -> WdtModel:
    Clock(dut.clk, 25, unit="ns").start()
    dut.tick.value = 0
    dut.pet.value = 0
    dut.rst.value = 1
    await RisingEdge(dut.clk)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    return WdtModel()


async def clock(dut: Any, m: WdtModel, tick: int, pet: int) -> int:
    dut.tick.value, dut.pet.value = tick, pet
    await RisingEdge(dut.clk)
    m.clock(tick, pet)
    await FallingEdge(dut.clk)
    trip = int(dut.trip.value)
    assert trip == m.trip, f"trip {trip} model {m.trip}"
    return trip


@cocotb.test()
async def never_trips_before_first_pet(dut: Any) -> None:
    m = await start(dut)
    for _ in range(400):
        assert await clock(dut, m, 1, 0) == 0


@cocotb.test()
async def trips_after_127_ticks_and_recovers(dut: Any) -> None:
    m = await start(dut)
    await clock(dut, m, 0, 1)
    for n in range(1, 127):
        assert await clock(dut, m, 1, 0) == 0, f"tripped after {n} ticks"
        await clock(dut, m, 0, 0)
    assert await clock(dut, m, 1, 0) == 1  # tick 127
    for _ in range(50):
        assert await clock(dut, m, 1, 0) == 1  # stays tripped (saturates)
    assert await clock(dut, m, 1, 1) == 0  # pet wins over the tick, bite cleared
    assert await clock(dut, m, 1, 0) == 0


@cocotb.test()
async def random_against_model(dut: Any) -> None:
    m = await start(dut)
    rng = random.Random(3)
    for _ in range(3000):
        await clock(dut, m, int(rng.random() < 0.7), int(rng.random() < 0.004))


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_wdt(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_wdt",
        sources=[hdl("pluto", "pluto_wdt.v")],
        test_module="test_pluto_wdt",
        test_dir=Path(__file__).parent,
    )
