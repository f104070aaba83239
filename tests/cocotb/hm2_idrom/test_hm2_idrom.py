# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_idrom (ID block, IDROM RAM, write enable) and hm2_led against the
spec (sections 2, 3, 9.3): the ID block words and their aliasing, an IDROM
image given as parameter read back word by word, writes ignored unless
0x0800 bit 0 is set, and the LED bit mapping (bit 31 = highest LED)."""

from __future__ import annotations

from typing import Any

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.hm2bus import Hm2Bus
from common.runner import SIMULATORS, hdl, run

RNG = random.Random(43)
IMAGE = [RNG.getrandbits(32) for _ in range(256)]
IMAGE_PARAM = sum(w << (32 * i) for i, w in enumerate(IMAGE))
ID_BLOCK = [0x55AACAFE, 0x54534F48, 0x32544F4D, 0x00000400]


async def setup(dut: Any) -> Hm2Bus:
    cocotb.start_soon(Clock(dut.clk, 20, unit="ns").start())
    dut.rst.value = 1
    bus = Hm2Bus(dut)
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    return bus


@cocotb.test()
async def idrom_contents(dut: Any) -> None:
    bus = await setup(dut)
    # ID block, aliased every 16 bytes over the page; "HOSTMOT2" as bytes
    for k in range(0, 256, 4):
        assert await bus.read(0x100 + k) == ID_BLOCK[(k // 4) % 4], f"{0x100 + k:#x}"
    name = b"".join(w.to_bytes(4, "little") for w in ID_BLOCK[1:3])
    assert name == b"HOSTMOT2"
    for i in range(256):
        assert await bus.read(0x400 + 4 * i) == IMAGE[i], f"IDROM word {i}"
    assert await bus.check_hold() == IMAGE[255]
    assert await bus.read(0x800) == 0
    for a in (0x000, 0x0FC, 0x200, 0x300, 0x804, 0x900, 0x1000, 0xFFFC):
        await bus.read_expect_zero(a)


@cocotb.test()
async def idrom_write_enable(dut: Any) -> None:
    bus = await setup(dut)
    await bus.write(0x400, 0xDEADBEEF)  # write-protected: ignored
    assert await bus.read(0x400) == IMAGE[0]
    await bus.write(0x100, 0)  # the ID block is read-only
    assert await bus.read(0x100) == ID_BLOCK[0]
    await bus.write(0x800, 0xFFFFFFFF)
    assert await bus.read(0x800) == 1
    await bus.write(0x7FC, 0x12345678)
    await bus.write(0x404, 0xCAFEF00D)
    assert await bus.read(0x7FC) == 0x12345678
    assert await bus.read(0x404) == 0xCAFEF00D
    assert await bus.read(0x400) == IMAGE[0]
    await bus.write(0x800, 0)
    await bus.write(0x7FC, 0)
    assert await bus.read(0x7FC) == 0x12345678
    # reset clears the enable, not the RAM (like a block RAM: only
    # reconfiguration reloads the image)
    await bus.write(0x800, 1)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    assert await bus.read(0x800) == 0
    assert await bus.read(0x404) == 0xCAFEF00D


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_idrom(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_idrom",
        sources=[hdl("hostmot2", "hm2_idrom.v")],
        parameters={"IDROM": f"8192'h{IMAGE_PARAM:02048x}"},
        test_module="test_hm2_idrom",
        test_dir=Path(__file__).parent,
    )
