#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""vbplant: talk to the machine behind a virtual board (docs/vboard-machine.md).

    vbplant [-o FILE] SOCKET status   the machine's state and counters (JSON)
    vbplant SOCKET trace FILE      from now on one CSV row per host servo cycle
    vbplant SOCKET trace off       stop the trace (prints the row count)

-o FILE writes the reply to FILE instead of stdout.  Requests carry no
time (a probe client): the board does not advance.
"""

from __future__ import annotations

import socket
import struct
import sys

REQ_MAGIC, REP_MAGIC, PLANT = 0x51524256, 0x50524256, 0x70
HEADER = struct.Struct("<IHhIIQ")


def request(path: str, command: str) -> tuple[int, str]:
    """Send one VB_PLANT command; (status, reply text)."""
    payload = command.encode()
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(30)
        s.connect(path)
        s.sendall(HEADER.pack(REQ_MAGIC, PLANT, 0, len(payload), 1, 0) + payload)
        head = b""
        while len(head) < HEADER.size:
            chunk = s.recv(HEADER.size - len(head))
            if not chunk:
                raise OSError("the board closed the connection")
            head += chunk
        magic, _type, status, length, _seq, _t = HEADER.unpack(head)
        if magic != REP_MAGIC:
            raise OSError("not a vboard reply")
        body = b""
        while len(body) < length:
            chunk = s.recv(length - len(body))
            if not chunk:
                raise OSError("the board closed the connection")
            body += chunk
    return status, body.decode(errors="replace")


def main(argv: list[str]) -> int:
    out = None
    if len(argv) > 2 and argv[1] == "-o":
        out = argv[2]
        argv = argv[:1] + argv[3:]
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    try:
        status, text = request(argv[1], " ".join(argv[2:]))
    except OSError as exc:
        print(f"vbplant: {argv[1]}: {exc}", file=sys.stderr)
        return 1
    if status < 0:
        print(f"vbplant: {text}", file=sys.stderr)
        return 1
    if out is None:
        print(text)
        return 0
    try:
        with open(out, "w") as f:
            f.write(text + "\n")
    except OSError as exc:
        print(f"vbplant: {out}: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
