# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_step top, pin level, through the EPP host model replaying the
LinuxCNC pluto_step driver's per-cycle transactions (spec sections 5, 6,
11): velocity registers, position feedback (21 bits, 11 fractional) against
the steps counted on the STEP/DIR pins, step length / direction time in
1.6 us units at 0 and at the maximum, step polarity, top step rate
(312.5 kHz), outputs, inputs, watchdog, LED, wedged host."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import cocotb
import pytest
from cocotb.triggers import ClockCycles, FallingEdge, Timer

from common.runner import SIMULATORS, hdl, run
from pluto_common.bench import epp_host, pins, start_clock_and_reset
from pluto_common.driver import StepDriver
from pluto_common.models import step_rate, step_timing_word

SOURCES = [
    hdl("pluto", f"{m}.v") for m in ("pluto_epp", "pluto_stepgen", "pluto_wdt", "pluto_step")
]
OUTS = 23
LED = 22
TICK_NS = 1600.0


def step_pin(n: int) -> int:
    return 14 + 2 * n


def dir_pin(n: int) -> int:
    return 15 + 2 * n


class StepMonitor:
    """Counts steps on the pins and measures pulse/hold/setup times (ns)."""

    def __init__(self, dut: Any, polarity: int = 0) -> None:
        self.dut = dut
        self.polarity = polarity
        self.net = [0] * 4
        self.rises = [0] * 4
        self.rise_times: list[list[float]] = [[], [], [], []]
        self.high_ns: list[float] = []
        self.low_ns: list[float] = []
        self.hold_ns: list[float] = []
        self.setup_ns: list[float] = []
        self.task = cocotb.start_soon(self._run())

    async def _run(self) -> None:
        dut = self.dut
        prev = None
        t_rise = [0.0] * 4
        t_fall = [-1e12] * 4
        t_dir = [-1e12] * 4
        while True:
            await FallingEdge(dut.clk)
            p = pins(int(dut.io_out.value), int(dut.io_oe.value), OUTS)
            now = cocotb.utils.get_sim_time("ns")
            if prev is not None:
                for n in range(4):
                    s0 = ((prev >> step_pin(n)) & 1) ^ self.polarity
                    s1 = ((p >> step_pin(n)) & 1) ^ self.polarity
                    d0, d1 = (prev >> dir_pin(n)) & 1, (p >> dir_pin(n)) & 1
                    if d0 != d1:
                        assert s1 == 0, "DIR changed during a step pulse"
                        self.hold_ns.append(now - t_fall[n])
                        t_dir[n] = now
                    if s1 and not s0:
                        self.rises[n] += 1
                        self.net[n] += -1 if d1 else 1
                        self.rise_times[n].append(now)
                        self.low_ns.append(now - t_fall[n])
                        self.setup_ns.append(now - t_dir[n])
                        t_rise[n] = now
                    if s0 and not s1:
                        self.high_ns.append(now - t_rise[n])
                        t_fall[n] = now
            prev = p


async def start(dut: Any) -> tuple[Any, StepDriver]:
    dut.io_in.value = 0
    host = epp_host(dut)
    await start_clock_and_reset(dut)
    await ClockCycles(dut.clk, 10)
    return host, StepDriver(host)


