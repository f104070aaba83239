# SPDX-License-Identifier: GPL-2.0-or-later
"""Talking to a virtual board (docs/vboard-protocol.md) for halscope's
merged waveforms: its time (a HELLO with time 0, "do not advance": the reply
header carries the board time in ns) and its waveform dump (DUMP 1 path /
DUMP 0).  Requests carry time 0, so they never move the board's clock."""

from __future__ import annotations

import socket
import struct

from .halapi import HalError

HEADER = struct.Struct("<IHhIIQ")  # magic, type, status, length, seq, time_ns
REQ_MAGIC, REP_MAGIC, HELLO, DUMP = 0x51524256, 0x50524256, 0x01, 0x60


def _recv(s: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = s.recv(n - len(data))
        if not chunk:
            raise HalError("the virtual board closed the connection")
        data += chunk
    return data


def request(path: str, kind: int, payload: bytes = b"", timeout: float = 60.0) -> int:
    """One request; returns the board time of the reply."""
    try:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
            s.settimeout(timeout)
            s.connect(path)
            s.sendall(HEADER.pack(REQ_MAGIC, kind, 0, len(payload), 1, 0) + payload)
            magic, _, status, length, _, t = HEADER.unpack(_recv(s, HEADER.size))
            body = _recv(s, length)
    except OSError as e:
        raise HalError(f"virtual board at {path}: {e.strerror or e}") from None
    if magic != REP_MAGIC:
        raise HalError(f"virtual board at {path}: not a virtual board's reply")
    if status != 0:
        why = body.decode(errors="replace") if body else f"status {status}"
        raise HalError(f"virtual board at {path}: {why}")
    return int(t)


def board_time(path: str) -> int:
    return request(path, HELLO)


def dump(path: str, on: bool, file: str = "") -> int:
    """Start (to `file`) or stop the board's waveform dump; the board time."""
    return request(path, DUMP, struct.pack("<I", 1 if on else 0) + file.encode())
