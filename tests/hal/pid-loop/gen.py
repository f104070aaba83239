# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (not run by `make test`): writes test.hal and the streamed input
files of the pid-* regression tests (pid-loop, pid-deriv, pid-special,
pid-tune) from fixed random seeds.  Their `expected` files are LinuxCNC 2.9's
output of the same test.hal (see each README); rerun this only together
with a new recording.

    python3 tests/hal/pid-loop/gen.py
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
TYPE_CODE = {"float": "f", "bit": "b", "s32": "s", "u32": "u"}
BITS = {"enable", "index-enable", "error-previous-target", "tune-mode"}
GAINS = ["Pgain", "Igain", "Dgain", "bias", "FF0", "FF1", "FF2", "FF3"]
LIMITS = ["deadband", "maxerror", "maxerrorI", "maxerrorD", "maxcmdD", "maxcmdDD", "maxcmdDDD"]
LIMITS += ["maxoutput"]
OUTS = ["output", "error", "errorI", "errorD", "commandD", "commandDD", "commandDDD"]
OUTS += ["saturated", "saturated-s", "saturated-count"]
OUT_TYPE = {"saturated": "bit", "saturated-count": "s32", "tune-start": "bit"}


@dataclass
class Chan:
    """One pid instance fed by streamer channels and read by one sampler."""

    pid: str
    ins: list[str]
    outs: list[str]
    rows: list[list[float]]
    pre: list[str] = field(default_factory=list)


def pin_type(name: str) -> str:
    return "bit" if name in BITS else "float"


def fmt(v: float) -> str:
    if v != v:
        return "nan"
    if isinstance(v, int):
        return str(v)
    return repr(float(v))


def write_test(
    name: str,
    comment: str,
    load: str,
    chans: list[Chan],
    period: int = 1000000,
    before_start: tuple[str, ...] = (),
) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    hal = [f"# {line}".rstrip() for line in comment.strip().splitlines()]
    hal.append(f"loadrt threads name1=t period1={period}")
    hal.append(load)
    streams: list[tuple[int, list[str]]] = []
    for k, c in enumerate(chans):
        for i in range(0, len(c.ins), 20):
            streams.append((k, c.ins[i : i + 20]))
    depth = max(len(c.rows) for c in chans) + 4
    hal.append(
        "loadrt streamer depth=%s cfg=%s"
        % (
            ",".join(str(depth) for _ in streams),
            ",".join("".join(TYPE_CODE[pin_type(p)] for p in s) for _, s in streams),
        )
    )
    hal.append(
        "loadrt sampler depth=%s cfg=%s"
        % (
            ",".join(str(depth) for _ in chans),
            ",".join("".join(TYPE_CODE[OUT_TYPE.get(p, "float")] for p in c.outs) for c in chans),
        )
    )
    for ch, (k, pins) in enumerate(streams):
        for j, p in enumerate(pins):
            hal.append(f"net {chans[k].pid}-{p} streamer.{ch}.pin.{j} => {chans[k].pid}.{p}")
    for k, c in enumerate(chans):
        for j, p in enumerate(c.outs):
            hal.append(f"net {c.pid}-{p} {c.pid}.{p} => sampler.{k}.pin.{j}")
        hal.extend(c.pre)
    for ch in range(len(streams)):
        hal.append(f"addf streamer.{ch} t")
    for c in chans:
        hal.append(f"addf {c.pid}.do-pid-calcs t")
    for k in range(len(chans)):
        hal.append(f"addf sampler.{k} t")
    for ch, (k, pins) in enumerate(streams):
        c = chans[k]
        first = c.ins.index(pins[0])
        lines = [
            " ".join(
                str(int(v)) if pin_type(p) == "bit" else fmt(v)
                for p, v in zip(pins, r[first : first + len(pins)])
            )
            for r in c.rows
        ]
        (d / f"in{ch}.txt").write_text("\n".join(lines) + "\n")
        hal.append(f"loadusr -w halstreamer -c {ch} in{ch}.txt")
    hal.extend(before_start)
    hal.append("start")
    for k, c in enumerate(chans):
        hal.append(f"loadusr -w halsampler -c {k} -n {len(c.rows)}")
    (d / "test.hal").write_text("\n".join(hal) + "\n")


def random_rows(
    r: random.Random, n: int, ins: list[str], special: str = "", start: dict | None = None
) -> list[list[float]]:
    cur = {p: 0.0 for p in ins}
    cur.update({"enable": 1, "Pgain": 1.0, "error-previous-target": 1})
    cur.update(start or {})
    rows = []
    for _ in range(n):
        for p in ins:
            if r.random() >= (0.5 if p in ("command", "feedback") else 0.08):
                continue
            if p in BITS:
                cur[p] = 1 - cur[p] if r.random() < 0.7 else cur[p]
            elif p in LIMITS:
                cur[p] = r.choice([0, 0, 0.5, 1, 2, 5, 1000, 3000])
            elif p in ("command", "feedback", "command-deriv", "feedback-deriv"):
                cur[p] = round(r.uniform(-5, 5), r.choice([0, 1, 3]))
            else:
                cur[p] = r.choice([0, 0, 1, 0.5, 2, -1, 0.01, 0.001, 10])
        row = [cur[p] for p in ins]
        if special and r.random() < 0.1:
            j = r.choice([i for i, p in enumerate(ins) if p not in BITS])
            row[j] = r.choice([float(s) for s in special.split(",")])
        rows.append(row)
    return rows


