# SPDX-License-Identifier: GPL-2.0-or-later
"""Both clocks with their exact ratio, measured on the pins: stepgen pulses in
ClockLow periods (5i20: ClockHigh/3, 5i25: ClockHigh/6) and PWM in ClockHigh
periods (spec §9.4, §9.6: PWMCLK = ClockHigh * rate / 65536, 9-bit sawtooth,
output high while the reference is below the value)."""

from __future__ import annotations

from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common and tools/vbfw on sys.path)
from vbhelpers import fw_json, stop_clean
from vboard import VBoardProcess


def _pin(desc: dict, module: str, unit: int, signal: str) -> int:
    for p in desc["pins"]:
        if (p["sec_module"], p["sec_unit"], p["sec_signal"]) == (module, unit, signal):
            return int(p["io"])
    raise LookupError(f"{module} {unit} {signal} not in the pin-out")


@pytest.mark.parametrize("board,fw", [("5i20", "SVST8_4"), ("5i25", "7I76x2")])
def test_stepgen_pulse_timing_in_clocklow_periods(sockdir: Path, board: str, fw: str) -> None:
    desc = fw_json(board, fw)
    hi, lo = desc["clocks"]["high_hz"], desc["clocks"]["low_hz"]
    t_low = 1e9 / hi * round(hi / lo)  # exactly R ClockHigh periods
    step = _pin(desc, "StepGen", 0, "Step")
    port, bit = divmod(step, desc["board"]["port_width"])
    p = VBoardProcess(sockdir / "b.sock", board, fw)
    try:
        with p.client() as c:
            c.write(0x1200 + 4 * port, 1 << bit)  # AltSource
            c.write(0x1100 + 4 * port, 1 << bit)  # DDR
            pw, idle = 3, 2  # (pw+1)+(idle+1) = 7 <= 8 clocks per step
            c.write_bursts([(0x2200, [0]), (0x2500, [pw]), (0x2600, [idle]), (0x2000, [1 << 29])])
            c.write(0x2900, 0xFFFFFFFF)  # a tick every ClockLow (but one in 2^32)
            c.advance(50_000)
            c.probe_reset(step)
            c.advance(200_000)
            s = c.pin(step)
        period = 8 * t_low  # rate 1/8 step per tick
        assert s.period_ns == pytest.approx(period, abs=1)
        assert s.last_high_ns == pytest.approx((pw + 1) * t_low, abs=1)
        assert s.min_high_ns == s.last_high_ns
        assert s.rising == pytest.approx(200_000 / period, abs=1)
    finally:
        stop_clean(p)


def test_pwm_in_clockhigh_periods(sockdir: Path) -> None:
    desc = fw_json("5i20", "SVST8_4")
    t_high = 1e9 / desc["clocks"]["high_hz"]
    out0 = _pin(desc, "PWMGen", 0, "Out0")
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    try:
        with p.client() as c:
            c.write(0x1200, 1 << out0)
            c.write(0x1100, 1 << out0)
            rate = 32768  # PWMCLK = ClockHigh / 2
            value = 128  # of 512 (9-bit sawtooth)
            c.write_bursts(
                [(0x4100, [0]), (0x4200, [rate]), (0x4000, [value << 16]), (0x4400, [1])]
            )
            c.advance(50_000)
            c.probe_reset(out0)
            c.advance(102_400)
            s = c.pin(out0)
        tick = t_high * 65536 / rate
        assert s.period_ns == pytest.approx(512 * tick, abs=0.5)
        assert s.last_high_ns == pytest.approx(value * tick, abs=0.5)
        assert s.min_low_ns == pytest.approx((512 - value) * tick, abs=0.5)
        assert s.rising == pytest.approx(10, abs=1)
        assert s.duty == pytest.approx(value / 512, abs=0.02)
    finally:
        stop_clean(p)
