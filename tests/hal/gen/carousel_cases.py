#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Write the inputs of the carousel regression tests (tests/hal/carousel-*).

Dev tool, not run by `make test`: it writes test.hal and in.txt; `expected`
is then recorded from LinuxCNC 2.9 (tests/hal/gen/record_linuxcnc.sh).
One instance gets every input from a streamer filled before `start`, its
outputs go to a sampler in the same thread (motor-vel through scale with
gain 2^40, exact), so the output does not depend on timing.  The sensor
inputs are a scripted carousel: the rows say where it is, whatever the
motor outputs.  The parameters (state, homing, timer, motor-dir, debounce)
are read with getp once the sampler is done, in a state that no longer
changes.

    tests/hal/gen/carousel_cases.py [CASE...]
"""

from __future__ import annotations

import random
import sys
from pathlib import Path
from typing import Callable

HERE = Path(__file__).resolve().parent

IN = [("pocket-number", "s"), ("enable", "b"), ("strobe", "b"), ("parity", "b")]
IN += [(f"sense-{i}", "b") for i in range(8)]
IN += [("rev-pulse", "f"), ("fwd-dc", "f"), ("rev-dc", "f"), ("hold-dc", "f")]
IN += [("align-dc", "f"), ("decel-time", "f"), ("counts", "s"), ("scale", "s")]
IN += [("width", "s"), ("home-offset", "s"), ("jog-fwd", "b"), ("jog-rev", "b")]
IN += [("unhome", "b")]
OUT = [("active", "b"), ("ready", "b"), ("motor-fwd", "b"), ("motor-rev", "b")]
OUT += [("parity-error", "b"), ("current-position", "s"), ("motor-vel", "f")]
OUT += [("homed", "b"), ("index-enable", "b")]
PARAMS = ["state", "homing", "timer", "motor-dir", "debounce"]
KEYS = ["pn", "en", "st", "par"] + [f"s{i}" for i in range(8)]
KEYS += ["rp", "fd", "rd", "hd", "ad", "dt", "cn", "sc", "wd", "ho", "jf", "jr", "uh"]
DEFAULT = dict.fromkeys(KEYS, 0.0) | {"st": 1.0, "fd": 1.0, "rd": -1.0, "sc": 100.0}

Row = list[float]


class Rows:
    """Rows of inputs, each the defaults with some changes; `pos` sets the
    sensor bits from a position with the case's encoding."""

    def __init__(self, enc: Callable[[int], dict[str, float]], **base: float) -> None:
        self.enc = enc
        self.base = dict(DEFAULT, **base)
        self.rows: list[Row] = []

    def seg(self, n: int, pos: int | None = None, **kw: float) -> None:
        d = dict(self.base)
        if pos is not None:
            d.update(self.enc(pos))
        d.update(kw)
        self.rows.extend([[float(d[k]) for k in KEYS]] * n)


def bits(v: int, n: int = 8) -> dict[str, float]:
    return {f"s{i}": float((v >> i) & 1) for i in range(n)}


def gray(v: int) -> dict[str, float]:
    return bits(v ^ (v >> 1))


