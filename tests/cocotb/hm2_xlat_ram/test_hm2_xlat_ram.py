# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_xlat_ram (the 7i43 firmwares' TranslationRAM, GTag 11) against
spec/hostmot2.md sections 9.7 and 9.8, with a dict as the reference: 256
read/write words at 0x7800-0x7BFC, 0 after configuration, every other
address reads 0 and a write there changes no word, read data follows the
bus rules (0 for a read that missed, held until the next read)."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge

from common.hm2bus import Hm2Bus
from common.runner import SIMULATORS, hdl, run

BASE = 0x7800
WORDS = 256


async def start(dut: Any) -> Hm2Bus:
    cocotb.start_soon(Clock(dut.clk, 20, unit="ns").start())
    bus = Hm2Bus(dut)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.rst.value = 0
    return bus


async def check_all(bus: Hm2Bus, model: dict[int, int]) -> None:
    for k in range(WORDS):
        got = await bus.read(BASE + 4 * k)
        assert got == model.get(k, 0), f"word {k}: {got:#x}, want {model.get(k, 0):#x}"


@cocotb.test()
async def ram_words(dut: Any) -> None:
    bus = await start(dut)
    model: dict[int, int] = {}
    await check_all(bus, model)  # configuration clears the RAM
    # every word its own value (an address bit stuck or aliased shows here)
    for k in range(WORDS):
        model[k] = (k * 0x01010101) ^ 0xA5000000 ^ (k << 12)
        await bus.write(BASE + 4 * k, model[k])
    await check_all(bus, model)
    # random traffic, reads right after writes of the same word included
    rng = random.Random(11)
    for _ in range(400):
        k = rng.randrange(WORDS)
        if rng.random() < 0.5:
            model[k] = rng.getrandbits(32)
            await bus.write(BASE + 4 * k, model[k])
        got = await bus.read(BASE + 4 * k)
        assert got == model[k], f"word {k}: {got:#x}, want {model[k]:#x}"
    assert await bus.check_hold() == model[k]


@cocotb.test()
async def outside_reads_zero(dut: Any) -> None:
    bus = await start(dut)
    model = {k: 0x1000 + k for k in range(WORDS)}
    for k, v in model.items():
        await bus.write(BASE + 4 * k, v)
    # neighbours of the window: the translated window 0x7C00, the page
    # below, the other end of the address space
    outside = [0x7C00, 0x7C04, 0x7FFC, 0x77FC, 0x7400, 0x3800, 0x0000, 0xF800]
    for a in outside:
        await bus.read_expect_zero(a)
        await bus.write(a, 0xDEADBEEF)  # must not land in the RAM
    assert await bus.check_hold() == 0
    await check_all(bus, model)
    # a read that hits, then one that misses: the miss reads 0 and is held
    assert await bus.read(BASE + 4 * 7) == model[7]
    await bus.read_expect_zero(0x7C00 + 4 * 7)


@cocotb.test()
async def bad_access_is_refused(dut: Any) -> None:
    """The bus master refuses what the bus cannot carry (unaligned address,
    data wider than 32 bits) before touching the RAM."""
    bus = await start(dut)
    await bus.write(BASE, 0x12345678)
    for a in (BASE + 1, BASE + 2, 0x10000):
        with pytest.raises(ValueError):
            await bus.write(a, 0)
    with pytest.raises(ValueError):
        await bus.write(BASE, 1 << 32)
    assert await bus.read(BASE) == 0x12345678


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_xlat_ram(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_xlat_ram",
        sources=[hdl("hostmot2", "hm2_xlat_ram.v")],
        test_module="test_hm2_xlat_ram",
        test_dir=Path(__file__).parent,
    )
