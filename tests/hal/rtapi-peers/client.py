# SPDX-License-Identifier: GPL-2.0-or-later
"""A raw client of rtapi_app's socket (protocol: host/hal/rtapi/rtapi_proto.h).

client.py OWNER_UID MODE: MODE is `list` (send a list request, print the
status and text of the reply), `stall` (connect, send nothing, report when
rtapi_app closes the connection), `half` (send half a request, same) or
`huge` (announce a 2 GiB request)."""

import os
import socket
import struct
import sys
import time

owner, mode = sys.argv[1], sys.argv[2]
name = "\0hm2hal-%s-%s.rtapi" % (owner, os.environ["HAL_INSTANCE"])
s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
s.connect(name)
if mode == "list":
    req = b"list\0"
    s.sendall(struct.pack("I", len(req)) + req)
elif mode == "half":
    s.sendall(struct.pack("I", 100) + b"load\0")
elif mode == "huge":
    s.sendall(struct.pack("I", 2**31))
else:
    print("connected", flush=True)
t0 = time.monotonic()
data = b""
while True:
    try:
        d = s.recv(4096)
    except ConnectionResetError:
        print("reset", flush=True)
        break
    if not d:
        break
    data += d
if mode == "list":
    st, ln = struct.unpack("iI", data[:8])
    print("status %d: %s" % (st, data[8 : 8 + ln].rstrip(b"\0").decode().strip()))
else:
    print(
        "%s: closed by rtapi_app after %s, %d bytes"
        % (mode, "< 0.5 s" if time.monotonic() - t0 < 0.5 else ">= 0.5 s", len(data))
    )
