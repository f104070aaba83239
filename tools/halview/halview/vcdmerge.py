# SPDX-License-Identifier: GPL-2.0-or-later
"""One VCD with a virtual board's firmware signals and a HAL capture.

The board's dump (every firmware signal, ps) is copied as it is; the
capture's channels are added under a top scope ``hal`` with identifier
codes the board does not use, at board time = HAL time + offset (ns), in
the board's time unit.  The body is merged in time order while streaming
the board's file, so a large dump is never held in memory.
"""

from __future__ import annotations

import re
from typing import IO, Iterator

from . import formats
from .capture import Capture
from .halapi import HalError

_UNIT = {"s": 10**15, "ms": 10**12, "us": 10**9, "ns": 10**6, "ps": 10**3, "fs": 1}


def parse_offset(text: str | None) -> int | None:
    if text is None:
        return None
    try:
        return int(text)
    except ValueError:
        raise HalError(f"--board-offset '{text}': a whole number of ns") from None


def _timescale_per_ns(header: str, path: str) -> int:
    """Board time units per ns (1000 for a ps dump)."""
    m = re.search(r"\$timescale\s+(1|10|100)\s*(s|ms|us|ns|ps|fs)\s+\$end", header)
    if not m:
        raise HalError(f"{path}: no $timescale this merge understands")
    fs_per_unit = int(m.group(1)) * _UNIT[m.group(2)]
    if 10**6 % fs_per_unit:
        raise HalError(f"{path}: time unit {m.group(1)}{m.group(2)} is coarser than 1 ns")
    return 10**6 // fs_per_unit


def _read_header(f: IO[str], path: str) -> str:
    lines = []
    for line in f:
        lines.append(line)
        if "$enddefinitions" in line:
            return "".join(lines)
    raise HalError(f"{path}: not a VCD file (no $enddefinitions)")


def check_merge(path: str, offset: str | None) -> None:
    parse_offset(offset)
    try:
        with open(path) as f:
            _timescale_per_ns(_read_header(f, path), path)
    except OSError as e:
        raise HalError(f"cannot read the board's dump {path}: {e.strerror}") from None


def _free_idents(header: str, n: int) -> list[str]:
    used = set(re.findall(r"\$var\s+\S+\s+\d+\s+(\S+)\s", header))
    out: list[str] = []
    i = 0
    while len(out) < n:
        code = "~" + formats._ident(i)
        if code not in used:
            out.append(code)
        i += 1
    return out


def _hal_changes(
    cap: Capture, idents: list[str], offset: int, per_ns: int
) -> Iterator[tuple[int, str]]:
    changes = sorted(formats.vcd_changes(cap, idents, offset, per_ns), key=lambda x: x[0])
    for t, line in changes:
        yield max(0, t), line


def write_merged(
    cap: Capture, board_vcd: str, out_path: str, offset_arg: str | None, title: str
) -> None:
    offset = parse_offset(offset_arg)
    if offset is None:
        offset = cap.board_offset
    if offset is None:
        raise HalError("merging needs the board's time: --board SOCKET or --board-offset NS")
    try:
        with open(board_vcd) as bf, open(out_path, "w") as out:
            header = _read_header(bf, board_vcd)
            per_ns = _timescale_per_ns(header, board_vcd)
            idents = _free_idents(header, len(cap.channels))
            hal_vars = ["$scope module hal $end"]
            hal_vars += formats.vcd_header_vars(
                [c.name for c in cap.channels], [c.type for c in cap.channels], idents
            )
            hal_vars.append("$upscope $end")
            head, _, _ = header.rpartition("$enddefinitions")
            out.write(f"$comment {title}; HAL time + {offset} ns = board time $end\n")
            out.write(head + "\n".join(hal_vars) + "\n$enddefinitions $end\n")
            _merge_body(bf, _hal_changes(cap, idents, offset, per_ns), out)
    except OSError as e:
        raise HalError(f"merging {board_vcd} into {out_path}: {e.strerror}") from None


def _merge_body(board: IO[str], hal: Iterator[tuple[int, str]], out: IO[str]) -> None:
    pending = next(hal, None)
    current = -1

    def emit_hal_before(limit: int | None) -> None:
        nonlocal pending, current
        while pending is not None and (limit is None or pending[0] < limit):
            t, line = pending
            if t != current:
                out.write(f"#{t}\n")
                current = t
            out.write(line + "\n")
            pending = next(hal, None)

    for line in board:
        if line.startswith("#") and line[1:].strip().isdigit():
            t = int(line[1:])
            emit_hal_before(t)
            if t != current:
                out.write(line)
                current = t
            while pending is not None and pending[0] == t:
                out.write(pending[1] + "\n")
                pending = next(hal, None)
        else:
            out.write(line)
    emit_hal_before(None)
