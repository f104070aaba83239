# SPDX-License-Identifier: GPL-2.0-or-later
"""Append the CPU time (user+system, seconds) of the process whose
executable is EXE (and, when given, whose environment has HAL_INSTANCE=INST)
to FILE.  Used by run.sh to measure rtapi_app's cost from inside a HAL file
(via loadusr -w), the same way for LinuxCNC's rtapi_app and ours."""
from __future__ import annotations

import os
import sys


def find(exe: str, inst: str | None) -> int | None:
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            if os.path.realpath(f"/proc/{pid}/exe") != exe:
                continue
            if inst is not None:
                env = open(f"/proc/{pid}/environ", "rb").read().split(b"\0")
                if f"HAL_INSTANCE={inst}".encode() not in env:
                    continue
            return int(pid)
        except OSError:
            continue
    return None


def main() -> None:
    exe, out = os.path.realpath(sys.argv[1]), sys.argv[2]
    inst = sys.argv[3] if len(sys.argv) > 3 else None
    pid = find(exe, inst)
    if pid is None:
        sys.exit(f"cpu.py: no process for {exe}")
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    ticks = int(fields[11]) + int(fields[12])
    with open(out, "a") as f:
        f.write(f"{ticks / os.sysconf('SC_CLK_TCK')}\n")


if __name__ == "__main__":
    main()
