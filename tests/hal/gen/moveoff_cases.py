#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Write the inputs of the moveoff regression tests (tests/hal/moveoff-*).

Dev tool, not run by `make test`: it writes test.hal and in.txt; `expected`
is then recorded from LinuxCNC 2.9 (tests/hal/gen/record_linuxcnc.sh).
One instance (names=mv personality=2) gets every input from a streamer
filled before `start`; its outputs go to a sampler in the same thread, so
the output does not depend on timing.  Offsets and pos-plusoffset go
through scale with gain 2^40 (exact: the sampler's 6 decimals show them
to ~1e-18, bit for bit); fb-minusoffset with gain 2^20 (to ~1e-12:
LinuxCNC 2.9 computes it with a different rounding in the last bits).
waypoint-sample-secs is 0 in every row: LinuxCNC 2.9 times the waypoint
samples by the wall clock, which would make the recording depend on the
machine's timing.

    tests/hal/gen/moveoff_cases.py [CASE...]
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
GAIN = {"f": 2.0**40, "F": 2.0**20}

IN = [
    ("power-on", "b"), ("move-enable", "b"), ("apply-offsets", "b"), ("backtrack-enable", "b"),
    ("epsilon", "f"), ("waypoint-threshold", "f"), ("waypoint-sample-secs", "f"),
    ("dbg-waypoint-limit-test", "b"), ("offset-in-0", "f"), ("offset-in-1", "f"),
    ("pos-0", "f"), ("pos-1", "f"), ("fb-0", "f"), ("fb-1", "f"),
    ("offset-vel-0", "f"), ("offset-vel-1", "f"), ("offset-accel-0", "f"),
    ("offset-accel-1", "f"), ("offset-min-0", "f"), ("offset-max-0", "f"),
]  # fmt: skip
OUT = [
    ("warning", "b"), ("offset-applied", "b"), ("waypoint-limit", "b"), ("waypoint-ct", "s"),
    ("waypoint-percent-used", "s"), ("dbg-state", "s"), ("offset-current-0", "f"),
    ("offset-current-1", "f"), ("pos-plusoffset-0", "f"), ("pos-plusoffset-1", "f"),
    ("fb-minusoffset-0", "F"), ("fb-minusoffset-1", "F"),
]  # fmt: skip
DEFAULT = dict(
    pw=1, me=0, ap=0, bt=1, eps=0.0005, wth=0.02, wss=0.0, dbg=0, o0=0.0, o1=0.0,
    p0=0.0, p1=0.0, f0=0.0, f1=0.0, v0=10.0, v1=10.0, a0=100.0, a1=100.0, mn=-1e20, mx=1e20,
)  # fmt: skip

Row = list[float]


class Rows:
    """Segments of rows: each a copy of the defaults with some changes."""

    def __init__(self, **base: float) -> None:
        self.base = dict(DEFAULT, **base)
        self.rows: list[Row] = []

    def seg(self, n: int, **kw: float) -> None:
        d = dict(self.base, **kw)
        self.rows.extend([[float(d[k]) for k in DEFAULT]] * n)


def fmt(x: float, t: str) -> str:
    return str(int(x)) if t in "bs" else repr(float(x))


def write(name: str, note: str, rows: list[Row]) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    icfg = "".join(t for _, t in IN)
    ocfg = "".join("f" if t == "F" else t for _, t in OUT)
    nf = sum(1 for _, t in OUT if t in "fF")
    hal = [
        "# SPDX-License-Identifier: GPL-2.0-or-later",
        f"# moveoff: {note}",
        "# Written by tests/hal/gen/moveoff_cases.py (see there for the scales).",
        "loadrt moveoff names=mv personality=2",
        "loadrt threads name1=t period1=1000000",
        f"loadrt streamer depth={len(rows) + 8} cfg={icfg}",
        f"loadrt sampler depth={len(rows) + 8} cfg={ocfg}",
        f"loadrt scale count={nf}",
        "addf streamer.0 t",
    ]
    for j, (pin, _) in enumerate(IN):
        hal.append(f"net i{j} streamer.0.pin.{j} => mv.{pin}")
    hal += ["addf mv.read-inputs t", "addf mv.write-outputs t"]
    s = 0
    for j, (pin, t) in enumerate(OUT):
        if t in "fF":
            hal += [
                f"net o{j} mv.{pin} => scale.{s}.in",
                f"net so{j} scale.{s}.out => sampler.0.pin.{j}",
                f"setp scale.{s}.gain {GAIN[t]!r}",
                f"addf scale.{s} t",
            ]
            s += 1
        else:
            hal.append(f"net o{j} mv.{pin} => sampler.0.pin.{j}")
    hal += [
        "addf sampler.0 t",
        "loadusr -w halstreamer in.txt",
        "start",
        f"loadusr -w halsampler -n {len(rows)}",
    ]
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    with open(d / "in.txt", "w") as f:
        for r in rows:
            f.write(" ".join(fmt(v, t) for v, (_, t) in zip(r, IN)) + "\n")
    (d / "README").write_text(
        "expected: LinuxCNC 2.9\n\n"
        "`expected` is the output of LinuxCNC 2.9's `halrun -f test.hal` in this\n"
        "folder, recorded with tests/hal/gen/record_linuxcnc.sh (normalized by\n"
        "../halnorm.py); our halrun must reproduce it byte for byte.  test.hal and\n"
        "in.txt are written by tests/hal/gen/moveoff_cases.py (which explains the\n"
        "scales and why waypoint-sample-secs is 0).\n"
    )


