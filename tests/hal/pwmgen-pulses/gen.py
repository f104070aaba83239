# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (not run by `make test`): writes test.hal and the streamed input
files of the pwmgen-pulses and pwmgen-edge regression tests from fixed
random seeds.  Their `expected` files are LinuxCNC 2.9's output of the same
test.hal (see each README); rerun this only together with a new recording.

    python3 tests/hal/pwmgen-pulses/gen.py
"""

from __future__ import annotations

import random
from pathlib import Path

HERE = Path(__file__).resolve().parent
OUTS = {0: ["pwm"], 1: ["pwm", "dir"], 2: ["up", "down"]}
VALUES = [
    0,
    0.5,
    -0.5,
    1,
    -1,
    0.1,
    0.25,
    0.9,
    0.33,
    2,
    -0.05,
    0.01,
    -0.99,
    0.999,
    1e-09,
]
ODD = VALUES + [float("nan"), float("inf"), float("-inf")]


def rows(seed: int, n: int, values: list[float]) -> list[tuple[float, int]]:
    """value held for a while then changed at random; enable mostly on,
    switched off now and then for a few periods."""
    r = random.Random(seed)
    out = []
    v, en = 0.0, 1
    for _ in range(n):
        if r.random() < 0.04:
            v = r.choice(values)
        if r.random() < (0.01 if en else 0.2):
            en = 1 - en
        out.append((v, en))
    if values is ODD:
        # a NaN, an inf and a -inf stretch, whatever the draw gave
        for start, x in (
            (120, float("nan")),
            (200, float("inf")),
            (280, float("-inf")),
        ):
            for i in range(start, start + 15):
                out[i] = (x, 1)
    return out


def write_test(
    name: str, comment: str, chans: list[dict], n: int, period: int, funcs: list[str]
) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    hal = [f"# {line}".rstrip() for line in comment.strip().splitlines()]
    hal.append(f"loadrt threads name1=t period1={period}")
    hal.append(f"loadrt pwmgen output_type={','.join(str(c['type']) for c in chans)}")
    hal.append(
        f"loadrt streamer depth={','.join([str(n + 4)] * len(chans))} cfg={','.join(['fb'] * len(chans))}"
    )
    ocfgs = ["ffff" + "b" * len(OUTS[c["type"]]) for c in chans]
    hal.append(f"loadrt sampler depth={','.join([str(n + 4)] * len(chans))} cfg={','.join(ocfgs)}")
    for k, c in enumerate(chans):
        hal.append(f"net p{k}-value streamer.{k}.pin.0 => pwmgen.{k}.value")
        hal.append(f"net p{k}-enable streamer.{k}.pin.1 => pwmgen.{k}.enable")
        outs = ["curr-dc", "pwm-freq", "max-dc", "min-dc"] + OUTS[c["type"]]
        for j, p in enumerate(outs):
            hal.append(f"net p{k}-{p} pwmgen.{k}.{p} => sampler.{k}.pin.{j}")
        for p, v in c["setp"].items():
            hal.append(f"sets p{k}-{p} {v}" if p in outs else f"setp pwmgen.{k}.{p} {v}")
    for k in range(len(chans)):
        hal.append(f"addf streamer.{k} t")
    hal += [f"addf pwmgen.{f} t" for f in funcs]
    for k in range(len(chans)):
        hal.append(f"addf sampler.{k} t")
    for k, c in enumerate(chans):
        (d / f"in{k}.txt").write_text("".join(f"{v!r} {e}\n" for v, e in c["rows"]))
        hal.append(f"loadusr -w halstreamer -c {k} in{k}.txt")
    hal.append("start")
    for k in range(len(chans)):
        hal.append(f"loadusr -w halsampler -c {k} -n {n}")
    hal.append("stop")
    # after stop the outputs depend on when it came; scale was written back by then
    hal += [f"show pin pwmgen.{k}.scale" for k in range(len(chans))]
    (d / "test.hal").write_text("\n".join(hal) + "\n")


def pulses() -> None:
    cfgs = [
        (0, {"pwm-freq": 1000, "max-dc": 0.8, "min-dc": 0.2}),
        (
            1,
            {"pwm-freq": 1000, "max-dc": 0.8, "min-dc": 0.2, "scale": 2, "offset": 0.1},
        ),
        (2, {"pwm-freq": 0, "scale": -3, "offset": -0.3}),
        (1, {"pwm-freq": 0, "max-dc": 1.5, "min-dc": -0.2}),
        (1, {"pwm-freq": 700, "dither-pwm": 1}),
        (1, {"pwm-freq": 700, "scale": 0}),
        (1, {"pwm-freq": 1300, "dither-pwm": 1}),
        (2, {"pwm-freq": 1e6}),
    ]
    chans = [
        dict(type=t, setp=s, rows=rows(9100 + k, 400, VALUES)) for k, (t, s) in enumerate(cfgs)
    ]
    write_test(
        "pwmgen-pulses",
        """pwmgen: eight channels of the three output types, pure PWM (1 kHz;
700 Hz rounded to whole periods: 714.29 Hz), dithered PWM (700 and 1300
Hz), PDM (pwm-freq 0) and a pwm-freq above the limit (5 kHz at 100 us);
min-dc/max-dc limits, out-of-range ones corrected and written back,
scale 2 set before the first update (2.9 then ignores value), negative
and zero scale, offset; value and enable streamed, every output sampled
each period.  make-pulses runs before update.  test.hal from gen.py;
expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        400,
        100000,
        ["make-pulses", "update"],
    )


