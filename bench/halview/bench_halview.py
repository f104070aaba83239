# SPDX-License-Identifier: GPL-2.0-or-later
"""bench/halview: scope_rt's cost in the thread and the live page's update
rate and latency (see run.sh for what is measured and how)."""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
import uuid
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("HM_BUILD", ROOT / "build"))
BIN = BUILD / "bin"
sys.path.insert(0, str(ROOT / "tools" / "halview"))
sys.path.insert(0, str(ROOT / "tests" / "halview"))
os.environ["HAL_INSTANCE"] = "hvbench-" + uuid.uuid4().hex[:8]
os.environ.pop("HAL_SIMCLOCK", None)

from halview import halapi  # noqa: E402

OUTS = ["sine", "cosine", "triangle", "sawtooth", "square", "clock"]


def halcmd(*args: str) -> None:
    subprocess.run([str(BIN / "halcmd"), *args], check=True, capture_output=True, text=True)


def median_time(n: int = 2000) -> float:
    vals = []
    for _ in range(n):
        vals.append(int(halapi.get(halapi.PIN, "t.time")))
        time.sleep(0.0005)
    return statistics.median(vals)


def wait_state(states: tuple[int, ...]) -> None:
    with halapi.ScopeHandle() as s:
        for _ in range(2000):
            if s.status().state in states and not s.status().pending:
                return
            time.sleep(0.005)
    raise SystemExit("bench/halview: the scope did not start")


def scope_cost(hz: float, tmp: Path) -> None:
    hal = tmp / "scope.hal"
    hal.write_text(
        "loadrt threads name1=t period1=100000\n"
        "loadrt siggen num_chan=3\n"
        "net a siggen.0.sine\nnet b siggen.1.clock\nnet c siggen.2.square\n"
        "loadrt scope_rt\naddf scope.sample t\nstart\n"
    )
    halcmd("-f", str(hal))
    try:
        halapi.require_session()
        chans = [f"siggen.{c}.{o}" for c in range(3) for o in OUTS][:13] + [
            "sig:a",
            "sig:b",
            "param:t.tmax",
        ]
        idle = median_time()
        runs = {}
        for mode, extra in (
            ("armed", ["--trigger", "siggen.0.sine", "--level", "5", "--samples", "1000"]),
            ("roll", ["--mode", "roll"]),
        ):
            p = subprocess.Popen(
                [
                    str(BIN / "halscope"),
                    "-c",
                    ",".join(chans),
                    "--timeout",
                    "0",
                    "-q",
                    "-o",
                    str(tmp / "x.csv"),
                    *extra,
                ],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.PIPE,
            )
            wait_state((halapi.ST_ARMED,) if mode == "armed" else (halapi.ST_ROLLING,))
            runs[mode] = median_time()
            p.terminate()
            p.wait(timeout=30)
        halcmd("delf", "scope.sample", "t")
        empty = median_time()
    finally:
        subprocess.run([str(BIN / "halrun"), "-U"], capture_output=True)
    ns = 1e9 / hz
    print(
        f"scope_rt, 16 channels (13 pins, 2 signals, 1 parameter), 100 us thread, "
        f"median THREAD.time of 2000 periods, TSC {hz / 1e9:.3f} GHz:"
    )
    for mode, clocks in runs.items():
        print(
            f"  {mode:5s}: {(clocks - idle) * ns:6.1f} ns per sample over scope.sample idle, "
            f"{(clocks - empty) * ns:6.1f} ns with the call itself  (goal <= 50 ns)"
        )
    print(
        f"  idle scope.sample call: {(idle - empty) * ns:.1f} ns; empty thread "
        f"{empty * ns:.0f} ns"
    )


def page_bench(tmp: Path) -> None:
    from cdp import Browser

    hal = tmp / "page.hal"
    hal.write_text(
        "loadrt threads name1=t period1=1000000\nloadrt siggen num_chan=16\n"
        + "".join(f"addf siggen.{i}.update t\n" for i in range(16))
        + "start\n"
    )
    halcmd("-f", str(hal))
    procs = []
    try:
        halapi.require_session()
        pins = [p for p in halapi.list_names(halapi.PIN, "siggen") if "update" not in p][:100]
        assert len(pins) == 100
        with Browser() as b:
            for rate in (20, 100):
                p = subprocess.Popen(
                    [
                        str(BIN / "halweb"),
                        "--page",
                        "meter",
                        "--rate",
                        str(rate),
                        "--port",
                        "0",
                        *[f"pin+{n}" for n in pins],
                    ],
                    stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE,
                    text=True,
                )
                procs.append(p)
                assert p.stdout is not None
                url = p.stdout.readline().split()[1]
                page = b.new_page(url)
                page.wait_for("window.halweb.stats.updates > 10", 30)
                page.eval("window.halweb.stats.updates = 0; window.halweb.stats.latencies = []")
                t0 = time.monotonic()
                time.sleep(10)
                st = page.eval("window.halweb.stats")
                dt = time.monotonic() - t0
                lat = sorted(st["latencies"])
                med = statistics.median(lat) * 1e3
                p99 = lat[int(len(lat) * 0.99) - 1] * 1e3
                shown = page.eval("document.querySelectorAll('#watch-list tr').length")
                print(
                    f"page, {shown} watched pins, --rate {rate}: {st['updates'] / dt:.1f} "
                    f"updates/s drawn, latency HAL read -> next frame median {med:.1f} ms, "
                    f"99% {p99:.1f} ms"
                )
                page.close()
                p.terminate()
                p.wait(timeout=30)
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
        subprocess.run([str(BIN / "halrun"), "-U"], capture_output=True)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--tsc-hz", type=float, required=True)
    ap.add_argument("--tmp", type=Path, required=True)
    a = ap.parse_args()
    scope_cost(a.tsc_hz, a.tmp)
    page_bench(a.tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
