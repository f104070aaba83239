# SPDX-License-Identifier: GPL-2.0-or-later
"""cocotb side of bench/pluto: measures on the Verilated firmware and
writes the figures as JSON lines to $PLUTO_BENCH_OUT."""

from __future__ import annotations

import json
import os
from typing import Any

import cocotb
from cocotb.triggers import ClockCycles, FallingEdge, Timer

from common.epp import EppStats, EppTiming
from pluto_common.bench import epp_host, start_clock_and_reset
from pluto_common.driver import ServoDriver, StepDriver
from pluto_common.models import servo_ctrl_word, servo_pwm_word, step_timing_word


def emit(**kw: Any) -> None:
    with open(os.environ["PLUTO_BENCH_OUT"], "a") as f:
        f.write(json.dumps(kw) + "\n")


async def rising_times(dut: Any, bit: int, n: int) -> list[float]:
    out, prev = [], None
    while len(out) < n:
        await FallingEdge(dut.clk)
        v = (int(dut.io_out.value) >> bit) & 1
        if prev == 0 and v == 1:
            out.append(float(cocotb.utils.get_sim_time("ns")))
        prev = v
    return out


async def bite_time(dut: Any, t0: float) -> float:
    while int(dut.io_oe.value):
        await FallingEdge(dut.clk)
    return float(cocotb.utils.get_sim_time("ns") - t0)


@cocotb.test()
async def measure(dut: Any) -> None:
    servo = dut._name == "pluto_servo"
    dut.io_in.value = 0
    name = "pluto_servo" if servo else "pluto_step"
    profiles = (("fast host", EppTiming()), ("PC pace (1 us/cycle)", EppTiming.pc_isa()))
    for profile, timing in profiles:
        host = epp_host(dut, timing=timing)
        if profile == "fast host":
            await start_clock_and_reset(dut)
            await ClockCycles(dut.clk, 10)
        drv: Any = ServoDriver(host) if servo else StepDriver(host)
        for _ in range(3):
            if servo:
                ctrl = servo_ctrl_word(0, False, True, False)
                wc = await drv.write([servo_pwm_word(0.5)] * 4, ctrl)
            else:
                wc = await drv.write([100] * 4, 0, step_timing_word(0, 0, False))
            rc = await drv.read()
        ws, rs = EppStats.of(wc), EppStats.of(rc)
        emit(
            kind="epp",
            fw=name,
            profile=profile,
            write_cycles=ws.cycles,
            read_cycles=rs.cycles,
            write_ns=ws.bus_ns,
            read_ns=rs.bus_ns,
            timeouts=ws.timeouts + rs.timeouts,
            ack_min=min(ws.ack_latency_ns + rs.ack_latency_ns),
            ack_max=max(ws.ack_latency_ns + rs.ack_latency_ns),
            trace_write=host.trace(wc),
            trace_read=host.trace(rc),
        )
        host.stop()
    host = epp_host(dut)
    drv = ServoDriver(host) if servo else StepDriver(host)
    if servo:
        await drv.write([servo_pwm_word(0.5)] * 4, servo_ctrl_word(0, False, True, False))
        t_pet = float(cocotb.utils.get_sim_time("ns"))
        t = await rising_times(dut, 10, 6)
        period = (t[-1] - t[1]) / 4
        emit(kind="rate", fw=name, what="PWM frequency", hz=1e9 / period, spec_hz=40e6 / 2047)
    else:
        await drv.write([1024, 0, 0, 0], 0x4000, step_timing_word(0, 0, False))
        t_pet = float(cocotb.utils.get_sim_time("ns"))
        t = await rising_times(dut, 14, 12)
        period = (t[-1] - t[1]) / 10
        emit(kind="rate", fw=name, what="max step rate", hz=1e9 / period, spec_hz=312.5e3)
    bite = await bite_time(dut, t_pet)
    # The pet lands a few clocks before the write cycle completes (its last
    # byte's strobe edge), so the measured time is up to ~0.2 us short.
    tick_ms = (2047 if servo else 2048) * 25e-6
    emit(kind="wdt", fw=name, bite_ms=bite / 1e6, spec_lo=126 * tick_ms, spec_hi=127 * tick_ms)
    await Timer(1, unit="us")
