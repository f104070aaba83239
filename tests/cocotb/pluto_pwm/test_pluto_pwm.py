# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_pwm (one PWM channel, compare against an external period counter)
clock by clock against pwm_outputs(), and spec facts on their own: the
on-time per period equals the duty (PWM and PDM), duty 0 never and 2047
always on, sign/xor bits, PDM spreads the on-time."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from common.runner import SIMULATORS, hdl, run
from pluto_common.models import PWM_PERIOD, pwm_outputs


async def start(dut: Any) -> None:
    Clock(dut.clk, 25, unit="ns").start()
    dut.cnt.value = 0
    dut.pdm.value = 0
    dut.word.value = 0
    dut.rst.value = 1
    await RisingEdge(dut.clk)
    await FallingEdge(dut.clk)
    dut.rst.value = 0


async def period(
    dut: Any, word: int, pdm: bool, counts: range | list[int] | None = None
) -> list[tuple[int, int]]:
    """Run the counter through ``counts`` (a full period by default) with
    ``word``; check every clock; return the (up, dn) sequence."""
    dut.word.value = word
    dut.pdm.value = int(pdm)
    seq = []
    for c in counts if counts is not None else range(PWM_PERIOD):
        dut.cnt.value = c
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        got = (int(dut.up_q.value), int(dut.dn_q.value))
        want = pwm_outputs(word, c, pdm)
        assert got == want, f"word {word:#06x} pdm {pdm} cnt {c}: {got} != {want}"
        seq.append(got)
    return seq


@cocotb.test()
async def duty_is_on_time(dut: Any) -> None:
    await start(dut)
    for pdm in (False, True):
        for duty in (0, 1, 2, 1023, 1024, 2046, 2047):
            up = [u for u, _ in await period(dut, duty, pdm)]
            assert sum(up) == duty, f"duty {duty} pdm {pdm}: on for {sum(up)} clocks"


@cocotb.test()
async def pdm_spreads_on_time(dut: Any) -> None:
    await start(dut)
    pwm = [u for u, _ in await period(dut, 1024, False)]
    pdm = [u for u, _ in await period(dut, 1024, True)]
    edges = lambda s: sum(1 for i in range(1, len(s)) if s[i] != s[i - 1])  # noqa: E731
    assert edges(pwm) == 1  # one block of on-time
    assert edges(pdm) > 100, f"PDM has only {edges(pdm)} transitions"
    longest = max(len(r) for r in "".join(map(str, pdm)).split("0"))
    assert longest <= 16, f"PDM on-run of {longest} clocks"


@cocotb.test()
async def sign_and_xor_bits(dut: Any) -> None:
    await start(dut)
    duty = 700
    # sign 0: pulses on UP, DN low; sign 1: pulses on DN, UP low.
    s0 = await period(dut, duty, False)
    assert sum(u for u, _ in s0) == duty and all(d == 0 for _, d in s0)
    s1 = await period(dut, duty | 0x8000, False)
    assert sum(d for _, d in s1) == duty and all(u == 0 for u, _ in s1)
    # bit 12 / 13 invert UP / DN (pwm+dir: DN is the static direction level).
    s2 = await period(dut, duty | 0x2000, False)
    assert sum(u for u, _ in s2) == duty and all(d == 1 for _, d in s2)
    s3 = await period(dut, duty | 0x1000 | 0x8000, False)
    assert all(u == 1 for u, _ in s3) and sum(d for _, d in s3) == duty


@cocotb.test()
async def random_words(dut: Any) -> None:
    await start(dut)
    rng = random.Random(11)
    for _ in range(25):
        word = rng.getrandbits(16)
        counts = [rng.randrange(PWM_PERIOD) for _ in range(60)]
        await period(dut, word, bool(rng.getrandbits(1)), counts)


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_pwm(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_pwm",
        sources=[hdl("pluto", "pluto_pwm.v")],
        test_module="test_pluto_pwm",
        test_dir=Path(__file__).parent,
    )
