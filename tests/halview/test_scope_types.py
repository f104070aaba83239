# SPDX-License-Identifier: GPL-2.0-or-later
"""Channels of every HAL type (bit, float, s32, u32, s64, u64; signals,
pins, parameters) at their extremes, in the CSV and in the VCD.  The VCD is
read by GTKWave's own loader (vcd2fst from Debian's gtkwave, then fst2vcd
to get it back as text): what a GTKWave user sees is what HAL held."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import pytest

from hvutil import BUILT, halrun, parse_vcd, read_csv

VCD2FST, FST2VCD = "/usr/bin/vcd2fst", "/usr/bin/fst2vcd"
pytestmark = pytest.mark.requires_build(*BUILT, VCD2FST, FST2VCD)

PERIOD = 100_000
# (signal, type, value in 1st ms, 2nd ms, 3rd ms) as halcmd sets/gets write them
SIGNALS = [
    ("b", "bit", "0", "1", "1"),
    ("f", "float", "0", "-0.1", "nan"),
    ("s", "s32", "0", "-2147483648", "2147483647"),
    ("u", "u32", "0", "4294967295", "1"),
    ("S", "s64", "0", "-9223372036854775808", "9223372036854775807"),
    ("U", "u64", "0", "18446744073709551615", "9223372036854775808"),
]
WIDTH = {"bit": 1, "s32": 32, "u32": 32, "s64": 64, "u64": 64}


def hal_file() -> str:
    lines = ["loadrt threads name1=fast period1=100000", "loadrt siggen"]
    lines += [f"newsig {n} {t}" for n, t, *_ in SIGNALS]
    chans = [n for n, *_ in SIGNALS] + ["param:fast.tmax", "pin:siggen.0.reset"]
    lines.append(
        "loadusr -Wn halscope halscope --thread fast -c "
        + ",".join(chans)
        + " --mode roll --duration 3ms -o ty.csv -o ty.vcd -q"
    )
    for ms in (1, 2):
        lines.append("simrun 1ms")
        lines += [f"sets {s[0]} {s[1 + ms + 1]}" for s in SIGNALS]
    lines += ["setp fast.tmax -5", "setp siggen.0.reset 1", "simrun 1ms", "waitusr halscope"]
    return "\n".join(lines) + "\n"


def expected(ms: int) -> dict[str, str]:
    """Values in CSV text for the records of millisecond ms (0, 1, 2)."""
    out = {n: v[ms] for n, _, *v in SIGNALS}
    out["fast.tmax"] = "-5" if ms == 2 else "0"
    out["siggen.0.reset"] = "1" if ms == 2 else "0"
    return out


def vcd_text(typ: str, value: str) -> str:
    """The value as a VCD value change (GTKWave writes vectors full width)."""
    if typ == "bit":
        return value
    if typ == "float":
        return "r" + value
    bits = int(value) & ((1 << WIDTH[typ]) - 1)
    return "b" + format(bits, f"0{WIDTH[typ]}b")


def test_every_type_in_csv_and_vcd(tmp_path: Path) -> None:
    r = halrun(tmp_path, hal_file())
    assert r.returncode == 0, r.stderr
    head, rows = read_csv(tmp_path / "ty.csv")
    names = head[2:]
    assert names == [n for n, *_ in SIGNALS] + ["fast.tmax", "siggen.0.reset"]
    assert len(rows) == 30
    for n, row in enumerate(rows):
        want = expected(n // 10)
        for name, got in zip(names, row[2:]):
            if want[name] == "nan":
                assert math.isnan(float(got)), (n, name, got)
            else:
                assert got == want[name] or float(got) == float(want[name]), (n, name, got)

    fst = tmp_path / "ty.fst"
    subprocess.run([VCD2FST, str(tmp_path / "ty.vcd"), str(fst)], check=True, capture_output=True)
    back = subprocess.run([FST2VCD, str(fst)], check=True, capture_output=True, text=True).stdout
    got = parse_vcd(back)
    # record 0 is taken at the end of the first period; one change per ms
    types = {n: t for n, t, *_ in SIGNALS} | {"fast.tmax": "s32", "siggen.0.reset": "bit"}
    for name, typ in types.items():
        want = [(PERIOD + ms * 1_000_000, vcd_text(typ, expected(ms)[name])) for ms in range(3)]
        want = [w for i, w in enumerate(want) if i == 0 or w[1] != want[i - 1][1]]
        assert got[name] == want, name
    # the file ends at the last record, also where nothing changed there
    assert got["#end"][0][0] == PERIOD * 30
