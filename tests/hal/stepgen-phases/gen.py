# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (not run by `make test`): writes test.hal and the streamed input
files of the stepgen-* regression tests (stepgen-phases, stepgen-timing,
stepgen-position, stepgen-edge) from fixed random seeds.  Their `expected`
files are LinuxCNC 2.9's output of the same test.hal (see each README);
rerun this only together with a new recording.

    python3 tests/hal/stepgen-phases/gen.py
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
TYPE_CODE = {"float": "f", "bit": "b", "s32": "s"}
PHASES = {2: 2, 3: 3, 4: 3, 5: 4, 6: 4, 7: 4, 8: 4, 9: 4, 10: 4, 11: 5, 12: 5, 13: 5, 14: 5}
ORDER = ("make-pulses", "capture-position", "update-freq")


@dataclass
class Chan:
    """One stepgen channel: its type, mode, parameters and command rows."""

    step_type: int
    pos_mode: bool
    rows: list[tuple[float, int]]
    params: dict[str, float] = field(default_factory=dict)
    phases: int = 0

    def outs(self) -> list[tuple[str, str]]:
        pins = [("float", "position-fb"), ("s32", "counts")]
        if self.step_type == 0:
            pins += [("bit", "step"), ("bit", "dir")]
        elif self.step_type == 1:
            pins += [("bit", "up"), ("bit", "down")]
        else:
            n = self.phases or PHASES[self.step_type]
            pins += [("bit", "phase-" + "ABCDE"[i]) for i in range(n)]
        return pins


def write_test(
    name: str,
    comment: str,
    chans: list[Chan],
    period: int = 1000000,
    user: str = "",
    order: tuple[str, ...] = ORDER,
    show: tuple[str, ...] = (),
) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    n = len(chans[0].rows)
    hal = [f"# {line}".rstrip() for line in comment.strip().splitlines()]
    hal.append(f"loadrt threads name1=t period1={period}")
    load = "loadrt stepgen step_type=%s ctrl_type=%s" % (
        ",".join(str(c.step_type) for c in chans),
        ",".join("p" if c.pos_mode else "v" for c in chans),
    )
    hal.append(load + (f" user_step_type={user}" if user else ""))
    ins = []
    outs = []
    for k, c in enumerate(chans):
        ins += [
            (k, "float", "position-cmd" if c.pos_mode else "velocity-cmd"),
            (k, "bit", "enable"),
        ]
        outs += [(k, t, p) for t, p in c.outs()]
    streams = [ins[i : i + 20] for i in range(0, len(ins), 20)]
    samples = [outs[i : i + 20] for i in range(0, len(outs), 20)]
    depth = n + 4
    hal.append(
        "loadrt streamer depth=%s cfg=%s"
        % (
            ",".join(str(depth) for _ in streams),
            ",".join("".join(TYPE_CODE[t] for _, t, _ in s) for s in streams),
        )
    )
    hal.append(
        "loadrt sampler depth=%s cfg=%s"
        % (
            ",".join(str(depth) for _ in samples),
            ",".join("".join(TYPE_CODE[t] for _, t, _ in s) for s in samples),
        )
    )
    for ci, s in enumerate(streams):
        for j, (k, _, p) in enumerate(s):
            hal.append(f"net c{k}-{p} streamer.{ci}.pin.{j} => stepgen.{k}.{p}")
    for ci, s in enumerate(samples):
        for j, (k, _, p) in enumerate(s):
            hal.append(f"net c{k}-{p} stepgen.{k}.{p} => sampler.{ci}.pin.{j}")
    for k, c in enumerate(chans):
        for p, v in c.params.items():
            hal.append(f"setp stepgen.{k}.{p} {v}")
    for ci in range(len(streams)):
        hal.append(f"addf streamer.{ci} t")
    for f in order:
        hal.append(f"addf stepgen.{f} t")
    for ci in range(len(samples)):
        hal.append(f"addf sampler.{ci} t")
    for ci, s in enumerate(streams):
        lines = []
        for r in range(n):
            vals = []
            for k, t, p in s:
                v = chans[k].rows[r][0 if t == "float" else 1]
                vals.append(str(int(v)) if t == "bit" else repr(float(v)))
            lines.append(" ".join(vals))
        (d / f"in{ci}.txt").write_text("\n".join(lines) + "\n")
        hal.append(f"loadusr -w halstreamer -c {ci} in{ci}.txt")
    hal.append("start")
    for ci in range(len(samples)):
        hal.append(f"loadusr -w halsampler -c {ci} -n {n}")
    hal.append("stop")
    hal.extend(show)
    (d / "test.hal").write_text("\n".join(hal) + "\n")


