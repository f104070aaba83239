# SPDX-License-Identifier: GPL-2.0-or-later
"""Normalization of halcmd/halrun output before comparing it.

Only what differs for reasons of addresses and process ids is normalized
(docs/halcmd.md lists it): halcmd<pid> component names, the PID column of
`show comp`, the CodeAddr/Arg columns of `show funct` (also in -s form),
the directory of rtapi_app in -v output, and the shared-memory byte counts
of `status`.  Lines that LinuxCNC's uspace rtapi_app prints about
its own process handling (fallback uid, POSIX non-realtime, waitpid) are
dropped, because our rtapi_app loads modules in-process and has no such
lines.
"""

from __future__ import annotations

import re
import sys

_DROP = [
    re.compile(r"^Running with fallback_uid"),
    re.compile(r"^Note: Using POSIX non-realtime"),
    re.compile(r"^(.*:\d+: )?waitpid failed "),
    re.compile(r"^(.*:\d+: )?\S*rtapi_app exited without becoming ready"),
]
_HALCMD = re.compile(r"halcmd\d+")
_COMP_USER = re.compile(r"^( +\d+  User  )(\S+) +(?:\d+|PID) (ready|initializing)$")
_FUNCT = re.compile(r"^( \d{5})  [0-9a-f]+  [0-9a-f]+  (YES|NO )")
_FUNCT_S = re.compile(r"^(\S+) [0-9a-f]{6,} [0-9a-f]{6,} (YES|NO )")
_PROG = re.compile(r"Program '\S*/rtapi_app' started")
_MEM = re.compile(r"^(  used/total shared memory:).*$")


def normalize(text: str) -> str:
    out = []
    for line in text.splitlines():
        if any(p.search(line) for p in _DROP):
            continue
        m = _COMP_USER.match(line)
        if m:
            name = _HALCMD.sub("halcmdPID", m.group(2))
            line = f"{m.group(1)}{name:<47}   PID {m.group(3)}"
        line = _HALCMD.sub("halcmdPID", line)
        line = _FUNCT.sub(r"\1  CODEADDR  ARG  \2", line)
        line = _FUNCT_S.sub(r"\1 CODEADDR ARG \2", line)
        line = _PROG.sub("Program 'rtapi_app' started", line)
        line = _MEM.sub(r"\1   USED/TOTAL", line)
        out.append(line)
    return "\n".join(out) + ("\n" if out else "")


if __name__ == "__main__":
    sys.stdout.write(normalize(sys.stdin.read()))
