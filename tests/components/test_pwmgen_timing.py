# SPDX-License-Identifier: GPL-2.0-or-later
"""pwmgen's pulses with make-pulses in a fast thread and update in a
slower one, on the simulated clock (LinuxCNC's threads interleave by
chance, so this cannot be recorded from 2.9).  The reference is
docs/pwmgen.md: pure PWM periods and high times in whole make-pulses
periods, dithered PWM averaging the exact duty cycle, PDM spreading the
high periods evenly, up/down and dir following the sign of value."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from halsession import run, rows  # noqa: E402

pytestmark = pytest.mark.requires_build("lib/rtlib/pwmgen.so", "lib/rtlib/sampler.so")

FAST = 25000  # ns
SERVO = 1000000
N = 8000  # 200 ms of fast periods


def session(setp: list[str], value: float, value2: float) -> str:
    lines = [
        f"loadrt threads name1=fast period1={FAST} name2=servo period2={SERVO}",
        "loadrt pwmgen output_type=0,1,2,0",
        f"loadrt sampler depth={N + 10} cfg=bbbbbb",
        "addf pwmgen.make-pulses fast",
        "addf sampler.0 fast",
        "addf pwmgen.update servo",
    ]
    for j, p in enumerate(["0.pwm", "1.pwm", "1.dir", "2.up", "2.down", "3.pwm"]):
        lines.append(f"net s{j} pwmgen.{p} => sampler.0.pin.{j}")
    lines += [f"setp pwmgen.{k}.enable 1" for k in range(4)]
    lines += setp
    lines += [f"setp pwmgen.{k}.value {value}" for k in range(4)]
    lines.append("simrun 100ms")
    lines += [f"setp pwmgen.{k}.value {value2}" for k in range(4)]
    lines.append("simrun 100ms")
    lines += [
        "getp pwmgen.0.pwm-freq",
        "getp pwmgen.0.curr-dc",
        "getp pwmgen.3.pwm-freq",
    ]
    lines.append(f"loadusr -w halsampler -n {N}")
    return "\n".join(lines) + "\n"


def runs(col: list[str]) -> list[tuple[str, int]]:
    out: list[tuple[str, int]] = []
    for v in col:
        if out and out[-1][0] == v:
            out[-1] = (v, out[-1][1] + 1)
        else:
            out.append((v, 1))
    return out


def test_pure_pwm_dither_and_pdm(tmp_path: Path) -> None:
    setp = [
        "setp pwmgen.0.pwm-freq 1000",
        "setp pwmgen.1.pwm-freq 1300",
        "setp pwmgen.1.dither-pwm 1",
        "setp pwmgen.2.pwm-freq 0",
        "setp pwmgen.3.pwm-freq 30000",
    ]
    out = run(tmp_path, session(setp, 0.25, -0.3))
    head = out.splitlines()[:3]
    # 1 kHz is 40 fast periods; 30 kHz is above 1 / (2 x 25 us): 20 kHz
    assert head == ["1000", "0", "20000"]
    s = rows(out, 6)
    assert len(s) == N
    first = s[: N // 2]
    start = next(i for i, r in enumerate(first) if r[0] == "1")
    # pure PWM: 10 periods high, 30 low, every 1 ms
    pure = runs([r[0] for r in first[start : start + 3200]])
    assert pure == [("1", 10), ("0", 30)] * 80
    # dithered 1300 Hz at 25%: 8 ms hold about 2 ms high in all
    assert abs(sum(r[1] == "1" for r in first[400:720]) - 80) <= 2
    assert all(r[2] == "0" for r in first[400:])  # dir: positive
    # PDM at 25%: one period high in every four, evenly
    pdm = [r[3] for r in first[400:]]
    assert pdm[:8] in (
        ["1", "0", "0", "0"] * 2,
        ["0", "1", "0", "0"] * 2,
        ["0", "0", "1", "0"] * 2,
        ["0", "0", "0", "1"] * 2,
    )
    assert pdm.count("1") == len(pdm) // 4
    assert all(r[4] == "0" for r in first[400:])
    # 20 kHz: two fast periods, 25% rounds to one of them
    assert set(runs([r[5] for r in first[400:]])) == {("0", 1), ("1", 1)}
    second = s[N // 2 + 80 :]
    # -0.3 on a pwm-only output is 0: never high; dir, down follow the sign
    assert all(r[0] == "0" for r in second)
    assert all(r[2] == "1" for r in second)
    assert all(r[3] == "0" for r in second)
    assert abs(sum(r[4] == "1" for r in second) - 0.3 * len(second)) <= 2
