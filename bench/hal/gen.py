# SPDX-License-Identifier: GPL-2.0-or-later
"""Generate the benchmark HAL files (see run.sh)."""
from __future__ import annotations

import sys


def dispatch(nfunct: int, period: int, seconds: float, rtapi_exe: str, out: str, inst: str) -> str:
    lines = [f"loadrt threads name1=t period1={period}"]
    if nfunct:
        lines.append(f"loadrt and2 count={nfunct}")
        lines += [f"addf and2.{i} t" for i in range(nfunct)]
    extra = f" {inst}" if inst else ""
    lines += [
        "start",
        "loadusr -w sleep 0.5",
        f"loadusr -w python3 {sys.path[0]}/cpu.py {rtapi_exe} {out}{extra}",
        f"loadusr -w sleep {seconds}",
        f"loadusr -w python3 {sys.path[0]}/cpu.py {rtapi_exe} {out}{extra}",
        "stop",
    ]
    return "\n".join(lines) + "\n"


def load2000() -> str:
    """A 2,000-line configuration: components, nets, setp, addf."""
    lines = ["loadrt threads name1=servo period1=1000000 name2=base period2=2000000",
             "loadrt and2 count=200", "loadrt or2 count=200", "loadrt not count=200"]
    i = 0
    while len(lines) < 2000:
        k = i % 200
        step = i // 200
        if step == 0:
            lines.append(f"net a{k} and2.{k}.out => or2.{k}.in0 not.{k}.in")
        elif step == 1:
            lines.append(f"net o{k} or2.{k}.out => and2.{(k + 1) % 200}.in0")
        elif step == 2:
            lines.append(f"setp and2.{k}.in1 TRUE")
        elif step == 3:
            lines.append(f"addf and2.{k} servo")
        elif step == 4:
            lines.append(f"addf or2.{k} servo")
        elif step == 5:
            lines.append(f"addf not.{k} base")
        elif step == 6:
            lines.append(f"setp or2.{k}.in1 FALSE")
        elif step == 7:
            lines.append(f"net n{k} not.{k}.out => or2.{(k + 7) % 200}.in1")
        elif step == 8:
            lines.append(f"getp and2.{k}.out")
        else:
            lines.append(f"# comment line {i}")
        i += 1
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    kind = sys.argv[1]
    if kind == "dispatch":
        n, period, secs, exe, out = sys.argv[2:7]
        inst = sys.argv[7] if len(sys.argv) > 7 else ""
        sys.stdout.write(dispatch(int(n), int(period), float(secs), exe, out, inst))
    else:
        sys.stdout.write(load2000())
