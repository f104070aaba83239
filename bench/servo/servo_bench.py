# SPDX-License-Identifier: GPL-2.0-or-later
"""bench/servo: the hm2 servo path (read + write of every TRAM register of a
5i20 SVST8_4 with all its modules) through hm2_sim, socket board vs
in-process board (inproc=1), and how the in-process path scales with the
number of boards and the servo period.  Run by bench/servo/run.sh.

Figures, all measured in HAL on the wall clock with host_time=0 (the board's
clocks stand still between periods; its bus cycles still run clock by clock):

* read+write per period: the servo thread's own .time (both functions of
  every board, clocks -> us at the measured TSC rate), median of the
  samples.
* for in-process boards, hm2_sim stats=1: per period, the ns spent in the
  calls to the board, of them in the Verilated model (the bus cycles), and
  the rest = the transport (calls, checks, copies).
* socket transport: the socket board's read+write minus the in-process
  board's (same driver, same registers, same model work).

and on the simulated clock (halrun -S, lockstep, the board runs every
ClockLow cycle of each 1 ms period): wall time per servo period, socket vs
in-process, i.e. the board's own advance plus the transport.
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BUILD = Path(os.environ["HM_BUILD"])
HALRUN = BUILD / "bin" / "halrun"
VBOARD = BUILD / "bin" / "vboard"
HZ = float(sys.argv[1])
SAMPLES = int(os.environ.get("SERVO_BENCH_SAMPLES", "60"))
ANCHORS = "goal <= 5 us transport, <= 20 us total (fast model); hm2_eth ~104 us, SoC UIO ~59 us"
STATS = re.compile(
    r"(hm2_\w+\.\d+): in-process board: (\d+) cycles \(queued reads \+ writes\); per cycle (\d+) ns in the board calls, "
    r"(\d+) ns in the model, (-?\d+) ns transport; ([\d.]+) words read, ([\d.]+) written"
)


def hal_script(loads: list[str], period_ns: int, names: list[str]) -> str:
    s = "loadrt hostmot2\n" + "\n".join(loads) + "\n"
    s += f"loadrt threads name1=servo period1={period_ns}\n"
    for n in names:
        s += f"addf {n}.read servo\naddf {n}.write servo\n"
    s += "start\nloadusr -w sleep 0.3\n"
    for _ in range(SAMPLES):
        s += "loadusr -w sleep 0.01\ngetp servo.time\n"
    s += "stop\n"
    for n in names:
        s += f"getp {n}.io_error\n"
    return s


def run(script: str, tmp: Path) -> tuple[float, list[re.Match[str]]]:
    f = tmp / "bench.hal"
    f.write_text(script)
    env = dict(os.environ, HAL_INSTANCE=f"servobench{os.getpid()}", HAL_TIMING_EVERY="1")
    r = subprocess.run(
        [str(HALRUN), "-f", str(f)], capture_output=True, text=True, timeout=600, env=env
    )
    out = r.stdout + r.stderr
    if r.returncode != 0 or "TRUE" in r.stdout.split():
        raise SystemExit(f"bench/servo: halrun failed or io_error:\n{out}")
    vals = [int(x) for x in r.stdout.split() if x.lstrip("-").isdigit() and int(x) > 0]
    if not vals:
        raise SystemExit(f"bench/servo: no samples:\n{out}")
    return statistics.median(vals) / HZ * 1e6, list(STATS.finditer(out))


def inproc(nboards: int, period_ns: int, tmp: Path) -> tuple[float, list[re.Match[str]]]:
    boards = ",".join(["5i20"] * nboards)
    fws = ",".join(["SVST8_4"] * nboards)
    cfg = ",".join([""] * nboards)
    load = (
        f'loadrt hm2_sim inproc=1 board={boards} firmware={fws} host_time=0 stats=1 config="{cfg}"'
    )
    names = [f"hm2_5i20.{i}" for i in range(nboards)]
    return run(hal_script([load], period_ns, names), tmp)


def socket(tmp: Path) -> float:
    sock = tmp / "vb.sock"
    p = subprocess.Popen(
        [str(VBOARD), "--socket", str(sock), "--board", "5i20", "--firmware", "SVST8_4"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        assert p.stdout is not None
        if "ready on" not in p.stdout.readline():
            raise SystemExit("bench/servo: vboard did not start")
        load = f'loadrt hm2_sim socket={sock} board=5i20 host_time=0 config=""'
        us, _ = run(hal_script([load], 1_000_000, ["hm2_5i20.0"]), tmp)
        return us
    finally:
        p.terminate()
        p.wait()


def lockstep(tmp: Path, load: str) -> float:
    """halrun -S: wall ms per 1 ms servo period over 40 periods."""
    s = "loadrt hostmot2\n" + load + "\nloadrt threads name1=servo period1=1000000\n"
    s += "addf hm2_5i20.0.read servo\naddf hm2_5i20.0.write servo\nsimrun 3ms\n"
    s += "loadusr -w date +@%s.%N\nsimrun 40ms\nloadusr -w date +@%s.%N\n"
    f = tmp / "lockstep.hal"
    f.write_text(s)
    env = dict(os.environ, HAL_INSTANCE=f"servobench{os.getpid()}")
    r = subprocess.run(
        [str(HALRUN), "-S", "-f", str(f)], capture_output=True, text=True, timeout=600, env=env
    )
    t = [float(x[1:]) for x in r.stdout.split() if x.startswith("@")]
    if r.returncode != 0 or len(t) != 2:
        raise SystemExit(f"bench/servo: halrun -S failed:\n{r.stdout}{r.stderr}")
    return (t[1] - t[0]) / 40 * 1e3


def lockstep_pair(tmp: Path) -> tuple[float, float]:
    sock = tmp / "vbl.sock"
    p = subprocess.Popen(
        [str(VBOARD), "--socket", str(sock), "--board", "5i20", "--firmware", "SVST8_4"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        assert p.stdout is not None
        if "ready on" not in p.stdout.readline():
            raise SystemExit("bench/servo: vboard did not start")
        s = lockstep(tmp, f'loadrt hm2_sim socket={sock} board=5i20 config=""')
    finally:
        p.terminate()
        p.wait()
    i = lockstep(tmp, 'loadrt hm2_sim inproc=1 board=5i20 firmware=SVST8_4 config=""')
    return s, i


def split(stats: list[re.Match[str]]) -> tuple[float, float, float, float]:
    """Sum over boards: calls, model, transport (us per period), words."""
    calls = sum(int(m.group(3)) for m in stats) / 1000
    model = sum(int(m.group(4)) for m in stats) / 1000
    tr = sum(int(m.group(5)) for m in stats) / 1000
    words = sum(float(m.group(6)) + float(m.group(7)) for m in stats)
    return calls, model, tr, words


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        print(
            f"5i20 SVST8_4, every module (all TRAM registers), wall-clock HAL, host_time=0, "
            f"median of {SAMPLES} periods; TSC {HZ / 1e9:.3f} GHz"
        )
        sock_us = socket(tmp)
        ip_us, st = inproc(1, 1_000_000, tmp)
        calls, model, tr, words = split(st)
        print(f"socket board     read+write {sock_us:7.1f} us per period   {ANCHORS}")
        print(
            f"in-process board read+write {ip_us:7.1f} us per period: {calls:.1f} us in the "
            f"board calls = {model:.1f} us Verilated model ({words:.0f} bus words) + "
            f"{tr:.2f} us transport"
        )
        print(
            f"  transport: in-process {tr:.2f} us vs socket ~{sock_us - ip_us + tr:.1f} us "
            f"(socket read+write minus in-process, plus in-process transport)   goal <= 5 us"
        )
        ls, li = lockstep_pair(tmp)
        print(
            f"simulated clock (lockstep, RTL model runs each 1 ms period): wall {ls:.1f} ms per "
            f"period over the socket, {li:.1f} ms in-process   real time: 1 ms"
        )
        print(
            "scaling, in-process boards (read+write of all boards per period: median; model "
            "and transport: mean):"
        )
        print(f"  {'boards':>6} {'period':>8} {'read+write':>11} {'model':>8} {'transport':>10}")
        for n in (1, 2, 4):
            for period in (250_000, 500_000, 1_000_000):
                t0 = time.monotonic()
                us, st = inproc(n, period, tmp)
                calls, model, tr, words = split(st)
                print(
                    f"  {n:>6} {period // 1000:>5} us {us:>8.1f} us {model:>5.1f} us "
                    f"{tr:>7.2f} us   ({time.monotonic() - t0:.0f} s)"
                )


if __name__ == "__main__":
    main()
