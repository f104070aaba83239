# SPDX-License-Identifier: GPL-2.0-or-later
"""sync_ff against a Python shift-register model: every output bit equals the
input bit STAGES clocks earlier, and reset forces RESET_VALUE."""

from __future__ import annotations

from typing import Any

import random
from collections import deque
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run


class SyncModel:
    """Reference: a STAGES-deep delay line per bit."""

    def __init__(self, stages: int, reset_value: int) -> None:
        self.stages = stages
        self.reset_value = reset_value
        self.line: deque[int] = deque([reset_value] * stages, maxlen=stages)

    def reset(self) -> None:
        self.line = deque([self.reset_value] * self.stages, maxlen=self.stages)

    def clock(self, d: int) -> None:
        self.line.appendleft(d)

    @property
    def q(self) -> int:
        return self.line[-1]


@cocotb.test()
async def delay_matches_model(dut: Any) -> None:
    width = int(dut.WIDTH.value)
    stages = int(dut.STAGES.value)
    reset_value = int(dut.RESET_VALUE.value)
    model = SyncModel(stages, reset_value)
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.rst.value = 1
    dut.d.value = 0
    for _ in range(stages + 1):
        await RisingEdge(dut.clk)
    await FallingEdge(dut.clk)
    assert int(dut.q.value) == reset_value, "reset value not held"
    dut.rst.value = 0
    rng = random.Random(1)
    for _ in range(200):
        d = rng.getrandbits(width)
        dut.d.value = d
        await RisingEdge(dut.clk)
        model.clock(d)
        await FallingEdge(dut.clk)
        assert int(dut.q.value) == model.q, f"q={int(dut.q.value):#x} model={model.q:#x}"
    # Reset in the middle of traffic clears the whole chain at once.
    dut.rst.value = 1
    await RisingEdge(dut.clk)
    model.reset()
    await FallingEdge(dut.clk)
    assert int(dut.q.value) == reset_value


@pytest.mark.parametrize("sim", SIMULATORS)
@pytest.mark.parametrize("width,stages,reset_value", [(1, 2, 0), (5, 3, 0b10101)])
def test_sync_ff(sim: str, width: int, stages: int, reset_value: int) -> None:
    run(
        sim=sim,
        toplevel="sync_ff",
        sources=[hdl("common", "sync_ff.v")],
        test_module="test_sync_ff",
        test_dir=Path(__file__).parent,
        parameters={"WIDTH": width, "STAGES": stages, "RESET_VALUE": reset_value},
    )