def backtrack() -> list[Row]:
    """Offsets away and back along the waypoints (backtracking), straight
    back (backtrack-enable FALSE, apply-offsets dropped: warning), one and
    two joints, few and many waypoints."""
    r = Rows(wth=0.1)
    r.seg(3)
    r.seg(3, me=1, ap=1)
    r.seg(150, me=1, ap=1, o0=1.0)
    r.seg(150, me=1, ap=1, o0=1.0, o1=-0.5)
    r.seg(900, me=0, ap=1, o0=1.0, o1=-0.5)
    r.seg(3, me=1, ap=1)
    r.seg(150, me=1, ap=1, o0=0.55)
    r.seg(300, me=0, ap=1, o0=0.55)
    r.seg(150, me=1, ap=1, o0=0.35, bt=0)
    r.seg(250, me=1, ap=0, o0=0.35, bt=0)
    r.seg(5, me=1, ap=1, o0=0.35, bt=0)  # warning cleared once back
    r.seg(60, me=1, ap=1, o0=0.04, o1=0.25, wth=0.03)  # waypoints from one joint
    r.seg(6, me=1, ap=0, o0=0.04, o1=0.25, wth=0.03)  # warning while returning
    r.seg(5, me=1, ap=1, o0=0.04, o1=0.25, wth=0.03)  # apply back: warning cleared
    r.seg(200, me=0, ap=1, o0=0.04, o1=0.25, wth=0.03)
    r.seg(30, me=1, ap=1, o0=0.3, wth=0.1)  # one waypoint
    r.seg(120, me=0, ap=1, o0=0.3, wth=0.1)
    r.seg(30, me=1, ap=1, o0=0.2, wth=0.1)  # two waypoints
    r.seg(150, me=0, ap=1, o0=0.2, wth=0.1)
    return r.rows


def limits(rng: random.Random) -> list[Row]:
    """power-on, re-enabling while returning, offset-min/max, velocity and
    acceleration limits, pos and fb, epsilon (below its 0.0001 floor too),
    then random rows."""
    r = Rows(wth=0.05)
    r.seg(3, pw=0)
    r.seg(3, pw=0, me=1, ap=1, o0=0.2)  # no power: nothing happens
    r.seg(60, me=1, ap=1, o0=0.2, p0=1.5, f0=0.25)
    r.seg(5, pw=0, me=1, ap=1, o0=0.2, p0=1.5, f0=0.25)  # power drops: offsets gone
    r.seg(40, me=1, ap=1, o0=0.2, p0=1.5, f0=0.25, p1=-2.0, f1=0.75)
    r.seg(30, me=0, ap=1, o0=0.2)
    r.seg(20, me=1, ap=1, o0=0.3, o1=0.1)  # re-enabled while returning
    r.seg(60, me=1, ap=1, o0=-0.3, o1=0.1, mn=-0.1, mx=0.25)
    r.seg(60, me=1, ap=1, o0=0.3, o1=-0.2, v0=2, a0=50, v1=1, a1=1000)
    r.seg(80, me=1, ap=0, o0=0.3, o1=-0.2, v0=2, a0=50, v1=1, a1=1000)
    r.seg(20, me=1, ap=1, o0=0.3, o1=-0.2)
    r.seg(100, me=0, ap=1, o0=0.3, o1=-0.2, eps=0.00001)
    r.seg(100, me=0, ap=1, eps=0.02)
    r.seg(10, me=1, ap=1, eps=0.02, bt=0, o0=0.05)
    r.seg(100, me=0, ap=1, eps=0.02, bt=0, o0=0.05)
    r.seg(10, pw=0)
    r.seg(100, me=1, ap=1, o0=0.1, o1=-0.1, mn=0.02, mx=0.04)
    r.seg(100, me=0, ap=1, o0=0.1, o1=-0.1, mn=0.02, mx=0.04)
    r.seg(5, pw=0)
    for _ in range(150):
        r.seg(
            rng.choice([1, 3, 8]), pw=int(rng.random() < 0.95), me=int(rng.random() < 0.7),
            ap=int(rng.random() < 0.8), bt=int(rng.random() < 0.7),
            o0=round(rng.uniform(-0.3, 0.3), 3), o1=round(rng.uniform(-0.3, 0.3), 3),
            p0=round(rng.uniform(-5, 5), 3), f0=round(rng.uniform(-5, 5), 3),
            p1=round(rng.uniform(-5, 5), 3), f1=round(rng.uniform(-5, 5), 3),
        )  # fmt: skip
    return r.rows


def waypoint_limit() -> list[Row]:
    """The waypoint memory filling up: 50 waypoints with
    dbg-waypoint-limit-test, then 1000; offsets freeze, waypoint-limit
    until an enabling pin drops."""
    r = Rows(wth=0.001)
    r.seg(3, dbg=1)
    r.seg(3, me=1, ap=1, dbg=1)
    r.seg(60, me=1, ap=1, o0=100, dbg=1)
    r.seg(20, me=1, ap=1, o0=-100, dbg=1)
    r.seg(120, me=0, ap=1, o0=-100, dbg=1)
    r.seg(5, pw=0)
    r.seg(3, me=1, ap=1)
    r.seg(1030, me=1, ap=1, o0=100)
    r.seg(20, me=0, ap=1, o0=100)
    return r.rows


CASES = {
    "moveoff-backtrack": ("away and back along the waypoints, straight back, warning", backtrack),
    "moveoff-limits": ("power-on, limits, pos/fb, epsilon, re-enable, random rows", None),
    "moveoff-waypoint-limit": ("waypoint memory full (50 in test mode, 1000)", waypoint_limit),
}


def main() -> None:
    names = sys.argv[1:] or sorted(CASES)
    for name in names:
        note, fn = CASES[name]
        rows = limits(random.Random(name)) if fn is None else fn()
        write(name, note, rows)


if __name__ == "__main__":
    main()
