# SPDX-License-Identifier: GPL-2.0-or-later
"""The driver's maths (hm2_math_dump output) against an independent Python
model written from spec §10 (LinuxCNC 2.9 driver computations)."""

from __future__ import annotations

import math
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from conftest_paths import bin_path  # noqa: E402

DUMP = bin_path("hm2_math_dump")
pytestmark = pytest.mark.requires_build(DUMP)


@pytest.fixture(scope="module")
def rows() -> dict[str, list[list[str]]]:
    out = subprocess.run([str(DUMP)], capture_output=True, text=True, timeout=60, check=True)
    d: dict[str, list[list[str]]] = {}
    for line in out.stdout.splitlines():
        kind, *rest = line.split(",")
        d.setdefault(kind, []).append(rest)
    return d


# ---- StepGen (§10.1) ----
SCENARIOS = [
    (50, 10, 1.0, 0.001, 0),
    (0, 10, 1.0, 0.001, 0),
    (200, 3, -2.0, 0.001, 0),
    (20, 10, 0.5, 0.0005, 1),
    (1000, 100, 0.3, 0.002, 1),
    (0, 5, -0.7, 0.001, 1),
]


def position_control(
    cmd: float, old: float, fb: float, vfb: float, maxaccel: float, T: float
) -> float:
    ff = (cmd - old) / T
    verr = vfb - ff
    if verr > 0:
        ma = -verr / T if maxaccel == 0 else -maxaccel
    elif verr < 0:
        ma = verr / T if maxaccel == 0 else maxaccel  # "∓verr/T"
    else:
        ma = 0.0
    t_match = 0.0 if ma == 0 else -verr / ma
    pos_at = fb + (ff + vfb) / 2 * (t_match + T)
    cmd_at = cmd + ff * t_match
    err = pos_at - cmd_at
    if t_match < T:
        v = ff - 0.5 * err / T
        if maxaccel > 0:
            v = min(max(v, vfb - maxaccel * T), vfb + maxaccel * T)
        return v
    dv = -2.0 * ma * T
    dp = dv * t_match
    if abs(err + 2 * dp) < abs(err):
        ma = -ma
    return vfb + ma * T


def test_stepgen_trajectories(rows: dict[str, list[list[str]]]) -> None:
    got = rows["traj"]
    assert len(got) == 1500 * len(SCENARIOS)
    for k, (maxaccel, maxvel, target, T, ramp) in enumerate(SCENARIOS):
        pos = fb = vfb = old = 0.0
        for i in range(1500):
            cmd = target
            if ramp:
                r = 5.0 * i * T * (-1 if target < 0 else 1)
                cmd = max(r, target) if target < 0 else min(r, target)
            v = position_control(cmd, old, fb, vfb, maxaccel, T)
            v = min(max(v, -maxvel), maxvel)
            old, vfb, pos = cmd, v, pos + v * T
            fb = math.floor(pos * 1000.0) / 1000.0  # feedback in whole steps
            row = got[k * 1500 + i]
            assert int(row[0]) == k and int(row[1]) == i
            assert float(row[2]) == pytest.approx(v, rel=1e-9, abs=1e-9), (k, i)
            assert float(row[3]) == pytest.approx(pos, rel=1e-9, abs=1e-9), (k, i)
        assert pos == pytest.approx(target, abs=2e-3)  # every scenario arrives


def test_stepgen_timing_registers(rows: dict[str, list[list[str]]]) -> None:
    for clk, ns, reg, clip in rows["sgtime"]:
        exact = math.floor(Fraction(int(ns) * int(clk), 10**9))
        assert int(reg) == min(exact, 0x3FFF), (clk, ns)
        assert int(clip) == (exact > 0x3FFF)


def test_stepgen_rate_register(rows: dict[str, list[list[str]]]) -> None:
    for clk, v, s, reg in rows["sgrate"]:
        rate = float(v) * float(s) * 2**32 / int(clk)
        r = max(min(int(rate), 2**31 - 1), -(2**31))  # truncation toward 0, clamped
        assert int(reg) == r & 0xFFFFFFFF, (clk, v, s)