def bcd(v: int) -> dict[str, float]:
    return bits((v // 10) << 4 | v % 10)


def single(v: int) -> dict[str, float]:
    return bits(1 << (v - 1) if v > 0 else 0)


def fmt(x: float, t: str) -> str:
    return str(int(x)) if t in "bs" else repr(float(x))


COUNTS = {"counts", "scale", "width", "home-offset"}
UNUSED = {  # inputs a case leaves at their defaults (the streamer has 21 at most)
    "coded": COUNTS | {"align-dc", "decel-time", "unhome"},
    "index": COUNTS | {"strobe", "parity"},
    "counts": {"strobe", "parity", "align-dc", "decel-time"},
}


def write(name: str, note: str, load: str, nsense: int, rows: list[Row], kind: str) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    ins = [
        (i, p, t)
        for i, (p, t) in enumerate(IN)
        if not (p.startswith("sense-") and int(p[6:]) >= nsense) and p not in UNUSED[kind]
    ]
    icfg = "".join(t for _, _, t in ins)
    ocfg = "".join(t for _, t in OUT)
    hal = [
        "# SPDX-License-Identifier: GPL-2.0-or-later",
        f"# carousel: {note}",
        "# Written by tests/hal/gen/carousel_cases.py.",
        f"loadrt carousel {load}",
        "loadrt threads name1=t period1=1000000",
        f"loadrt streamer depth={len(rows) + 8} cfg={icfg}",
        f"loadrt sampler depth={len(rows) + 8} cfg={ocfg}",
        "loadrt scale count=1",
        "addf streamer.0 t",
    ]
    for j, (_, pin, _) in enumerate(ins):
        hal.append(f"net i{j} streamer.0.pin.{j} => carousel.0.{pin}")
    hal.append("addf carousel.0 t")
    for j, (pin, t) in enumerate(OUT):
        if t == "f":
            hal += [
                f"net o{j} carousel.0.{pin} => scale.0.in",
                f"net so{j} scale.0.out => sampler.0.pin.{j}",
                "setp scale.0.gain 1099511627776.0",
                "addf scale.0 t",
            ]
        else:
            hal.append(f"net o{j} carousel.0.{pin} => sampler.0.pin.{j}")
    hal += [
        "addf sampler.0 t",
        "loadusr -w halstreamer in.txt",
        "start",
        f"loadusr -w halsampler -n {len(rows)}",
    ]
    hal += [f"getp carousel.0.{p}" for p in PARAMS]
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    with open(d / "in.txt", "w") as f:
        for r in rows:
            f.write(" ".join(fmt(r[i], t) for i, _, t in ins) + "\n")
    (d / "README").write_text(
        "expected: LinuxCNC 2.9\n\n"
        "`expected` is the output of LinuxCNC 2.9's `halrun -f test.hal` in this\n"
        "folder, recorded with tests/hal/gen/record_linuxcnc.sh (normalized by\n"
        "../halnorm.py); our halrun must reproduce it byte for byte.  test.hal and\n"
        "in.txt are written by tests/hal/gen/carousel_cases.py.\n"
    )


def coded(enc: Callable[[int], dict[str, float]], npk: int, rng: random.Random) -> list[Row]:
    """Decoding of every sensor pattern (strobe high and low, parity), then
    moves both ways, modulo pocket numbers, pocket 0, the hold duty cycle, a
    reverse pulse, enable dropped while moving, jogs,
    random moves."""
    r = Rows(enc)
    for v in range(16):
        r.seg(2, **bits(v * 17 % 256))
    for v in range(0, 256, 37):
        r.seg(2, st=0, **bits(v))
    r.seg(2, par=1, **bits(5))
    r.seg(2, par=1, **bits(7))
    r.seg(3, pos=3)
    r.seg(3, pos=3, pn=3, en=1)
    r.seg(3, pos=3, pn=3)
    for tgt, path in ((npk - 1, range(3, npk)), (2, [npk - 1, npk, 1, 2]), (npk + 3, [3])):
        r.seg(2, pos=path[0], pn=tgt, en=1)
        for p in path:
            r.seg(3, pos=p, pn=tgt, en=1)
        r.seg(3, pos=path[-1], pn=tgt)
    r.seg(3, pos=3, pn=0, en=1)
    r.seg(3, pos=3, pn=-2, en=1)
    r.seg(3, pos=3, pn=5, en=1)  # pn changed while moving
    r.seg(3, pos=4, pn=5, en=1, hd=0.25)
    r.seg(3, pos=5, pn=5, en=1, hd=0.25)
    r.seg(3, pos=5, pn=5, hd=0.25)
    r.seg(3, pos=5, pn=6, en=1, rp=0.004, rd=-0.5)
    r.seg(8, pos=6, pn=6, en=1, rp=0.004, rd=-0.5)
    r.seg(3, pos=6, pn=6, rp=0.004, rd=-0.5)
    r.seg(3, pos=6, pn=1, en=1)  # enable dropped while moving
    r.seg(3, pos=7, pn=1)
    for jf, jr, p in ((1, 0, 7), (1, 0, 8), (0, 0, 8), (0, 1, 8), (0, 1, 7), (0, 0, 7)):
        r.seg(3, pos=p, jf=jf, jr=jr)
    r.seg(3, pos=8, jf=0, jr=0)
    pos = 8
    for _ in range(12):
        tgt = rng.randrange(1, npk + 1)
        r.seg(2, pos=pos, pn=tgt, en=1, fd=0.5, rd=-0.25)
        step = 1 if (tgt - pos) % npk <= npk // 2 else -1
        while pos != tgt:
            pos = (pos - 1 + step) % npk + 1
            r.seg(2, pos=pos, pn=tgt, en=1, fd=0.5, rd=-0.25)
        r.seg(2, pos=pos, pn=tgt, fd=0.5, rd=-0.25)
    r.seg(3, pos=pos)
    return r.rows


def index_rows(edge: bool) -> list[Row]:
    """Homing (index and pulse together), counting pulses (edge mode: both
    edges) only while moving, moves both ways, decel-time and the alignment
    after a move forwards and in reverse and after homing, unhome, enable
    dropped while homing."""

    def ip(i: int, p: int) -> dict[str, float]:
        return {"s0": float(i), "s1": float(p)}

    r = Rows(lambda v: {})
    r.seg(3, **ip(0, 0))
    r.seg(3, pn=3, en=1, **ip(0, 0))
    r.seg(3, pn=3, en=0, **ip(0, 1))  # enable dropped while homing
    r.seg(3, pn=3, en=0, **ip(0, 0))
    r.seg(3, pn=3, en=1, **ip(1, 1))
    r.seg(3, pn=3, en=1, **ip(0, 0))
    for _ in range(4):
        r.seg(3, pn=3, en=1, **ip(0, 1))
        r.seg(3, pn=3, en=1, **ip(0, 0))
    r.seg(3, pn=3, **ip(0, 0))
    r.seg(3, pn=1, en=1, **ip(0, 0))
    for _ in range(3):
        r.seg(3, pn=1, en=1, **ip(0, 1))
        r.seg(3, pn=1, en=1, **ip(0, 0))
    r.seg(3, pn=1, **ip(0, 0))
    # decel-time and the alignment (not in edge mode: there LinuxCNC 2.9
    # keeps counting edges while aligning and never finishes the alignment)
    k = {} if edge else dict(dt=0.005, ad=0.1)
    r.seg(2, pn=3, en=1, **k, **ip(0, 0))
    for seq in ([1] * 2, [0] * 2, [1] * 3, [0] * 8, [0] * 3, [1] * 3, [0] * 3, [1] * 6):
        for p in seq:
            r.seg(1, pn=3, en=1, **k, **ip(0, p))
    r.seg(3, pn=3, **k, **ip(0, 1))
    r.seg(2, pn=2, en=1, **k, **ip(0, 1))
    for seq in ([0] * 2, [1] * 3, [1] * 8, [0] * 3, [1] * 3, [0] * 3, [1] * 6):
        for p in seq:
            r.seg(1, pn=2, en=1, **k, **ip(0, p))
    r.seg(3, pn=2, **k, **ip(0, 1))
    r.seg(3, uh=1, **ip(0, 0))
    r.seg(3, **ip(0, 0))
    r.seg(3, pn=5, en=1, **k, **ip(0, 0))  # homing with decel-time
    r.seg(2, pn=5, en=1, **k, **ip(1, 1))
    for seq in ([0] * 8, [1] * 2, [0] * 3, [1] * 3, [0] * 3, [1] * 4):
        for p in seq:
            r.seg(1, pn=5, en=1, **k, **ip(0, p))
    r.seg(3, pn=5, **k, **ip(0, 1))
    r.seg(3, jf=1, **ip(0, 1))
    r.seg(3, jf=1, **ip(0, 0))
    r.seg(3, jf=0, **ip(0, 1))
    r.seg(3, jf=0, **ip(0, 0))
    return r.rows


def counts_rows() -> list[Row]:
    """Homing on the encoder index (index-enable set, then cleared by the
    encoder), pockets from counts with scale, width and home-offset."""
    r = Rows(lambda v: {}, sc=100.0, wd=10.0, ho=25.0)
    r.seg(3, cn=1000)
    r.seg(3, cn=1000, pn=3, en=1)
    for c in range(1000, 1400, 20):
        r.seg(1, cn=c, pn=3, en=1)
    r.seg(2, cn=1400, pn=3, en=1)
    for c in range(1400, 1800, 15):
        r.seg(1, cn=c, pn=3, en=1)
    r.seg(3, cn=1800, pn=3)
    for c in range(1800, 1500, -12):
        r.seg(1, cn=c, pn=2, en=1)
    r.seg(3, cn=1500, pn=2)
    return r.rows


def main() -> None:
    cases: dict[str, tuple[str, str, int, Callable[[], list[Row]], str]] = {
        "carousel-gray": (
            "gray code, 12 pockets, bidirectional",
            "pockets=12 encoding=gray num_sense=4 dir=2", 4,
            lambda: coded(gray, 12, random.Random(1)), "coded",
        ),
        "carousel-gray-uni": (
            "gray code, 10 pockets, unidirectional (jog-rev ignored), odd parity",
            "pockets=10 encoding=gray num_sense=4 dir=1 parity=1", 4,
            lambda: coded(gray, 10, random.Random(2)), "coded",
        ),
        "carousel-binary": (
            "binary, 8 pockets, 3 sensors", "pockets=8 encoding=binary num_sense=3", 3,
            lambda: coded(bits, 8, random.Random(3)), "coded",
        ),
        "carousel-bcd": (
            "BCD, 24 pockets, 6 sensors", "pockets=24 encoding=bcd num_sense=6", 6,
            lambda: coded(bcd, 24, random.Random(4)), "coded",
        ),
        "carousel-single": (
            "one sensor a pocket, 8 pockets", "pockets=8 encoding=single num_sense=8", 8,
            lambda: coded(single, 8, random.Random(5)), "coded",
        ),
        "carousel-index": (
            "index and pulse, 10 pockets", "pockets=10 encoding=index dir=2", 2,
            lambda: index_rows(False), "index",
        ),
        "carousel-edge": (
            "pulse edges, 10 pockets", "pockets=10 encoding=edge dir=2 num_sense=2", 2,
            lambda: index_rows(True), "index",
        ),
        "carousel-counts": (
            "encoder counts, 8 pockets", "pockets=8 encoding=counts dir=2 num_sense=1", 1,
            counts_rows, "counts",
        ),
    }  # fmt: skip
    names = sys.argv[1:] or sorted(cases)
    for name in names:
        note, load, nsense, fn, kind = cases[name]
        write(name, note, load, nsense, fn(), kind)


if __name__ == "__main__":
    main()
