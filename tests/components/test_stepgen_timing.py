# SPDX-License-Identifier: GPL-2.0-or-later
"""stepgen's step timing with make-pulses and update-freq in threads of
different rates, on the simulated clock (something LinuxCNC's own output
cannot be recorded for: its threads interleave by chance).  The reference
is the timing rules of docs/stepgen.md: parameters rounded up to whole
make-pulses periods, a pulse exactly steplen long, steps at most
1 / (steplen + stepspace) apart, the direction output changing only
steplen + dirhold after the last step, the first step the other way only
steplen + dirhold + dirsetup after it (steplen + dirdelay for the other
step types)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from halsession import run, rows  # noqa: E402

pytestmark = pytest.mark.requires_build("lib/rtlib/stepgen.so", "lib/rtlib/sampler.so")

FAST = 25000  # ns
SERVO = 1000000


def session(step_type: int, params: dict[str, float], cmds: list[tuple[float, str]]) -> str:
    pins = ["step", "dir"] if step_type == 0 else ["phase-A", "phase-B"]
    n = sum(int(float(t[:-2]) * 1e6) // FAST for _, t in cmds)
    lines = [
        f"loadrt threads name1=fast period1={FAST} name2=servo period2={SERVO}",
        f"loadrt stepgen step_type={step_type} ctrl_type=v",
        f"loadrt sampler depth={n + 10} cfg=bbs",
        "addf stepgen.make-pulses fast",
        "addf sampler.0 fast",
        "addf stepgen.update-freq servo",
        "addf stepgen.capture-position servo",
        f"net a stepgen.0.{pins[0]} => sampler.0.pin.0",
        f"net b stepgen.0.{pins[1]} => sampler.0.pin.1",
        "net c stepgen.0.counts => sampler.0.pin.2",
        "setp stepgen.0.enable 1",
    ]
    lines += [f"setp stepgen.0.{k} {v}" for k, v in params.items()]
    for v, t in cmds:
        lines += [f"setp stepgen.0.velocity-cmd {v}", f"simrun {t}"]
    lines += [f"getp stepgen.0.{p}" for p in params] + ["getp stepgen.0.frequency"]
    lines.append(f"loadusr -w halsampler -n {n}")
    return "\n".join(lines) + "\n"


def rises(samples: list[list[str]], col: int) -> list[int]:
    return [i for i in range(1, len(samples)) if samples[i][col] == "1" != samples[i - 1][col]]


def test_step_dir_timing_in_a_fast_thread(tmp_path: Path) -> None:
    params = {"steplen": 60000, "stepspace": 40000, "dirhold": 30000, "dirsetup": 55000}
    out = run(tmp_path, session(0, params, [(20000, "50ms"), (-20000, "50ms")]))
    lines = out.splitlines()
    # rounded up to whole 25 us periods: 3, 2, 2 and 3 periods
    assert lines[:5] == ["75000", "50000", "50000", "75000", "-8000"]
    s = rows(out, 3)
    assert len(s) == 4000
    up = rises(s, 0)
    assert len(up) > 700
    for r in (r for r in up if r + 3 < len(s)):
        # every pulse exactly steplen (3 samples) long
        assert [x[0] for x in s[r : r + 4]] == ["1", "1", "1", "0"], r
        assert s[r][1] == s[r + 2][1], f"dir changed during the pulse at {r}"
    gaps = [b - a for a, b in zip(up, up[1:])]
    # never closer than steplen + stepspace; 5 periods = 8 kHz at full speed
    assert min(gaps) == 5 and gaps.count(5) > 600
    # one reversal: dir changes steplen + dirhold after the last forward
    # step, the first reverse step steplen + dirhold + dirsetup after it
    flips = [i for i in range(1, len(s)) if s[i][1] != s[i - 1][1]]
    assert len(flips) == 1
    last_fwd = max(r for r in up if r < flips[0])
    first_rev = min(r for r in up if r > flips[0])
    assert flips[0] - last_fwd >= 5
    assert first_rev - last_fwd >= 8
    # counts (captured each 1 ms servo period, so up to 8 steps late) peak
    # at the reversal and come back down by one per reverse step
    counts = [int(x[2]) for x in s]
    fwd = sum(1 for r in up if r < flips[0])
    rev = sum(1 for r in up if r > flips[0])
    assert max(counts) == fwd
    assert 0 <= counts[-1] - (fwd - rev) <= 8


def test_phase_outputs_and_dirdelay(tmp_path: Path) -> None:
    params = {"steplen": 30000, "dirdelay": 110000}
    out = run(tmp_path, session(2, params, [(50000, "10ms"), (-50000, "10ms")]))
    lines = out.splitlines()
    assert lines[:3] == ["50000", "125000", "-20000"]  # 2 and 5 periods; 1 / 50 us
    s = rows(out, 3)
    states = [(x[0], x[1]) for x in s]
    changes = [i for i in range(1, len(states)) if states[i] != states[i - 1]]
    # quadrature: one phase changes per step, at least steplen (2 samples) apart
    for i in changes:
        assert sum(a != b for a, b in zip(states[i], states[i - 1])) == 1
    assert min(b - a for a, b in zip(changes, changes[1:])) >= 2
    # forward order 10 11 01 00, then backwards after the reversal
    order = ["10", "11", "01", "00"]
    seq = ["".join(states[i]) for i in changes]
    steps = [(order.index(b) - order.index(a)) % 4 for a, b in zip(["".join(states[0])] + seq, seq)]
    assert set(steps) <= {1, 3}
    turn = steps.index(3)
    assert all(d == 1 for d in steps[:turn]) and all(d == 3 for d in steps[turn:])
    # first step the other way at least steplen + dirdelay (7 samples) later
    assert changes[turn] - changes[turn - 1] >= 7


def test_position_mode_respects_maxvel_and_maxaccel(tmp_path: Path) -> None:
    script = "\n".join(
        [
            f"loadrt threads name1=fast fp1=0 period1=50000 name2=servo period2={SERVO}",
            "loadrt stepgen step_type=0",
            "loadrt sampler depth=1010 cfg=fs",
            "addf stepgen.make-pulses fast",
            "addf stepgen.capture-position servo",
            "addf stepgen.update-freq servo",
            "addf sampler.0 servo",
            "net p stepgen.0.position-fb => sampler.0.pin.0",
            "net c stepgen.0.counts => sampler.0.pin.1",
            "setp stepgen.0.position-scale 100",
            "setp stepgen.0.maxvel 20",
            "setp stepgen.0.maxaccel 200",
            "setp stepgen.0.enable 1",
            "setp stepgen.0.position-cmd 3.0",
            "simrun 1s",
            "loadusr -w halsampler -n 1000",
        ]
    )
    s = rows(run(tmp_path, script + "\n"), 2)
    pos = [float(x[0]) for x in s]
    assert int(s[-1][1]) == 300 and abs(pos[-1] - 3.0) < 0.005
    vel = [(b - a) / 0.001 for a, b in zip(pos, pos[1:])]
    assert max(vel) <= 20.0 * 1.0001 and max(vel) > 19.9  # cruises at maxvel
    acc = [(b - a) / 0.001 for a, b in zip(vel, vel[1:])]
    assert max(abs(a) for a in acc) <= 200.0 * 1.05
    # a trapezoid: 0.1 s up, 0.05 s cruise, 0.1 s down: there by ~0.26 s
    assert next(i for i, p in enumerate(pos) if abs(p - 3.0) < 0.005) < 300
