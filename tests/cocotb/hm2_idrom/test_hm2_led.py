# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_led against spec/hostmot2.md section 9.3: LED i shows bit
32-NUM_LEDS+i of the last word written to 0x0200 (bit 31 = highest LED);
other addresses do not touch it."""

from __future__ import annotations

from typing import Any

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.runner import SIMULATORS, hdl, run

RNG = random.Random(5)


@cocotb.test()
async def led_bits(dut: Any) -> None:
    cocotb.start_soon(Clock(dut.clk, 20, unit="ns").start())
    dut.rst.value = 1
    dut.bus_addr.value = 0
    dut.bus_wdata.value = 0
    dut.bus_we.value = 0
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    n = len(dut.leds)
    assert int(dut.leds.value) == 0

    async def write(a: int, d: int) -> None:
        await FallingEdge(dut.clk)
        dut.bus_addr.value = a
        dut.bus_wdata.value = d
        dut.bus_we.value = 1
        await FallingEdge(dut.clk)
        dut.bus_we.value = 0

    for d in (0x80000000, 1 << (32 - n), 0xFFFFFFFF >> n, 0xA5000000, RNG.getrandbits(32)):
        await write(0x200, d)
        assert int(dut.leds.value) == d >> (32 - n), f"wrote {d:#x}"
    cur = int(dut.leds.value)
    await write(0x204, 0xFFFFFFFF)  # instance 1 does not exist
    await write(0x300, 0xFFFFFFFF)
    assert int(dut.leds.value) == cur


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_led(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_led",
        sources=[hdl("hostmot2", "hm2_led.v")],
        parameters={"NUM_LEDS": 6},
        test_module="test_hm2_led",
        test_dir=Path(__file__).parent,
    )
