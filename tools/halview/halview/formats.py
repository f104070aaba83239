# SPDX-License-Identifier: GPL-2.0-or-later
"""Capture files: CSV (spreadsheets, scripts) and VCD (GTKWave).

CSV: a header row ``index,time,NAME...``; one row per record; ``index`` is
the record number relative to the trigger (0 = the trigger record; from the
first record when there is no trigger), ``time`` the same in seconds.
Values: bits 0/1, integers in decimal, floats as Python's repr (exact).

VCD: one variable per channel under nested scopes made from the dotted
name (``siggen.0.sine`` -> scope siggen, scope 0, var sine); bit as a
1-bit wire, float as real, s32/s64 as integer, u32/u64 as wire vectors.
Only changes are dumped, and the last record's time ends the file (a
viewer shows the whole capture even when nothing changed at its end).
Time is the session's clock (simulated time
under ``halrun -S``) in ns, unless a time offset/scale is given (merging
with a virtual board's dump in ps).
"""

from __future__ import annotations

import csv
import io
from typing import IO, Iterable

import numpy as np

from . import halapi
from .capture import Capture

_WIDTH = {halapi.HAL_S32: 32, halapi.HAL_U32: 32, halapi.HAL_S64: 64, halapi.HAL_U64: 64}


def format_value(t: int, v: object) -> str:
    if t == halapi.HAL_FLOAT:
        return repr(float(v))  # type: ignore[arg-type]
    return str(int(v))  # type: ignore[call-overload]


def write_csv(cap: Capture, out: IO[str]) -> None:
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["index", "time"] + [c.name for c in cap.channels])
    ref = cap.trigger if cap.trigger is not None else 0
    idx = cap.index() - ref
    cols = [[format_value(c.type, v) for v in col] for c, col in zip(cap.channels, cap.columns)]
    for r in range(cap.length):
        t = int(idx[r]) * cap.interval
        w.writerow([int(idx[r]), f"{t / 1e9:.9f}"] + [col[r] for col in cols])


def csv_text(cap: Capture) -> str:
    buf = io.StringIO()
    write_csv(cap, buf)
    return buf.getvalue()


def _ident(n: int) -> str:
    """VCD identifier codes: printable ASCII 33..126, base 94."""
    chars = ""
    n += 1
    while n:
        n -= 1
        chars += chr(33 + n % 94)
        n //= 94
    return chars


def vcd_value(t: int, v: object, ident: str) -> str:
    if t == halapi.HAL_BIT:
        return f"{int(v)}{ident}"  # type: ignore[call-overload]
    if t == halapi.HAL_FLOAT:
        return f"r{float(v)!r} {ident}"  # type: ignore[arg-type]
    width = _WIDTH.get(t, 64)
    return f"b{int(v) & ((1 << width) - 1):b} {ident}"  # type: ignore[call-overload]


def _var_decl(t: int) -> tuple[str, int]:
    if t == halapi.HAL_BIT:
        return "wire", 1
    if t == halapi.HAL_FLOAT:
        return "real", 64
    if t in (halapi.HAL_S32, halapi.HAL_S64):
        return "integer", _WIDTH[t]
    return "wire", _WIDTH.get(t, 64)


def vcd_header_vars(names: list[str], types: list[int], idents: list[str]) -> list[str]:
    """$scope/$var lines for dotted names, grouped into nested scopes."""
    lines: list[str] = []
    stack: list[str] = []
    order = sorted(range(len(names)), key=lambda i: names[i].split("."))
    for i in order:
        parts = names[i].split(".")
        path, leaf = parts[:-1], parts[-1]
        common = 0
        while common < min(len(stack), len(path)) and stack[common] == path[common]:
            common += 1
        while len(stack) > common:
            lines.append("$upscope $end")
            stack.pop()
        for p in path[common:]:
            lines.append(f"$scope module {p} $end")
            stack.append(p)
        kind, width = _var_decl(types[i])
        lines.append(f"$var {kind} {width} {idents[i]} {leaf} $end")
    while stack:
        lines.append("$upscope $end")
        stack.pop()
    return lines


def vcd_changes(
    cap: Capture, idents: list[str], offset: int = 0, scale: int = 1
) -> Iterable[tuple[int, str]]:
    """(time, value line) for every change, time = (ns + offset) * scale."""
    times = (cap.times() + offset) * scale
    for c, col, ident in zip(cap.channels, cap.columns, idents):
        if len(col) == 0:
            continue
        change = np.ones(len(col), dtype=bool)
        if c.type == halapi.HAL_FLOAT:
            same = (col[1:] == col[:-1]) | (np.isnan(col[1:]) & np.isnan(col[:-1]))
        else:
            same = col[1:] == col[:-1]
        change[1:] = ~same
        for r in np.nonzero(change)[0]:
            yield int(times[r]), vcd_value(c.type, col[r], ident)


def write_vcd(cap: Capture, out: IO[str], title: str = "halscope capture") -> None:
    idents = [_ident(i) for i in range(len(cap.channels))]
    out.write(f"$comment {title} $end\n")
    out.write("$version halscope (hm2stack) $end\n")
    out.write("$timescale 1ns $end\n")
    out.write("$scope module hal $end\n")
    for line in vcd_header_vars(
        [c.name for c in cap.channels], [c.type for c in cap.channels], idents
    ):
        out.write(line + "\n")
    out.write("$upscope $end\n$enddefinitions $end\n")
    last = write_vcd_body(sorted(vcd_changes(cap, idents), key=lambda x: x[0]), out)
    if cap.length and last != int(cap.times()[-1]):
        out.write(f"#{int(cap.times()[-1])}\n")


def write_vcd_body(changes: Iterable[tuple[int, str]], out: IO[str]) -> int | None:
    """The changes under their time stamps; returns the last time stamp."""
    last = None
    for t, line in changes:
        if t != last:
            out.write(f"#{t}\n")
            last = t
        out.write(line + "\n")
    return last
