# SPDX-License-Identifier: GPL-2.0-or-later
"""Random requests (fixed seed): every one gets exactly one reply with its seq,
malformed ones an error, the board never dies and still serves afterwards."""

from __future__ import annotations

import random
import socket
import struct

import vbhelpers  # noqa: F401  (puts tests/common on sys.path)
import vboard
from vboard import VBoardClient

TYPES = [
    vboard.HELLO,
    vboard.READ,
    vboard.WRITE,
    vboard.EPP,
    vboard.EPP_STALL,
    vboard.CONFIG,
    vboard.TIME,
    vboard.PROBE,
    vboard.DRIVE,
    vboard.QUAD,
    vboard.LOOP,
    vboard.PROBE_RESET,
    vboard.DUMP,
    0x00,
    0x12,
    0x7F,
    0xFFFF,
]


def _payload(rng: random.Random, rtype: int) -> bytes:
    choice = rng.random()
    if rtype == vboard.DUMP:
        # Never a random path: the board would create that file.
        return struct.pack("<I", 0) if choice < 0.5 else b"\x01\x00"
    if choice < 0.4:
        return bytes(
            rng.getrandbits(8) for _ in range(rng.choice([0, 1, 3, 4, 7, 8, 12, 16, 24, 33]))
        )
    # Plausible structures with random fields, small enough to run fast.
    if rtype == vboard.READ:
        return b"".join(
            struct.pack("<II", rng.randrange(0, 0x10010, 2), rng.choice([0, 4, 6, 8, 64, 0x20000]))
            for _ in range(rng.randint(0, 3))
        )
    if rtype == vboard.WRITE:
        size = rng.choice([0, 4, 8, 5])
        return struct.pack("<II", rng.randrange(0, 0x10000, 4), size) + bytes(rng.randint(0, size))
    if rtype == vboard.TIME:
        return struct.pack("<IIQ", rng.randint(0, 3), 0, rng.choice([0, 1, 1000, 2**64 - 1]))
    if rtype in (vboard.PROBE, vboard.PROBE_RESET):
        return struct.pack(
            "<II", rng.choice([0, 5, 71, 72, 2**32 - 1]), rng.choice([0, 1, 72, 2**32 - 1])
        )
    if rtype == vboard.DRIVE:
        return struct.pack("<II", rng.randint(0, 80), rng.randint(0, 3))
    if rtype == vboard.QUAD:
        return struct.pack(
            "<IIIId",
            rng.randint(0, 80),
            rng.randint(0, 80),
            rng.choice([2**32 - 1, 5, 90]),
            rng.randint(0, 10),
            rng.choice([0.0, 1e5, -1e5, float("nan"), 1e12]),
        )
    if rtype == vboard.LOOP:
        return struct.pack(
            "<IIII", rng.randint(0, 80), rng.choice([rng.randint(0, 80), 2**32 - 1]), 1, 0
        )
    if rtype == vboard.CONFIG:
        return struct.pack("<II", rng.choice([0, 2, 9]), 0) + bytes(
            rng.getrandbits(8) for _ in range(rng.randint(0, 80))
        )
    return b""


def test_random_requests(client: VBoardClient) -> None:
    rng = random.Random(20260524)
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(30)
    s.connect(client.path)
    errors = 0
    for seq in range(1, 400):
        rtype = rng.choice(TYPES)
        payload = _payload(rng, rtype)
        s.sendall(vboard.HEADER.pack(vboard.REQ_MAGIC, rtype, 0, len(payload), seq, 0) + payload)
        head = b""
        while len(head) < vboard.HEADER.size:
            chunk = s.recv(vboard.HEADER.size - len(head))
            assert chunk, f"board closed the connection after request {seq} type 0x{rtype:x}"
            head += chunk
        magic, rt, status, length, rseq, _t = vboard.HEADER.unpack(head)
        assert (magic, rt, rseq) == (vboard.REP_MAGIC, rtype, seq)
        body = b""
        while len(body) < length:
            body += s.recv(length - len(body))
        if status < 0:
            errors += 1
            assert body and b"\0" not in body  # a message, UTF-8 without NUL
            body.decode("utf-8")
    s.close()
    assert 50 < errors < 399
    # Still serving, on a new connection too.
    with VBoardClient(client.path) as c:
        assert c.hello().board == "5i20"
