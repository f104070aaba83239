# SPDX-License-Identifier: GPL-2.0-or-later
"""Generate the benchmark HAL files (see run.sh)."""

from __future__ import annotations

import sys


def dispatch(nfunct: int, period: int, samples: int, comp: str = "and2") -> str:
    """A thread with nfunct functions of `comp` (and2, or bench/hal's
    pinload for more than 1,000); its own run time (THREAD.time,
    time-stamp-counter clocks, measured the same way by LinuxCNC 2.9 and
    us) is read `samples` times while it runs."""
    lines = [f"loadrt threads name1=t period1={period}"]
    if nfunct > 0:
        lines.append(f"loadrt {comp} count={nfunct}")
    lines += [f"addf {comp}.{i} t" for i in range(nfunct)]
    lines += ["start", "loadusr -w sleep 0.5"]
    for _ in range(samples):
        lines += ["getp t.time", "loadusr -w sleep 0.01"]
    lines.append("stop")
    return "\n".join(lines) + "\n"


def load2000() -> str:
    """A 2,000-line configuration: components, nets, setp, addf, between two
    `loadusr -w date` lines that time it from inside (halrun's own start and
    end, and lcnc-halrun's cleanup, stay out of the figure)."""
    lines = [
        "loadrt threads name1=servo period1=1000000 name2=base period2=2000000",
        "loadrt and2 count=200",
        "loadrt or2 count=200",
        "loadrt not count=200",
    ]
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
    stamp = "loadusr -w date +%s.%N"
    return "\n".join([stamp, *lines, stamp]) + "\n"


if __name__ == "__main__":
    kind = sys.argv[1]
    if kind == "dispatch":
        comp = sys.argv[5] if len(sys.argv) > 5 else "and2"
        sys.stdout.write(dispatch(int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), comp))
    else:
        sys.stdout.write(load2000())