def loop_inputs(deriv: str = "") -> list[str]:
    ins = ["command", "feedback", "enable", "index-enable", "error-previous-target"]
    ins += GAINS + LIMITS
    if "c" in deriv:
        ins.append("command-deriv")
    if "f" in deriv:
        ins.append("feedback-deriv")
    return ins


def pid_loop() -> None:
    r = random.Random(9001)
    ins = loop_inputs()
    write_test(
        "pid-loop",
        """pid: 250 periods of a 1 kHz loop with every input streamed (gains,
limits, deadband, enable, index-enable, error-previous-target) and every
output sampled.  Inputs from ../pid-loop/gen.py; expected recorded from
LinuxCNC 2.9 (README).""",
        "loadrt pid num_chan=1 debug=1",
        [Chan("pid.0", ins, OUTS, random_rows(r, 250, ins))],
    )


def pid_deriv() -> None:
    r = random.Random(9002)
    both, cmd_only = loop_inputs("cf"), loop_inputs("c")
    write_test(
        "pid-deriv",
        """pid: command-deriv and feedback-deriv connected (a: both, b: only
command-deriv; the other is estimated from feedback), 150 periods each;
the pins of a loop made with names= and debug=1 (errorI ... commandDDD,
ultimate-gain, ultimate-period).  Inputs from ../pid-loop/gen.py; expected
recorded from LinuxCNC 2.9.""",
        "loadrt pid names=a,b debug=1",
        [
            Chan("a", both, OUTS, random_rows(r, 150, both)),
            Chan("b", cmd_only, OUTS, random_rows(r, 150, cmd_only)),
        ],
        before_start=("show pin b",),
    )


def pid_special() -> None:
    r = random.Random(9003)
    ins = loop_inputs()
    write_test(
        "pid-special",
        """pid: infinite inputs (a) and NaN inputs (b) now and then in any float
input, 150 periods each, at a 250 us period.  Inputs from
../pid-loop/gen.py; expected recorded from LinuxCNC 2.9.""",
        "loadrt pid names=a,b debug=1",
        [
            Chan("a", ins, OUTS, random_rows(r, 150, ins, "inf,-inf")),
            Chan("b", ins, OUTS, random_rows(r, 150, ins, "nan")),
        ],
        period=250000,
    )


def tune_rows(r: random.Random, n: int, drop: str) -> list[list[float]]:
    """command, feedback, enable, tune-mode, bias: a feedback that swings
    around the command with a random period, so the relay oscillates."""
    rows = []
    cmd, bias = 0.0, 0.0
    amp, per = r.uniform(0.5, 3), r.randint(3, 12)
    for i in range(n):
        if r.random() < 0.05:
            cmd = round(r.uniform(-1, 1), 3)
        if r.random() < 0.05:
            bias = r.choice([0, 0.1, -0.2, 0.5])
        side = 1 if (i // per) % 2 == 0 else -1
        fb = round(cmd + amp * side * r.uniform(0.2, 1.0) + r.uniform(-0.3, 0.3), 3)
        enable = 0 if drop == "enable" and 60 <= i < 65 else 1
        mode = 0 if (drop == "mode" and 60 <= i < 65) or i < 3 else 1
        rows.append([cmd, fb, enable, mode, bias])
    return rows


def pid_tune() -> None:
    r = random.Random(9004)
    ins = ["command", "feedback", "enable", "tune-mode", "bias"]
    outs = ["output", "tune-start", "Pgain", "Igain", "Dgain", "FF1", "ultimate-gain"]
    outs += ["ultimate-period", "errorI", "error", "commandD", "saturated", "saturated-count"]
    cases = [  # name, effort, cycles, type, what interrupts
        ("a", 1.0, 6, 0, ""),
        ("b", 0.5, 5, 1, ""),
        ("c", 2.0, 50, 0, "enable"),
        ("d", 0.3, 50, 1, "mode"),
    ]
    chans = []
    for pid, effort, cycles, typ, drop in cases:
        pre = [
            f"setp {pid}.tune-effort {effort}",
            f"setp {pid}.tune-cycles {cycles}",
            f"setp {pid}.tune-type {typ}",
            f"sets {pid}-tune-start 1",
            f"sets {pid}-Dgain 0.25",
            f"sets {pid}-FF1 0.75",
        ]
        chans.append(Chan(pid, ins, outs, tune_rows(r, 120, drop), pre))
    write_test(
        "pid-tune",
        """pid: relay auto-tuning (tune-mode, tune-start) of four loops: tune-type
0 and 1, an odd tune-cycles, tuning aborted by enable and by tune-mode, the
gains it writes into Pgain/Igain/Dgain/FF1.  Inputs from ../pid-loop/gen.py;
expected recorded from LinuxCNC 2.9.""",
        "loadrt pid names=a,b,c,d debug=1",
        chans,
    )


if __name__ == "__main__":
    pid_loop()
    pid_deriv()
    pid_special()
    pid_tune()
