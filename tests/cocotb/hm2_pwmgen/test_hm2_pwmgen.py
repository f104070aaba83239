# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_pwmgen_bank at pin level, two clock domains (ClockLow 33.3 MHz bus,
ClockHigh 100 MHz PWM, unrelated phase).

Checks in every test:
* the ClockHigh configuration register only ever holds a complete state the
  bus wrote (never a torn mix), in write order, and ends at the last one;
* Out0/Out1 on every ClockHigh edge equal the reference model
  (pwmgen_model.py) fed with that configuration;
and per test independent spec-formula checks of duty, frequency, PDM
density, output types and Not-Enable."""

from __future__ import annotations

from typing import Any

from pathlib import Path

import cocotb
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer
from cocotb.utils import get_sim_time

from common.hm2bus import Hm2Bus
from common.pins import DutyMeter, VectorLog
from common.runner import SIMULATORS, hdl, run
from pwmgen_model import Config, PwmBankModel, pdm_density, pwm_duty, pwm_frequency, reg_value

BASE = 0x4000
PERIOD_LOW = 30
PERIOD_HIGH = 10
CLOCK_HIGH = 1e9 / PERIOD_HIGH
R_VAL, R_MODE, R_PWMRATE, R_PDMRATE, R_ENABLE = range(5)
EPS = 1e-3  # ns: float slack when comparing event times with clock edges


def addr(reg: int, inst: int = 0) -> int:
    return BASE + reg * 0x100 + inst * 4


class Harness:
    def __init__(self, dut: Any) -> None:
        self.dut = dut
        self.num = int(dut.NUM.value)
        self.bus = Hm2Bus(dut)
        # ClockLow shadow states after each write, in order
        self.vals = [0] * self.num
        self.modes = [0] * self.num
        self.rates = [0, 0]
        self.states: list[int] = [self._pack()]
        self.t0 = 0.0
        self.logs: dict[str, VectorLog] = {}

    def _pack(self) -> int:
        w = 0
        for i, v in enumerate(self.vals):
            w |= v << (13 * i)
        base = 13 * self.num
        for i, m in enumerate(self.modes):
            w |= m << (base + 6 * i)
        base += 6 * self.num
        return w | (self.rates[0] << base) | (self.rates[1] << (base + 16))

    async def start(self) -> None:
        d = self.dut
        cocotb.start_soon(Clock(d.clk, PERIOD_LOW, unit="ns").start())
        await Timer(3, unit="ns")  # ClockHigh edges fall between ClockLow edges
        cocotb.start_soon(Clock(d.clk_high, PERIOD_HIGH, unit="ns").start())
        d.rst.value = 1
        self.bus.idle()
        await ClockCycles(d.clk, 4)
        await FallingEdge(d.clk)
        d.rst.value = 0
        while True:
            await RisingEdge(d.clk_high)
            await Timer(1, unit="ns")
            if int(d.rst_h.value) == 0:
                break
        await RisingEdge(d.clk_high)
        self.t0 = get_sim_time("ns")  # first edge with the ClockHigh side out of reset
        self.logs = {
            n: VectorLog(getattr(d, n)).start()
            for n in ("cfg_h_q", "pwm_out0", "pwm_out1", "pwm_nenable")
        }

    async def write(self, reg: int, inst: int, data: int) -> None:
        await self.bus.write(addr(reg, inst), data)
        if inst < self.num and reg == R_VAL:
            self.vals[inst] = ((data >> 31) << 12) | ((data >> 16) & 0xFFF)
        elif inst < self.num and reg == R_MODE:
            self.modes[inst] = data & 0x3F
        elif inst == 0 and reg == R_PWMRATE:
            self.rates[0] = data & 0xFFFF
        elif inst == 0 and reg == R_PDMRATE:
            self.rates[1] = data & 0xFFFF
        else:
            return
        self.states.append(self._pack())

    async def settle(self) -> None:
        """Long enough for a pending transfer plus one more to complete."""
        await ClockCycles(self.dut.clk, 16)

    async def wait_ns(self, ns: float) -> None:
        await Timer(round(ns * 1000) / 1000, unit="ns")

    def trace(self, name: str, i: int) -> Any:
        return self.logs[name].bit(i)

    def check(self) -> None:
        """CDC integrity and the cycle model over the whole test."""
        cfg = self.logs["cfg_h_q"]
        seen = [cfg.v0] + [v for _, v in cfg.changes]
        pos = 0
        for v in seen:
            try:
                pos = self.states.index(v, pos)
            except ValueError:
                raise AssertionError(
                    f"ClockHigh configuration {v:#x} is not a state the bus "
                    "wrote (torn or out of order transfer)"
                ) from None
        assert seen[-1] == self.states[-1], "last write never reached ClockHigh"

        end = get_sim_time("ns")
        model = PwmBankModel(self.num)
        o0, o1 = self.logs["pwm_out0"], self.logs["pwm_out1"]
        cfg_i = o0_i = o1_i = 0
        cur_cfg, l0, l1 = cfg.v0, o0.v0, o1.v0
        k = 0
        while True:
            t = self.t0 + k * PERIOD_HIGH
            if t > end - PERIOD_HIGH:
                break
            while cfg_i < len(cfg.changes) and cfg.changes[cfg_i][0] < t - EPS:
                cur_cfg = cfg.changes[cfg_i][1]
                cfg_i += 1
            model.clock(Config.unpack(cur_cfg, self.num))
            while o0_i < len(o0.changes) and o0.changes[o0_i][0] <= t + EPS:
                l0 = o0.changes[o0_i][1]
                o0_i += 1
            while o1_i < len(o1.changes) and o1.changes[o1_i][0] <= t + EPS:
                l1 = o1.changes[o1_i][1]
                o1_i += 1
            want = model.outputs()
            if (l0, l1) != want:
                raise AssertionError(
                    f"ClockHigh edge {k} (t={t}): out0,out1 = {l0:#x},{l1:#x}, "
                    f"model {want[0]:#x},{want[1]:#x}"
                )
            k += 1


@cocotb.test()
async def bus_rules(dut: Any) -> None:
    """Enable is R/W and drives Not-Enable low; the rest is write-only."""
    h = Harness(dut)
    await h.start()
    assert int(dut.pwm_nenable.value) == (1 << h.num) - 1, "enabled out of reset"
    await h.write(R_ENABLE, 0, 0xFFFFFFFE)
    assert await h.bus.read(addr(R_ENABLE)) == ((1 << h.num) - 1) & ~1
    await h.bus.check_hold()
    assert int(dut.pwm_nenable.value) == 1
    for reg, inst in ((R_VAL, 0), (R_MODE, 1), (R_PWMRATE, 0), (R_PDMRATE, 0)):
        await h.write(reg, inst, 0x12345678)
        await h.bus.read_expect_zero(addr(reg, inst))
    await h.bus.read_expect_zero(addr(R_ENABLE, 1))
    await h.bus.read_expect_zero(addr(5, 0))
    await h.bus.read_expect_zero(BASE - 0x100)
    await h.bus.read_expect_zero(0x3000)
    await h.write(R_ENABLE, 1, 0)  # alias: ignored
    assert await h.bus.read(addr(R_ENABLE)) == ((1 << h.num) - 1) & ~1
    await h.write(R_ENABLE, 0, 0)
    await h.settle()
    assert int(dut.pwm_nenable.value) == (1 << h.num) - 1
    h.check()


@cocotb.test()
async def cdc_burst(dut: Any) -> None:
    """Back-to-back writes of every register faster than the handshake:
    ClockHigh sees only whole states, in order, ending at the last."""
    h = Harness(dut)
    await h.start()
    for n in range(40):
        await h.write(R_VAL, n % h.num, reg_value(n & 1, 37 * n))
        await h.write(R_MODE, (n + 1) % h.num, n & 0x3F)
        if n % 5 == 0:
            await h.write(R_PWMRATE, 0, 1000 * n + 7)
            await h.write(R_PDMRATE, 0, 0xFFFF - n)
    await h.settle()
    h.check()
    assert len(h.logs["cfg_h_q"].changes) >= 10, "handshake never ran"


@cocotb.test()
async def resolutions_and_duty(dut: Any) -> None:
    """Sawtooth and symmetric at 9..12 bits: 0 %, a middle value, 2^bits
    (100 %) and above; duty over whole periods and frequency by formula."""
    h = Harness(dut)
    await h.start()
    rate = 0x8000  # PWMCLK = ClockHigh/2
    await h.write(R_PWMRATE, 0, rate)
    for mode in (0, 1, 2, 3, 4, 7):
        bits = 9 + (mode & 3)
        f = pwm_frequency(CLOCK_HIGH, rate, mode)
        per = 1e9 / f
        for i, value in enumerate((0, (1 << bits) // 3, 1 << bits, 0xFFF)):
            inst = i % h.num
            await h.write(R_MODE, inst, mode)
            await h.write(R_VAL, inst, reg_value(0, value))
            await h.settle()
            await h.wait_ns(per)  # one whole period to take the new value
            t_a = get_sim_time("ns")
            await h.wait_ns(2 * per)
            t_b = get_sim_time("ns")
            meter = DutyMeter(h.trace("pwm_out0", inst))
            duty = meter.duty(t_a, t_b)
            want = pwm_duty(mode, value & 0xFFF)  # 12-bit field: 4096 wraps to 0
            assert abs(duty - want) < 2.5 * PERIOD_HIGH / per + 1e-9, (mode, value, duty, want)
            if 0 < want < 1:
                periods = meter.periods(t_a - per, t_b)
                assert periods and all(abs(p - per) < 1e-6 for p in periods), (
                    mode,
                    periods[:3],
                    per,
                )
    h.check()


@cocotb.test()
async def output_types(dut: Any) -> None:
    """Modes 00 PWM/DIR, 01 DIR/PWM, 10 up/down (Out0 when DIR=1), 11 PDM/DIR,
    each with both DIR values."""
    h = Harness(dut)
    await h.start()
    await h.write(R_PWMRATE, 0, 0xFFFF)
    await h.write(R_PDMRATE, 0, 0x8000)
    per = 512 * 65536 / 0xFFFF * PERIOD_HIGH
    value = 128  # 25 % at 9 bits
    for omode in range(4):
        for dirn in (0, 1):
            await h.write(R_MODE, 0, omode << 3)
            await h.write(R_VAL, 0, reg_value(dirn, value))
            await h.settle()
            await h.wait_ns(per)
            t_a = get_sim_time("ns")
            await h.wait_ns(2 * per)
            t_b = get_sim_time("ns")
            d0 = DutyMeter(h.trace("pwm_out0", 0)).duty(t_a, t_b)
            d1 = DutyMeter(h.trace("pwm_out1", 0)).duty(t_a, t_b)
            tol = 0.01
            if omode == 0:
                ok = abs(d0 - 0.25) < tol and d1 == dirn
            elif omode == 1:
                ok = d0 == dirn and abs(d1 - 0.25) < tol
            elif omode == 2:
                ok = (
                    (abs(d0 - 0.25) < tol and d1 == 0)
                    if dirn
                    else (d0 == 0 and abs(d1 - 0.25) < tol)
                )
            else:
                ok = abs(d0 - pdm_density(value)) < tol and d1 == dirn
                # PDM: pulses are single slots (2 clocks), spread out
                widths = DutyMeter(h.trace("pwm_out0", 0)).high_widths(t_a, t_b)
                ok = ok and widths and max(widths) == 2 * PERIOD_HIGH
            assert ok, (omode, dirn, d0, d1)
    h.check()


@cocotb.test()
async def pdm_density_exact(dut: Any) -> None:
    """PDM: over 4096 slots exactly value slots are high, for 0, 1, a middle
    value and 4095."""
    h = Harness(dut)
    await h.start()
    await h.write(R_PDMRATE, 0, 0x8000)  # one slot per 2 ClockHigh clocks
    await h.write(R_MODE, 1, 3 << 3)
    slot = 2 * PERIOD_HIGH
    for value in (0, 1, 1234, 4095):
        await h.write(R_VAL, 1, reg_value(0, value))
        await h.settle()
        await h.wait_ns(3 * slot)
        t_a = get_sim_time("ns")
        await h.wait_ns(4096 * slot)
        t_b = get_sim_time("ns")
        high = DutyMeter(h.trace("pwm_out0", 1)).high_time(t_a, t_b)
        assert abs(high / slot - value) <= 1.01, (value, high / slot)
    h.check()


@cocotb.test()
async def double_buffer(dut: Any) -> None:
    """Mode bit 5: a value written mid-cycle only shows from the next cycle
    start, so every whole period has either the old or the new width."""
    h = Harness(dut)
    await h.start()
    await h.write(R_PWMRATE, 0, 0xFFFF)
    await h.write(R_MODE, 0, 0x20)  # 9 bit, double buffered
    await h.write(R_MODE, 1, 0x00)  # 9 bit, immediate
    per = 512 * 65536 / 0xFFFF * PERIOD_HIGH
    for v in (100, 400, 50, 300, 200):
        await h.write(R_VAL, 0, reg_value(0, v))
        await h.write(R_VAL, 1, reg_value(0, v))
        await h.wait_ns(per * 0.77)
    await h.wait_ns(2 * per)
    allowed = {
        round(v * PERIOD_HIGH * 65536 / 0xFFFF / PERIOD_HIGH) for v in (100, 400, 50, 300, 200)
    }
    w0 = [round(w / PERIOD_HIGH) for w in DutyMeter(h.trace("pwm_out0", 0)).high_widths(0, 1e12)]
    assert w0 and all(min(abs(w - a) for a in allowed) <= 1 for w in w0), w0
    w1 = [round(w / PERIOD_HIGH) for w in DutyMeter(h.trace("pwm_out0", 1)).high_widths(0, 1e12)]
    # immediate mode: some pulse is a mix of two values (proves the test can tell)
    assert any(min(abs(w - a) for a in allowed) > 1 for w in w1), w1
    h.check()


def _pulses(h: Harness, inst: int) -> list[tuple[float, float, int]]:
    """(rise, fall, pin) of every pulse on Out0/Out1 of an instance; asserts
    the two pins are never high together."""
    edges = sorted(
        [(t, v, 0) for t, v in h.trace("pwm_out0", inst).changes]
        + [(t, v, 1) for t, v in h.trace("pwm_out1", inst).changes]
    )
    out: list[tuple[float, float, int]] = []
    high: dict[int, float] = {}
    for t, v, pin in edges:
        if v:
            assert not high, f"Out0 and Out1 high together at {t}"
            high[pin] = t
        else:
            out.append((high.pop(pin), t, pin))
    return out


@cocotb.test()
async def updown_level_changes(dut: Any) -> None:
    """Output mode 2 (up/down) as the driver sets it for output-type 2
    (double buffered): whatever the value and sign writes mid-period, every
    PWM period has exactly one pulse on one pin, i.e. two level changes,
    starting at the period start; it moves to the other pin only at a period
    start.  Without double buffering a sign change mid-period splits a
    period's pulse over both pins (more level changes for the same duty):
    spec §20 "PWMGen output mode 2 edge count"."""
    h = Harness(dut)
    await h.start()
    await h.write(R_PWMRATE, 0, 0xFFFF)
    await h.write(R_MODE, 0, 0x20 | (2 << 3))  # 9 bit, up/down, double buffered
    await h.write(R_MODE, 1, 2 << 3)  # 9 bit, up/down, immediate
    clocks = 512 * 65536 / 0xFFFF
    per = clocks * PERIOD_HIGH
    seq = [(1, 300), (0, 300), (1, 120), (0, 400), (0, 60), (1, 450), (0, 250), (1, 250)]
    for dirn, v in seq:
        await h.write(R_VAL, 0, reg_value(dirn, v))
        await h.write(R_VAL, 1, reg_value(dirn, v))
        await h.wait_ns(per * 1.37)
    await h.wait_ns(2 * per)
    h.check()
    widths = {round(v * 65536 / 0xFFFF) for _, v in seq}
    p0 = _pulses(h, 0)
    assert len(p0) >= len(seq)
    rises = [r for r, _, _ in p0]
    for a, b in zip(rises, rises[1:]):
        n = (b - a) / per
        assert abs(n - round(n)) * clocks <= 1.01 and round(n) >= 1, (a, b, n)
    for r, f, pin in p0:
        assert min(abs((f - r) / PERIOD_HIGH - w) for w in widths) <= 1, (r, f, pin)
    # the pin follows DIR: Out0 for DIR = 1, Out1 for DIR = 0, in write order
    pins = [pin for _, _, pin in p0]
    runs = [pins[0]] + [b for a, b in zip(pins, pins[1:]) if a != b]
    want = [1 - d for d, _ in seq]
    want = [want[0]] + [b for a, b in zip(want, want[1:]) if a != b]
    assert runs == want, (runs, want)
    # immediate: some period's pulse ends on one pin and continues on the other
    p1 = _pulses(h, 1)
    split = [
        (a, b) for a, b in zip(p1, p1[1:]) if a[2] != b[2] and abs(b[0] - a[1]) < 1.5 * PERIOD_HIGH
    ]
    assert split, p1


@cocotb.test()
async def linuxcnc_driver_use(dut: Any) -> None:
    """As the 2.9 driver programs it (spec §10.3) at ClockHigh = 100 MHz:
    pwm_frequency 20 kHz -> 12 bits, dds 53687; output-type 1; value 0.3 and
    -0.6 of scale; enable bit; PDM (output-type 3) at 10 MHz."""
    h = Harness(dut)
    await h.start()
    f_req = 20000
    for bits in (12, 11, 10, 9):
        dds = int(f_req * 65536 * (1 << bits) / CLOCK_HIGH)
        if dds < 65536:
            break
    assert bits == 12 and dds == 53687
    pdm_dds = int(10e6 * 65536 / CLOCK_HIGH)
    await h.write(R_MODE, 0, (bits - 9) | (0 << 3) | 0x20)  # type 1: PWM/DIR, double buffer
    await h.write(R_MODE, 1, (12 - 9) | (3 << 3))  # type 3: PDM/DIR, no double buffer
    await h.write(R_PWMRATE, 0, dds)
    await h.write(R_PDMRATE, 0, pdm_dds)
    await h.write(R_ENABLE, 0, 0b11)

    def regval(s: float, b: int) -> int:
        v = abs(s) * ((1 << b) - 1)
        return (int(v * 65536) & 0x7FFFFFFF) | (0x80000000 if s < 0 else 0)

    f = pwm_frequency(CLOCK_HIGH, dds, bits - 9)
    assert abs(f - f_req) / f_req < 1e-3
    per = 1e9 / f
    for s in (0.3, -0.6):
        await h.write(R_VAL, 0, regval(s, bits))
        await h.write(R_VAL, 1, regval(s, 12))
        await h.settle()
        await h.wait_ns(1.2 * per)
        t_a = get_sim_time("ns")
        await h.wait_ns(per)
        t_b = get_sim_time("ns")
        m0 = DutyMeter(h.trace("pwm_out0", 0))
        assert abs(m0.duty(t_a, t_b) - abs(s)) < 0.002, (s, m0.duty(t_a, t_b))
        assert DutyMeter(h.trace("pwm_out1", 0)).duty(t_a, t_b) == (1 if s < 0 else 0)
        assert abs(DutyMeter(h.trace("pwm_out0", 1)).duty(t_a, t_b) - abs(s)) < 0.01
        ps = m0.periods(t_a - per, t_b)
        assert ps and abs(sum(ps) / len(ps) - per) < PERIOD_HIGH, (ps, per)
    assert int(dut.pwm_nenable.value) == 0
    h.check()


@pytest.mark.parametrize("sim", SIMULATORS)
def test_hm2_pwmgen(sim: str) -> None:
    run(
        sim=sim,
        toplevel="hm2_pwmgen_bank",
        sources=[
            hdl("common", "sync_ff.v"),
            hdl("hostmot2", "hm2_pwmgen.v"),
            hdl("hostmot2", "hm2_pwmgen_bank.v"),
        ],
        test_module="test_hm2_pwmgen",
        test_dir=Path(__file__).parent,
        parameters={"NUM": 2},
    )