@cocotb.test()
async def driver_cycle_and_feedback_matches_pins(dut: Any) -> None:
    host, drv = await start(dut)
    mon = StepMonitor(dut)
    timing = step_timing_word(steplen_ns=5000, dirtime_ns=20000, step_polarity=False)
    assert timing == 3 | 12 << 8
    # Below fmax = 625 kHz / (2 + steplen 3 + stepspace 0) = 125 kHz, as the driver limits.
    rates = [step_rate(v) for v in (20000.0, -35000.0, 1000.0, -110000.0)]
    cycles = await drv.write(rates, 0x1234, timing)
    # Spec section 11: A(00) then 12 data writes, LSB first.
    raw = b"".join((r & 0xFFFF).to_bytes(2, "little") for r in rates)
    raw += (0x1234).to_bytes(2, "little") + timing.to_bytes(2, "little")
    assert host.trace(cycles) == "A(00) " + " ".join(f"W({x:02x})" for x in raw)
    for _ in range(6):  # six 1 ms servo periods
        await Timer(1, unit="ms")
        cycles = await drv.read()
        assert str(cycles[0]) == "A(00)" and [c.kind.value for c in cycles[1:]] == ["R"] * 20
    await drv.write([0, 0, 0, 0], 0x1234, timing)
    await Timer(200, unit="us")
    await drv.read()
    for n in range(4):
        # Whole steps of the feedback equal the net steps seen on the pins.
        assert int(drv.position_steps(n) // 1) == mon.net[n], (n, drv.last_count[n], mon.net[n])
        # Rate: position moved ~ rate * ticks / 2048.
        expect = rates[n] / 2048.0 * (6e6 / TICK_NS)
        assert abs(drv.position_steps(n) - expect) <= abs(expect) * 0.02 + 2, (n, expect)
    assert min(mon.high_ns) == max(mon.high_ns) == 4 * TICK_NS  # steplen 3 -> 4 ticks
    pin_out = pins(int(dut.io_out.value), int(dut.io_oe.value), OUTS)
    assert pin_out & 0x3FFF == 0x1234


@cocotb.test()
async def top_step_rate_and_polarity(dut: Any) -> None:
    host, drv = await start(dut)
    mon = StepMonitor(dut, polarity=1)
    await drv.write([1024, -1024, 0, 0], 0, step_timing_word(0, 0, True))
    await Timer(400, unit="us")
    t = mon.rise_times[0][5:]
    periods = {round(t[i + 1] - t[i]) for i in range(len(t) - 1)}
    assert periods == {3200}, periods  # 312.5 kHz
    assert min(mon.high_ns) == TICK_NS and min(mon.low_ns) >= TICK_NS
    # Polarity 1: idle STEP pins high.
    await drv.write([0, 0, 0, 0], 0, step_timing_word(0, 0, True))
    await Timer(20, unit="us")
    p = pins(int(dut.io_out.value), int(dut.io_oe.value), OUTS)
    assert all((p >> step_pin(n)) & 1 for n in range(4))
    await drv.read()
    assert mon.net[0] == int(drv.position_steps(0) // 1)
    assert mon.net[1] == int(drv.position_steps(1) // 1)


@cocotb.test()
async def timing_fields_at_zero_and_max(dut: Any) -> None:
    """steplen/dirtime 0 -> 1 tick (1.6 us); the driver's max (49.6 us,
    31 ticks) is written as 31 and the 4-bit fields keep 15 -> 16 ticks
    (25.6 us), 30 us = 18 ticks wraps to 2 -> 3 ticks: the spec's section 12
    discrepancy, reproduced."""
    for steplen_ns, dirtime_ns, want in (
        (0, 0, 1),
        (49600, 49600, 16),
        (24000, 24000, 16),
        (30000, 30000, 3),
    ):
        host, drv = await start(dut)
        mon = StepMonitor(dut)
        timing = step_timing_word(steplen_ns, dirtime_ns, False)
        rate = 2048 // (want + 1) // 2
        for v in (rate, -rate, rate):
            await drv.write([v, 0, 0, 0], 0, timing)
            await Timer(500, unit="us")
        await drv.write([0, 0, 0, 0], 0, timing)
        await Timer(100, unit="us")
        await drv.read()
        mon.task.cancel()
        assert set(mon.high_ns) == {want * TICK_NS}, (steplen_ns, set(mon.high_ns))
        assert len(mon.hold_ns) >= 2
        assert min(mon.hold_ns) >= want * TICK_NS, (dirtime_ns, mon.hold_ns)
        assert min(mon.hold_ns) <= want * TICK_NS + TICK_NS
        assert min(s for s in mon.setup_ns if s < 1e9) >= want * TICK_NS
        assert mon.net[0] == int(drv.position_steps(0) // 1)


@cocotb.test()
async def inputs_and_outputs(dut: Any) -> None:
    host, drv = await start(dut)
    rng = random.Random(6)
    for _ in range(5):
        v = rng.getrandbits(16)
        dut.io_in.value = v
        d = rng.getrandbits(14)
        await drv.write([0] * 4, d, 0)
        await ClockCycles(dut.clk, 4)
        await drv.read()
        assert drv.din == v
        p = pins(int(dut.io_out.value), int(dut.io_oe.value), OUTS)
        assert p & 0x3FFF == d


@cocotb.test()
async def watchdog_bites_and_recovers(dut: Any) -> None:
    host, drv = await start(dut)
    # The stock driver never sets bit 14: no watchdog.
    await drv.write([300, 0, 0, 0], 0x3FFF, 0)
    await Timer(7, unit="ms")
    assert int(dut.io_oe.value) == (1 << OUTS) - 1
    # Bit 14 of register 8-9 arms/pets it: bite 127 x 2048 clocks later.
    await drv.write([300, 0, 0, 0], 0x3FFF | 0x4000, 0)
    t = cocotb.utils.get_sim_time("ns")
    while int(dut.io_oe.value):
        await FallingEdge(dut.clk)
    dt = cocotb.utils.get_sim_time("ns") - t
    assert 126 * 2048 * 25 <= dt <= 127 * 2048 * 25 + 200, dt
    assert pins(int(dut.io_out.value), 0, OUTS) == (1 << OUTS) - 1
    await drv.write([0, 0, 0, 0], 0x0F0F | 0x4000, 0)
    await ClockCycles(dut.clk, 2)
    assert int(dut.io_oe.value) == (1 << OUTS) - 1
    assert int(dut.io_out.value) & 0x3FFF == 0x0F0F


@cocotb.test()
async def led_is_step0_xor_dir0(dut: Any) -> None:
    host, drv = await start(dut)
    await drv.write([-700, 0, 0, 0], 0, 0)
    for _ in range(300):
        await FallingEdge(dut.clk)
        p = int(dut.io_out.value)
        assert (p >> LED) & 1 == ((p >> step_pin(0)) ^ (p >> dir_pin(0))) & 1


@cocotb.test()
async def wedged_host_then_recovery(dut: Any) -> None:
    host, drv = await start(dut)
    await drv.write([500, 0, 0, 0], 0x4000, 0)
    await host.write_addr(2)
    await host.abandoned_strobe(write=False)
    await Timer(7, unit="ms")
    assert int(dut.io_oe.value) == 0
    await host.release_all()
    host.violations.clear()
    await drv.write([0, 0, 0, 0], 0x4000 | 5, 0)
    await ClockCycles(dut.clk, 4)
    assert int(dut.io_out.value) & 0x3FFF == 5 and int(dut.io_oe.value) != 0
    await drv.read()
    assert host.status == 0 and drv.last_count[0] > 0


@pytest.mark.parametrize("sim", SIMULATORS)
def test_pluto_step(sim: str) -> None:
    run(
        sim=sim,
        toplevel="pluto_step",
        sources=SOURCES,
        test_module="test_pluto_step",
        test_dir=Path(__file__).parent,
    )