def phases() -> None:
    chans = []
    for t in range(2, 16):
        rows = [(500.0, 1)] * 30 + [(-500.0, 1)] * 30 + [(1000.0, 1)] * 12 + [(-1000.0, 1)] * 30
        chans.append(Chan(t, False, rows, phases=3 if t == 15 else 0))
    write_test(
        "stepgen-phases",
        """stepgen: the output patterns of step types 2-14 and of a user pattern
(type 15, user_step_type=1,3,2,6,4,5): velocity mode, forwards then back
past zero, every phase sampled each period.  test.hal from gen.py;
expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        user="1,3,2,6,4,5",
    )


def velocity_rows(r: random.Random, n: int) -> list[tuple[float, int]]:
    speeds = [100, -100, 250, -250, 333.3, -500, 1000, -1000, 120, -75, 50, -50, 0]
    rows, v, en = [], 0.0, 1
    for i in range(n - 12):
        if r.random() < 0.08:
            v = r.choice(speeds)
        if r.random() < (0.004 if en else 0.2):
            en = 1 - en
        rows.append((v, en))
    return rows + [(0.0, 1)] * 12


def timing_params(r: random.Random, t: int, period: int) -> dict[str, float]:
    def mult() -> int:
        return r.choice([1, 1, 2, 3, 4]) * period - r.choice([0, 0, 0, period // 3])

    p: dict[str, float] = {"steplen": mult(), "maxaccel": r.choice([0, 0, 20000, 5000])}
    if t < 2:
        p["stepspace"] = r.choice([0, period, 2 * period, period // 2])
    if t == 0:
        p["dirsetup"] = r.choice([0, mult()])
        p["dirhold"] = mult()
    else:
        p["dirdelay"] = r.choice([0, 1, period, 2 * period, 3 * period])
    return p


TIMING_SHOW = tuple(
    f"show param stepgen.{k}.{p}"
    for k in range(8)
    for p in ("steplen", "stepspace", "dirsetup", "dirhold", "dirdelay")
)


def timing() -> None:
    r = random.Random(7001)
    period = 250000
    types = [0, 0, 0, 0, 1, 1, 2, 3]
    chans = [Chan(t, False, velocity_rows(r, 250), timing_params(r, t, period)) for t in types]
    write_test(
        "stepgen-timing",
        """stepgen: steplen, stepspace, dirsetup, dirhold and dirdelay (whole and
fractional periods, 0) in a 250 us thread: step/dir, up/down and phase
outputs of random velocity commands with reversals and enable dropouts;
the rounded parameters afterwards.  test.hal from ../stepgen-phases/gen.py;
expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        period=period,
        show=TIMING_SHOW,
    )


def position_rows(r: random.Random, n: int) -> list[tuple[float, int]]:
    rows, p, v, en = [], 0.0, 0.0, 1
    for i in range(n - 40):
        x = r.random()
        if x < 0.05:
            p = round(r.uniform(-30, 30), 3)
        elif x < 0.1:
            v = r.choice([0, 0, 0.05, -0.1, 0.3, -0.02])
        p += v
        if r.random() < (0.004 if en else 0.2):
            en = 1 - en
        rows.append((round(p, 6), en))
    return rows + [(round(p, 6), 1)] * 40


def position() -> None:
    r = random.Random(7002)
    types = [0, 0, 0, 1, 2, 4, 15, 0]
    chans = []
    for t in types:
        scale = r.choice([1, 2.5, -3, 0.7, 10])
        params = {
            "maxaccel": r.choice([0, 5000, 20000.5, 1000, 300]),
            # within what 1 ms steps allow (else 2.9 prints a message)
            "maxvel": r.choice([0, 400, 200, 50, 1000]) * (0.5 if t < 2 else 1.0) / abs(scale),
            "position-scale": scale,
        }
        chans.append(Chan(t, True, position_rows(r, 300), params, phases=2 if t == 15 else 0))
    write_test(
        "stepgen-position",
        """stepgen: position mode (its position loop with maxvel, maxaccel,
negative and fractional position-scale) following steps and ramps of the
position command, with enable dropouts; update-freq runs first in the
thread.  test.hal from ../stepgen-phases/gen.py; expected recorded from
LinuxCNC 2.9 (README).""",
        chans,
        user="1,2",
        order=("update-freq", "make-pulses", "capture-position"),
        show=tuple(
            f"show param stepgen.{k}.{p}"
            for k in range(8)
            for p in ("maxvel", "maxaccel", "position-scale")
        ),
    )


def edge() -> None:
    rows = [(100.0, 1)] * 20 + [(-300.0, 1)] * 20 + [(50.0, 1)] * 20 + [(0.0, 1)] * 10
    params: list[dict[str, float]] = [
        {"maxvel": -100},
        {"maxaccel": -5000},
        {"position-scale": 0.0},
        {"position-scale": 1e-21},
        {"steplen": 0, "stepspace": 0, "dirsetup": 0, "dirhold": 0},
        {"maxvel": -5000, "maxaccel": -200000},
        {"maxaccel": 1e12},
        {"position-scale": -1e-21},
    ]
    write_test(
        "stepgen-edge",
        """stepgen: parameters out of range: negative maxvel and maxaccel (set to
0 by 2.9, no message), position-scale 0 (no motion) and +-1e-21 (replaced
by 1), zero timing parameters, a maxaccel above what the timing allows
(lowered); the parameters afterwards.  test.hal from
../stepgen-phases/gen.py; expected recorded from LinuxCNC 2.9 (README).""",
        [Chan(0, False, rows, p) for p in params],
        show=tuple(
            f"show param stepgen.{k}.{p}"
            for k in range(8)
            for p in ("maxvel", "maxaccel", "position-scale", "steplen", "dirhold")
        ),
    )


if __name__ == "__main__":
    phases()
    timing()
    position()
    edge()
