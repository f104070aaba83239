# SPDX-License-Identifier: GPL-2.0-or-later
"""Pin access to a running virtual board, for HAL scripts (loadusr -w):

    vbprobe.py SOCK probe KEY PIN[,PIN...]   print '%%KEY [json pins]'
    vbprobe.py SOCK reset PIN[,PIN...]       clear edge counters/measurements
    vbprobe.py SOCK drive PIN[,PIN...] low|high|release
    vbprobe.py SOCK quad A B RATE [INDEX EVERY]
    vbprobe.py SOCK hello KEY                print '%%KEY {hello}'
    vbprobe.py SOCK stall on|off             EPP boards: stop/resume acknowledging
    vbprobe.py SOCK sserial KEY CMD...       Smart Serial remotes (VB_SSERIAL): print '%%KEY json'

Every request carries host time 0: the board's clock is not advanced, the
HAL session (lockstep) owns it.
"""

from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
import vboard  # noqa: E402

MODES = {"low": vboard.DRIVE_LOW, "high": vboard.DRIVE_HIGH, "release": vboard.DRIVE_RELEASE}


def pins(arg: str) -> list[int]:
    return [int(p) for p in arg.split(",")]


def main(argv: list[str]) -> int:
    sock, cmd, *rest = argv
    with vboard.VBoardClient(sock) as c:
        if cmd == "probe":
            out = [dataclasses.asdict(c.pin(p)) for p in pins(rest[1])]
            print(f"%%{rest[0]} {json.dumps(out)}", flush=True)
        elif cmd == "reset":
            for p in pins(rest[0]):
                c.probe_reset(p, 1)
        elif cmd == "drive":
            # several pins change in the same board clock
            c.drive([(p, MODES[rest[1]]) for p in pins(rest[0])])
        elif cmd == "quad":
            a, b, rate = int(rest[0]), int(rest[1]), float(rest[2])
            if len(rest) > 3:
                c.quad(a, b, rate, int(rest[3]), int(rest[4]))
            else:
                c.quad(a, b, rate)
        elif cmd == "stall":
            c.epp_stall(rest[0] == "on")
        elif cmd == "sserial":
            reply = c.call(vboard.SSERIAL, " ".join(rest[1:]).encode()).decode()
            print(f"%%{rest[0]} {reply}", flush=True)
        elif cmd == "hello":
            print(f"%%{rest[0]} {json.dumps(dataclasses.asdict(c.hello()))}", flush=True)
        else:
            print(f"vbprobe: unknown command {cmd}", file=sys.stderr)
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
