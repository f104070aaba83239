# SPDX-License-Identifier: GPL-2.0-or-later
"""cocotb measurements behind `bench/hdl/run.sh` (not part of `make test`).

Each test measures at pin level in simulation and appends its figures as
JSON lines to the file named by $HM_BENCH_OUT.  The tests assert nothing
about speed (speed goals live in the report, not in pass/fail); they do
assert that what they measured was correct motion (counts match), so a
figure is never taken from a broken run."""

from __future__ import annotations

from typing import Any

import json
import os

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer
from cocotb.utils import get_sim_time

from common.hm2bus import Hm2Bus
from common.pins import DutyMeter, QuadSource, StepLimits, VectorLog, check_stepdir


def emit(**fig: object) -> None:
    with open(os.environ["HM_BENCH_OUT"], "a") as f:
        f.write(json.dumps(fig) + "\n")


async def reset(dut: Any, clk: Any, cycles: int = 4) -> None:
    dut.rst.value = 1
    await ClockCycles(clk, cycles)
    await FallingEdge(clk)
    dut.rst.value = 0
    await RisingEdge(clk)


@cocotb.test()
async def stepgen_rates(dut: Any) -> None:
    """Max step rate and timing resolution at several ClockLow values."""
    if not hasattr(dut, "step_out"):
        return
    bus = Hm2Bus(dut)
    for period in (30.0, 20.0, 10.0):  # 33.33, 50, 100 MHz
        clk = cocotb.start_soon(Clock(dut.clk, period, unit="ns").start())
        await reset(dut, dut.clk)
        await bus.write(0x2900, 0xFFFFFFFF)
        for pw, pi in ((0, 0), (1, 0)):
            await bus.write(0x2500, pw)
            await bus.write(0x2600, pi)
            await bus.write(0x2000, 0x7FFFFFFF)
            await ClockCycles(dut.clk, 50)
            log = VectorLog(dut.step_out).start()
            t0 = get_sim_time("ns")
            await ClockCycles(dut.clk, 3000)
            t1 = get_sim_time("ns")
            log.stop()
            rep = check_stepdir(log.bit(0), log.bit(1), period, StepLimits(pw + 1, pi + 1, 1, 1))
            assert not rep.violations, rep.violations[:3]
            rate = len([t for t in rep.rises if t0 <= t < t1]) / ((t1 - t0) * 1e-9)
            emit(
                kind="step_rate",
                clock_mhz=1e3 / period,
                pulsewidth=pw,
                pulseidle=pi,
                rate_hz=rate,
                width_ns=min(rep.widths) * period,
            )
        # timing resolution: pulse width for PulseWidth = 0..3
        widths = []
        for pw in range(4):
            await bus.write(0x2500, pw)
            await bus.write(0x2600, 3)
            log = VectorLog(dut.step_out).start()
            await ClockCycles(dut.clk, 200)
            log.stop()
            ws = DutyMeter(log.bit(0)).high_widths(0, 1e15)
            widths.append(sorted(set(ws))[0])
        steps = [b - a for a, b in zip(widths, widths[1:])]
        emit(
            kind="step_resolution",
            clock_mhz=1e3 / period,
            resolution_ns=min(steps),
            widths_ns=widths,
        )
        await bus.write(0x2000, 0)
        clk.cancel()


@cocotb.test()
async def encoder_count_rate(dut: Any) -> None:
    """Highest 4x count rate counted without error, filter off and on,
    sampling every ClockLow (QFilterRate = 0xFFF)."""
    if not hasattr(dut, "enc_a"):
        return
    bus = Hm2Bus(dut)
    for period in (30.0, 20.0):
        clk = cocotb.start_soon(Clock(dut.clk, period, unit="ns").start())
        dut.enc_a.value = 0
        dut.enc_b.value = 0
        dut.enc_idx.value = 0
        dut.enc_idxmask.value = 0
        await reset(dut, dut.clk)
        await bus.write(0x3400, 0xFFF)
        for filt, n_samples in ((0, 3), (1, 15)):
            await bus.write(0x3100, (filt << 11) | (1 << 15))
            best = None
            # edge spacing in clocks, from slow to fast; stop at the first failure
            spacing = 12.0 if filt else 3.0
            while spacing > 0.3:
                src = QuadSource(dut.enc_a, dut.enc_b, seed=3)
                await ClockCycles(dut.clk, 40)
                await bus.write(0x3000, 0)
                await bus.write(0x3100, (filt << 11) | (1 << 15))
                await Timer(0.377, unit="ns")
                edge = round(spacing * period, 3)
                await src.move(300, edge)
                await ClockCycles(dut.clk, 40)
                mid = await bus.read(0x3000) & 0xFFFF
                await src.move(-300, edge)
                await ClockCycles(dut.clk, 40)
                end = await bus.read(0x3000) & 0xFFFF
                qerr = (await bus.read(0x3100) >> 15) & 1
                if mid != 300 or end != 0 or qerr:
                    break
                best = spacing
                spacing = round(spacing - 0.1, 2)
            assert best is not None, "encoder failed even at the slowest rate"
            emit(
                kind="encoder_rate",
                clock_mhz=1e3 / period,
                filter=n_samples,
                min_edge_clocks=best,
                rate_hz=1e9 / (best * period),
            )
        clk.cancel()


@cocotb.test()
async def pwm_frequency(dut: Any) -> None:
    """PWM frequency per resolution at the maximum rate DDS, PDM slot rate."""
    if not hasattr(dut, "pwm_out0"):
        return
    bus = Hm2Bus(dut)
    for period_h in (10.0, 5.0):  # ClockHigh 100, 200 MHz
        clk = cocotb.start_soon(Clock(dut.clk, 30, unit="ns").start())
        clkh = cocotb.start_soon(Clock(dut.clk_high, period_h, unit="ns").start())
        await reset(dut, dut.clk, 8)
        await ClockCycles(dut.clk, 8)
        await bus.write(0x4200, 0xFFFF)
        await bus.write(0x4300, 0xFFFF)
        for bits in (12, 11, 10, 9):
            await bus.write(0x4100, bits - 9)
            await bus.write(0x4000, (1 << (bits - 1)) << 16)  # 50 %
            await bus.write(0x4104, (bits - 9) | (3 << 3))  # instance 1: PDM
            await bus.write(0x4004, 1 << 16)  # density 1/4096: isolated slots
            await ClockCycles(dut.clk, 20)
            per_est = (1 << bits) * period_h
            log = VectorLog(dut.pwm_out0).start()
            t0 = get_sim_time("ns")
            await Timer(round(per_est * 6, 3), unit="ns")
            log.stop()
            ps = DutyMeter(log.bit(0)).periods(t0, 1e15)
            assert len(ps) >= 4
            f = 1e9 / (sum(ps) / len(ps))
            pd = DutyMeter(log.bit(1)).high_widths(t0, 1e15)
            emit(
                kind="pwm",
                clock_high_mhz=1e3 / period_h,
                bits=bits,
                freq_hz=f,
                step_ns=period_h,
                pdm_slot_ns=min(pd) if pd else None,
            )
        clk.cancel()
        clkh.cancel()
