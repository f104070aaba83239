# SPDX-License-Identifier: GPL-2.0-or-later
"""conv_* with s64/u64 (pairs LinuxCNC 2.9 lacks, built from the same
conv.comp.in as its eleven): every pair against a Python model of the rules
in docs/conv.md, over the edges of each type, with clamp TRUE then FALSE.
(The eleven 2.9 pairs are checked against 2.9's own output in
tests/hal/conv_all.)"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from hcomp_util import hal_env, halrun

I32 = (-(2**31), 2**31 - 1)
U32 = (0, 2**32 - 1)
I64 = (-(2**63), 2**63 - 1)
U64 = (0, 2**64 - 1)
RANGE = {"s32": I32, "u32": U32, "s64": I64, "u64": U64, "bit": (0, 1)}

INPUTS: dict[str, list] = {
    "bit": [0, 1, 0],
    "float": [
        0.0,
        1.0,
        -1.0,
        2.5,
        -2.5,
        1e10,
        -1e10,
        2.0**31,
        2.0**32 + 5,
        9.2e18,
        2.0**63,
        -(2.0**63),
        -1e19,
        1.5e19,
        2.0**64,
        1e20,
        math.nan,
        math.inf,
        -math.inf,
    ],
    "s32": [0, 1, -1, 2, I32[0], I32[1]],
    "u32": [0, 1, 2, 2**31 - 1, 2**31, 2**32 - 1],
    "s64": [0, 1, -1, 2, 2**31 - 1, 2**31, -(2**31) - 1, 2**32 - 1, 2**32, I64[0], I64[1]],
    "u64": [0, 1, 2, 2**31 - 1, 2**31, 2**32 - 1, 2**32, 2**63 - 1, 2**63, U64[1]],
}

PAIRS = (
    "bit:s64 bit:u64 float:s64 float:u64 s32:s64 s32:u64 u32:s64 u32:u64 s64:bit "
    "s64:float s64:s32 s64:u32 s64:u64 u64:bit u64:float u64:s32 u64:u32 u64:s64"
).split()
# input can leave the output's range (docs/conv.md): out-of-range pin + clamp
RANGED = (
    "float:s64 float:u64 s32:u64 s64:bit s64:s32 s64:u32 s64:u64 u64:bit u64:s32 " "u64:u32 u64:s64"
).split()


def wrap(v: int, t: str) -> int:
    """Two's complement: the low bits of v as type t."""
    bits = 64 if t in ("s64", "u64") else 32
    v &= (1 << bits) - 1
    if t.startswith("s") and v >= 1 << (bits - 1):
        v -= 1 << bits
    return v


def cast(v: float | int, i: str, o: str) -> float | int:
    """gcc's cast on x86-64 (docs/conv.md)."""
    if o == "bit":
        return int(v != 0)
    if o == "float":
        return float(v)
    if i == "float":
        assert isinstance(v, float)
        if o == "s64":
            if math.isnan(v) or not (-(2.0**63) <= v < 2.0**63):
                return I64[0]
            return int(v)
        if o == "u64":
            if math.isnan(v) or v < -(2.0**63):
                return 2**63
            if v < 2.0**63:
                return wrap(int(v), "u64")
            if v - 2.0**63 >= 2.0**63:
                return 0
            return int(v - 2.0**63) ^ (1 << 63)
    return wrap(int(v), o)


def in_range(v: float | int, o: str) -> tuple[bool, bool]:
    """(above, below) the output's range, as conv compares them."""
    lo, hi = RANGE[o]
    if isinstance(v, float):
        if o == "s64":
            return v >= 2.0**63, v < -(2.0**63)
        if o == "u64":
            return v >= 2.0**64, v < 0
    return v > hi, v < lo


def differs(out: float | int, v: float | int, i: str, o: str) -> bool:
    """out != in, compared as C's usual conversions do."""
    if i == "float" or o == "float":
        return float(out) != float(v)
    if "u64" in (i, o):
        return wrap(int(out), "u64") != wrap(int(v), "u64")
    return int(out) != int(v)


def model(i: str, o: str) -> list[tuple[float | int, bool]]:
    """(out, out-of-range) after each input, clamp TRUE then FALSE."""
    rows = []
    sticky = False
    for clamp in (True, False):
        for v in INPUTS[i]:
            if clamp and not pair_ranged(i, o):
                rows.append((cast(v, i, o), False))
            elif clamp:
                above, below = in_range(v, o)
                if above:
                    rows.append((RANGE[o][1], True))
                elif below:
                    rows.append((RANGE[o][0], True))
                else:
                    rows.append((cast(v, i, o), False))
            else:
                # never cleared in this mode, not even what clamp TRUE left
                sticky = sticky or rows[-1][1]
                out = cast(v, i, o)
                if pair_ranged(i, o) and differs(out, v, i, o):
                    sticky = True
                rows.append((out, sticky))
    return rows


def pair_ranged(i: str, o: str) -> bool:
    return f"{i}:{o}" in RANGED


def fmt_in(v: float | int, t: str) -> str:
    if t == "float":
        assert isinstance(v, float)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    return str(int(v))


@pytest.mark.parametrize("pair", PAIRS)
def test_conv64(pair: str, tmp_path: Path) -> None:
    i, o = pair.split(":")
    inst = f"conv-{i}-{o}.0"
    lines = [f"loadrt conv_{i}_{o}", "loadrt threads name1=t period1=1000000", f"addf {inst} t"]
    for clamp in (1, 0):
        if pair_ranged(i, o):
            lines.append(f"setp {inst}.clamp {clamp}")
        for v in INPUTS[i]:
            lines += [f"setp {inst}.in {fmt_in(v, i)}", "simrun 1ms", f"getp {inst}.out"]
            if pair_ranged(i, o):
                lines.append(f"getp {inst}.out-of-range")
    p = halrun("\n".join(lines) + "\n", tmp_path, hal_env(), "-S")
    assert p.returncode == 0, p.stderr
    got = p.stdout.split()
    want = model(i, o)
    step = 2 if pair_ranged(i, o) else 1
    assert len(got) == step * len(want)
    if not pair_ranged(i, o):
        want = want[: len(INPUTS[i])]  # no clamp: the second pass is the same
        got = got[: len(want)]
    for k, (out, oor) in enumerate(want):
        g = got[step * k]
        where = f"{pair} row {k}: in={INPUTS[i][k % len(INPUTS[i])]}"
        if o == "float":
            assert float(g) == pytest.approx(out, rel=1e-6), where
        elif o == "bit":
            assert g == ("TRUE" if out else "FALSE"), where
        else:
            assert int(g) == out, where
        if step == 2:
            assert got[step * k + 1] == ("TRUE" if oor else "FALSE"), where
