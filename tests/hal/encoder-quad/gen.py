# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (not run by `make test`): writes test.hal and the streamed input
files of the encoder-quad and encoder-velocity regression tests from fixed
random seeds.  Their `expected` files are LinuxCNC 2.9's output of the same
test.hal (see each README); rerun this only together with a new recording.

    python3 tests/hal/encoder-quad/gen.py
"""

from __future__ import annotations

import random
from pathlib import Path

HERE = Path(__file__).resolve().parent
INS = ["phase-A", "phase-B", "phase-Z", "latch-input", "latch-rising", "latch-falling"]
INS += ["reset", "min-speed-estimate"]
IN_TYPE = {"min-speed-estimate": "f"}
OUTS = ["counts", "rawcounts", "position", "position-interpolated", "velocity", "velocity-rpm"]
OUTS += ["counts-latched", "position-latched", "index-enable"]
OUT_TYPE = {"counts": "s", "rawcounts": "s", "counts-latched": "s", "index-enable": "b"}
GRAY = [(0, 0), (1, 0), (1, 1), (0, 1)]


def rows(seed: int, n: int, counter: bool, speeds: list[float], mse: list[float]) -> list[list]:
    """An encoder turning at random speeds (counts per period), its index
    every 17 counts, a glitch (both phases flipped) now and then, random
    latch, reset and min-speed-estimate inputs."""
    r = random.Random(seed)
    out = []
    x, v = 0.0, 0.0
    lr, lf, lin, m = 1, 1, 0, 1.0
    for _ in range(n):
        if r.random() < 0.05:
            v = r.choice(speeds)
        x += v
        c = int(x // 1)
        if counter:
            a, b = (1 if x % 1.0 < 0.5 else 0), r.randint(0, 1)
        else:
            a, b = GRAY[c % 4]
        if r.random() < 0.01:
            a, b = 1 - a, 1 - b
        z = 1 if c % 17 == 0 else 0
        if r.random() < 0.05:
            lin = 1 - lin
        if r.random() < 0.02:
            lr = 1 - lr
        if r.random() < 0.02:
            lf = 1 - lf
        rst = 1 if r.random() < 0.02 else 0
        if r.random() < 0.02:
            m = r.choice(mse)
        out.append([a, b, z, lin, lr, lf, rst, m])
    return out


def write_test(name: str, comment: str, chans: list[dict], n: int) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    hal = [f"# {line}".rstrip() for line in comment.strip().splitlines()]
    hal.append("loadrt threads name1=t period1=1000000")
    hal.append(f"loadrt encoder num_chan={len(chans)}")
    cfg = "".join(IN_TYPE.get(p, "b") for p in INS)
    ocfg = "".join(OUT_TYPE.get(p, "f") for p in OUTS)
    hal.append(
        f"loadrt streamer depth={','.join([str(n + 4)] * len(chans))} cfg={','.join([cfg] * len(chans))}"
    )
    hal.append(
        f"loadrt sampler depth={','.join([str(n + 4)] * len(chans))} cfg={','.join([ocfg] * len(chans))}"
    )
    for k, ch in enumerate(chans):
        for j, p in enumerate(INS):
            hal.append(f"net e{k}-{p} streamer.{k}.pin.{j} => encoder.{k}.{p}")
        for j, p in enumerate(OUTS):
            hal.append(f"net e{k}-{p} encoder.{k}.{p} => sampler.{k}.pin.{j}")
        for p, v in ch.get("setp", {}).items():
            hal.append(f"setp encoder.{k}.{p} {v}")
        if ch.get("index"):
            hal.append(f"sets e{k}-index-enable 1")
    for k in range(len(chans)):
        hal.append(f"addf streamer.{k} t")
    hal += ["addf encoder.update-counters t", "addf encoder.capture-position t"]
    for k in range(len(chans)):
        hal.append(f"addf sampler.{k} t")
    for k, ch in enumerate(chans):
        lines = [
            " ".join(repr(float(v)) if IN_TYPE.get(p) else str(int(v)) for p, v in zip(INS, row))
            for row in ch["rows"]
        ]
        (d / f"in{k}.txt").write_text("\n".join(lines) + "\n")
        hal.append(f"loadusr -w halstreamer -c {k} in{k}.txt")
    hal.append("start")
    for k in range(len(chans)):
        hal.append(f"loadusr -w halsampler -c {k} -n {n}")
    hal.append("stop")
    hal += [f"show pin encoder.{k}.min-speed-estimate" for k in range(len(chans))]
    (d / "test.hal").write_text("\n".join(hal) + "\n")


def quad() -> None:
    speeds = [0, 0.3, -0.3, 1, -1, 0.05, -0.05, 0.7, 2.5, -2.5, 0.01]
    mse = [1.0, 0.1, 10.0, 100.0]
    cfgs: list[dict] = [
        {},
        {"index": 1},
        {"setp": {"x4-mode": 0}, "index": 1},
        {"setp": {"position-scale": -4.5}},
        {"counter": 1, "setp": {"counter-mode": 1}, "index": 1},
        {"setp": {"position-scale": 500}, "index": 1},
        {"setp": {"x4-mode": 0, "position-scale": -2}},
        {"counter": 1, "setp": {"counter-mode": 1, "x4-mode": 0, "position-scale": 2.5}},
    ]
    chans = [
        dict(c, rows=rows(8100 + k, 300, bool(c.get("counter")), speeds, mse))
        for k, c in enumerate(cfgs)
    ]
    write_test(
        "encoder-quad",
        """encoder: eight channels (x4, x1, counter mode, negative and fractional
position-scale) turned at random speeds with glitches, index pulses with
and without index-enable, latch-input with latch-rising/-falling, reset;
every output sampled each period.  test.hal from gen.py; expected recorded
from LinuxCNC 2.9 (README).""",
        chans,
        300,
    )


def velocity() -> None:
    speeds = [0, 0.5, -0.5, 1, 0.02, -0.02, 0.2, 3.0]
    mse = [0.0, -1.0, 1e-6, 1.0, 0.3]
    cfgs: list[dict] = [
        {},
        {"setp": {"position-scale": 0.001}},
        {"setp": {"position-scale": 0.004}},
        {"setp": {"position-scale": 1e-21}},
        {"setp": {"position-scale": -0.002, "x4-mode": 0}},
        {"setp": {"position-scale": 1000}},
        {"setp": {"x4-mode": 0}},
        {"setp": {"position-scale": 0}},
    ]
    chans = [dict(c, rows=rows(8200 + k, 300, False, speeds, mse)) for k, c in enumerate(cfgs)]
    write_test(
        "encoder-velocity",
        """encoder: the velocity estimate and position-interpolated at tiny, large,
negative, zero and near-zero position-scale, with min-speed-estimate 0
(taken as 1 and written back), negative (never estimates), tiny and
ordinary, and the pin values afterwards.  test.hal from ../encoder-quad/gen.py;
expected recorded from LinuxCNC 2.9 (README).""",
        chans,
        300,
    )


if __name__ == "__main__":
    quad()
    velocity()
