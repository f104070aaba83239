#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Write the behaviour tests of simple components (tests/hal/<comp>-io).

Dev tool, not run by `make test`.  For each component: instances with
different parameters share the same streamed inputs (streamer -> every
instance), every output goes to the sampler, float outputs through scale
with gain 2^40 (a power of two: exact), so that the sampler's 6 decimals
compare them to ~1e-18 absolute.  `expected` is then recorded from
LinuxCNC 2.9 with tests/hal/gen/record_linuxcnc.sh.

    tests/hal/gen/comp_cases.py [COMP...]
"""

from __future__ import annotations

import math
import random
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

HERE = Path(__file__).resolve().parent
GAIN = 2.0**40
NAN, INF = math.nan, math.inf

Row = list[float]


@dataclass
class Spec:
    """One component's behaviour test."""

    comp: str
    inputs: list[tuple[str, str]]  # (pin, type f/b/s/u)
    outputs: list[tuple[str, str]]
    rows: Callable[[random.Random], list[Row]]
    setps: list[dict[str, str]] = field(default_factory=lambda: [{}])
    functs: list[str] = field(default_factory=lambda: [""])
    prefix: str = ""  # HAL prefix (default: the component name)
    note: str = ""
    period: int = 1000000
    test: str = ""  # test folder name (default: COMP-io)
    io: list[str] = field(default_factory=list)  # IO pins: own column per instance
    singleton: bool = False  # `option singleton`: one instance named like the component
    load: str = ""  # loadrt arguments instead of count=N
    gfuncts: list[str] = field(default_factory=list)  # functions of the whole component


def fmt(x: float, t: str) -> str:
    if t in "su":
        return str(int(x))
    if t == "b":
        return "1" if x else "0"
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(float(x))


def specials() -> list[float]:
    return [0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e20, -1e20, NAN, INF, -INF]


def floats(rng: random.Random, n: int, lo: float = -10.0, hi: float = 10.0) -> list[float]:
    return [round(rng.uniform(lo, hi), 6) for _ in range(n)]


def write(spec: Spec, d: Path, rng: random.Random) -> None:
    rows = spec.rows(rng)
    prefix = spec.prefix or spec.comp.replace("_", "-")
    k = len(spec.setps)
    insts = [prefix] if spec.singleton else [f"{prefix}.{i}" for i in range(k)]
    shared = [(p, t) for p, t in spec.inputs if p not in spec.io]
    own = [(p, t) for p, t in spec.inputs if p in spec.io]
    icfg = "".join(t for _, t in shared)
    ocfg = "".join(t for _ in insts for _, t in spec.outputs)
    nfloat = sum(1 for _, t in spec.outputs if t == "f") * k
    hal = [
        f"# {spec.comp}: listing of {len(insts)} instance(s), then {spec.note}".rstrip(),
        "# Float outputs are scaled by 2^40 (exact) before the sampler, so its",
        "# 6 decimals compare them bit for bit (written by tests/hal/gen/comp_cases.py).",
        f"loadrt {spec.comp}"
        + (f" {spec.load}" if spec.load else "" if spec.singleton else f" count={k}"),
        f"show pin {prefix}",
        f"show param {prefix}",
        f"show funct {prefix}",
        f"loadrt threads name1=t period1={spec.period}",
        f"loadrt streamer depth={len(rows) + 8} cfg={icfg}",
        f"loadrt sampler depth={len(rows) + 8} cfg={ocfg}",
    ]
    if nfloat:
        hal.append(f"loadrt scale count={nfloat}")
    hal.append("addf streamer.0 t")
    for j, (pin, _) in enumerate(shared):
        hal.append(f"net i{j} streamer.0.pin.{j} => " + " ".join(f"{x}.{pin}" for x in insts))
    # an IO pin cannot share a signal with the streamer's OUT pin (LinuxCNC
    # refuses): its signal starts at the first row's value (sets) and only
    # the component writes it afterwards
    iosig: dict[tuple[str, str], str] = {}
    first = dict(zip((p for p, _ in spec.inputs), rows[0]))
    sets = []
    for x in insts:
        for pin, t in own:
            sig = f"io{len(iosig)}"
            iosig[(x, pin)] = sig
            hal.append(f"net {sig} {x}.{pin}")
            sets.append(f"sets {sig} {fmt(first[pin], t)}")
    for i, x in enumerate(insts):
        for p, v in spec.setps[i].items():
            hal.append(f"setp {x}.{p} {v}")
        for f in spec.functs:
            hal.append(f"addf {x}{'.' + f if f else ''} t")
    for f in spec.gfuncts:
        hal.append(f"addf {prefix}.{f} t")
    s = 0
    c = 0
    for x in insts:
        for pin, t in spec.outputs:
            if (x, pin) in iosig:
                hal.append(f"net {iosig[(x, pin)]} => sampler.0.pin.{c}")
            elif t == "f":
                hal += [
                    f"net o{c} {x}.{pin} => scale.{s}.in",
                    f"net so{c} scale.{s}.out => sampler.0.pin.{c}",
                    f"setp scale.{s}.gain {GAIN!r}",
                    f"addf scale.{s} t",
                ]
                s += 1
            else:
                hal.append(f"net o{c} {x}.{pin} => sampler.0.pin.{c}")
            c += 1
    hal += sets + [
        "addf sampler.0 t",
        "loadusr -w halstreamer in.txt",
        "start",
        f"loadusr -w halsampler -n {len(rows)}",
    ]
    d.mkdir(exist_ok=True)
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    with open(d / "in.txt", "w") as f:
        for r in rows:
            vals = dict(zip((p for p, _ in spec.inputs), r))
            cols = [fmt(vals[p], t) for p, t in shared]
            f.write(" ".join(cols) + "\n")
    readme = d / "README"
    readme.write_text(
        "expected: LinuxCNC 2.9\n\n"
        "`expected` is the output of LinuxCNC 2.9's `halrun -f test.hal` in this\n"
        "folder, recorded with tests/hal/gen/record_linuxcnc.sh (normalized by\n"
        "../halnorm.py); our halrun must reproduce it byte for byte.  test.hal and\n"
        "in.txt are written by tests/hal/gen/comp_cases.py.  Data flows streamer ->\n"
        "component -> (scale x 2^40, exact) -> sampler within one thread, with the\n"
        "streamer's FIFO filled before `start` and the sampler deep enough for\n"
        "every sample, so the output does not depend on timing.\n"
    )


SPECS: dict[str, Spec] = {}


def spec(s: Spec) -> None:
    SPECS[s.test or f"{s.comp}-io"] = s


def rows_of(cols: list[list[float]]) -> list[Row]:
    n = max(len(c) for c in cols)
    return [[c[i % len(c)] for c in cols] for i in range(n)]


def main() -> None:
    import comp_cases as cc
    import specs_simple  # noqa: F401  (registers the specs in comp_cases.SPECS)
    import specs_compat  # noqa: F401  (the components LinuxCNC's sample configs use)

    names = sys.argv[1:] or sorted(cc.SPECS)
    for name in names:
        s = cc.SPECS[name]
        cc.write(s, HERE.parent / name, random.Random(name.removesuffix("-io")))


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    main()