def edge() -> None:
    cfgs = [
        (0, {"pwm-freq": 333, "dither-pwm": 1, "offset": 0.2}),
        (1, {"pwm-freq": 2500, "dither-pwm": 1}, ODD),
        (2, {"pwm-freq": 2500}, ODD),
        (1, {"pwm-freq": 0}, ODD),
        (0, {"pwm-freq": 1000}, ODD),
        (1, {"pwm-freq": 0.3, "min-dc": 0.7, "max-dc": 0.4}),
        (2, {"pwm-freq": -5, "scale": 1e-21}),
        (0, {"pwm-freq": 10, "min-dc": 0.5}),
    ]
    chans = [
        dict(
            type=c[0],
            setp=c[1],
            rows=rows(9200 + k, 400, c[2] if len(c) > 2 else VALUES),
        )
        for k, c in enumerate(cfgs)
    ]
    write_test(
        "pwmgen-edge",
        """pwmgen: NaN and infinite values (NaN: a high time of INT_MIN, curr-dc
INT_MIN / 27 in pure PWM at 1 kHz), pwm-freq below 0.5 Hz, negative,
min-dc above max-dc, a scale below 1e-20 (taken as 1); a 37 us period.  test.hal from
../pwmgen-pulses/gen.py; expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        400,
        37000,
        ["make-pulses", "update"],
    )


def first() -> None:
    cfgs = [
        (0, {"pwm-freq": 1000}),
        (1, {"pwm-freq": 700, "dither-pwm": 1}),
        (2, {"pwm-freq": 0}),
        (0, {"pwm-freq": 10, "min-dc": 0.5}),
    ]
    chans = [dict(type=t, setp=s, rows=rows(9300 + k, 60, VALUES)) for k, (t, s) in enumerate(cfgs)]
    write_test(
        "pwmgen-first",
        """pwmgen: update runs before make-pulses, so its first call sees no
make-pulses period yet: 2.9 then clamps a pwm-freq above 0 to -5e8 and,
one period later, to 0 (PDM from then on).  test.hal from
../pwmgen-pulses/gen.py; expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        60,
        100000,
        ["update", "make-pulses"],
    )


if __name__ == "__main__":
    pulses()
    edge()
    first()