# ---- PWMGen (§10.3) ----
def test_pwm_rates(rows: dict[str, list[list[str]]]) -> None:
    for clk, f, bits, dds, clipped, pdm in rows["pwmrate"]:
        clk_i, f_i = int(clk), int(f)
        want = None
        for b in (12, 11, 10, 9):
            d = math.floor(Fraction(f_i * 65536 * 2**b, clk_i))
            if d < 65536:
                want = (b, d, 0)
                break
        if want is None:
            want = (9, 65535, 1)
        assert (int(bits), int(dds), int(clipped)) == want, (clk, f)
        p = math.floor(Fraction(f_i * 100 * 65536, clk_i))
        assert int(pdm) == min(max(p, 1), 65535), (clk, f)


def test_pwm_values(rows: dict[str, list[list[str]]]) -> None:
    for typ, bits, off, dither, val, reg in rows["pwmval"]:
        s = max(-1.0, min(1.0, float(val)))
        t = 1.0625 if int(dither) else 1.0
        pdm = int(typ) == 3
        if int(off):
            b = 11 if pdm else int(bits) - 1
            v = s * (2**b - t) + 2**b
        else:
            b = 12 if pdm else int(bits)
            v = abs(s) * (2**b - t)
        want = int(v * 65536) | (0x80000000 if s < 0 else 0)
        assert int(reg) == want, (typ, bits, off, dither, val)


# ---- Watchdog (§10.4) and encoder rates (§10.2) ----
def test_watchdog_timer(rows: dict[str, list[list[str]]]) -> None:
    for clk, ns, reg in rows["wd"]:
        v = int(ns) * (int(clk) / 1e9) - 1
        want = 0x7FFFFFFF if v >= 2**31 else max(0, int(v))
        assert int(reg) == want, (clk, ns)


def test_encoder_rates(rows: dict[str, list[list[str]]]) -> None:
    for clk, lo, hi in rows["tsdiv"]:
        assert int(lo) == max(int(clk) // 2_000_000 - 2, 0)
        assert int(hi) == max(int(clk) // 10_000_000 - 2, 0)
    for clk, f, reg, eff in rows["qfilter"]:
        c, fi = int(clk), int(f)
        div = c // fi if fi else 1
        if div <= 1:
            assert (int(reg), int(eff)) == (0xFFF, c)
        else:
            div = min(div, 0x7FF + 2)
            assert (int(reg), int(eff)) == (div - 2, c // div), (clk, f)


def wrap16(d: int) -> int:
    if d > 32768:
        return d - 65536
    if d < -32768:
        return d + 65536
    return d


def test_encoder_state_machine(rows: dict[str, list[list[str]]]) -> None:
    scale, tick, timeout = 4.0, 1e-6, 0.05
    prev_count, raw, state = 50000, 0, 0
    ev_raw = ev_ts = toi_prev = roll = prev_ds = 0
    vel = 0.0
    for i, count, ts, tsc, g_raw, g_vel, g_state in rows["enc"]:
        count, ts, tsc = int(count), int(ts), int(tsc)
        diff = wrap16(count - prev_count)
        raw += diff
        prev_count = count
        if state == 0:
            if diff:
                ev_raw, ev_ts, toi_prev, roll, prev_ds, state = raw, ts, ts, 0, 0, 1
        elif diff:
            toi = ts
            if toi < toi_prev:
                roll += 1
            ds = raw - ev_raw
            dt = (toi - ev_ts) + 65536 * roll
            if abs(ds) == 1 and prev_ds != 0 and (ds > 0) != (prev_ds > 0):
                vel = 0.0
            elif dt > 0:
                vel = (ds / scale) / (dt * tick)
            prev_ds, ev_raw, ev_ts, roll = ds, raw, toi, 0
            toi_prev = toi
        else:
            toi = tsc
            if toi < toi_prev:
                roll += 1
            dt_s = ((toi - ev_ts) + 65536 * roll) * tick
            if dt_s >= timeout:
                vel, state = 0.0, 0
            else:
                if dt_s > 0:
                    bound = abs(1.0 / scale) / dt_s
                    if bound < abs(vel):
                        vel = math.copysign(bound, vel)
                toi_prev = toi
        assert int(g_raw) == raw, i
        assert float(g_vel) == pytest.approx(vel, rel=1e-12, abs=1e-12), i
        assert int(g_state) == state, i
