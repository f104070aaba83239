#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""vbsserial: talk to the Smart Serial remote boards of a virtual board
(vboard --sserial P.C=TYPE; docs/sserial.md).

    vbsserial [-q] SOCKET status                 every remote's state (JSON)
    vbsserial SOCKET get P.C KEY [KEY...]        values from the remote's state
    vbsserial [-q] SOCKET set P.C plugged 0|1    the cable of channel P.C
    vbsserial [-q] SOCKET set P.C inputs MASK    7I76 field inputs 0..31 at once
    vbsserial [-q] SOCKET set P.C input N 0|1    one 7I76 field input
    vbsserial [-q] SOCKET set P.C analog N VOLTS 7I76 analog input N (0..3)
    vbsserial [-q] SOCKET set P.C field VOLTS    7I76 field supply voltage

-q prints nothing on success.  Requests carry no time (a probe client): the
board does not advance.
"""

from __future__ import annotations

import json
import socket
import struct
import sys

REQ_MAGIC, REP_MAGIC, SSERIAL = 0x51524256, 0x50524256, 0x71
HEADER = struct.Struct("<IHhIIQ")


def _recv(s: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = s.recv(n - len(data))
        if not chunk:
            raise OSError("the board closed the connection")
        data += chunk
    return data


def request(path: str, command: str) -> tuple[int, str]:
    """Send one VB_SSERIAL command; (status, reply text)."""
    payload = command.encode()
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(30)
        s.connect(path)
        s.sendall(HEADER.pack(REQ_MAGIC, SSERIAL, 0, len(payload), 1, 0) + payload)
        magic, _type, status, length, _seq, _t = HEADER.unpack(_recv(s, HEADER.size))
        if magic != REP_MAGIC:
            raise OSError("not a vboard reply")
        body = _recv(s, length)
    return status, body.decode(errors="replace")


def main(argv: list[str]) -> int:
    quiet = len(argv) > 1 and argv[1] == "-q"
    if quiet:
        argv = argv[:1] + argv[2:]
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    get = argv[2] == "get"
    if get and len(argv) < 5:
        print("vbsserial: want: get P.C KEY [KEY...]", file=sys.stderr)
        return 2
    try:
        status, text = request(argv[1], "status" if get else " ".join(argv[2:]))
    except OSError as exc:
        print(f"vbsserial: {argv[1]}: {exc}", file=sys.stderr)
        return 1
    if status < 0:
        print(f"vbsserial: {text}", file=sys.stderr)
        return 1
    if get:
        return print_keys(text, argv[3], argv[4:])
    if not quiet:
        print(text)
    return 0


def print_keys(status_json: str, channel: str, keys: list[str]) -> int:
    """Print KEY=VALUE for each key of the remote on channel (P.C)."""
    for r in json.loads(status_json)["remotes"]:
        if r["channel"] == channel:
            for k in keys:
                if k not in r:
                    print(f"vbsserial: no key '{k}' (known: {', '.join(r)})", file=sys.stderr)
                    return 1
                print(f"{k}={json.dumps(r[k])}")
            return 0
    print(f"vbsserial: no remote on channel '{channel}'", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
