# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_pwm_counter: counts 0..2046 (period 2047 clocks = 51.175 us at
40 MHz), wrap high exactly at 2046, restarts after reset."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run


@cocotb.test()
async def counts_one_period(dut: Any) -> None:
    Clock(dut.clk, 25, unit="ns").start()
    dut.rst.value = 1
    await RisingEdge(dut.clk)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    seen, wraps = [], []
    for i in range(2 * 2047 + 5):
        seen.append(int(dut.cnt.value))
        if int(dut.wrap.value):
            wraps.append(i)
        await FallingEdge(dut.clk)
    assert seen[:2047] == list(range(2047))
    assert seen[2047:4094] == list(range(2047))
    assert wraps == [2046, 4093]
    dut.rst.value = 1
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    assert int(dut.cnt.value) == 0


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_pwm_counter(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_pwm_counter",
        sources=[hdl("pluto", "pluto_pwm_counter.v")],
        test_module="test_pluto_pwm_counter",
        test_dir=Path(__file__).parent,
    )
