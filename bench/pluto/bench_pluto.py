# SPDX-License-Identifier: GPL-2.0-or-later
"""bench/pluto: EPP cycles and simulated EPP bus time per servo cycle for
the pluto_servo and pluto_step drivers' transaction lists (spec section 11),
printed next to the anchor, and the measured PWM frequency / max step rate
/ watchdog time against the spec's numbers.  Runs the Verilated firmware."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "cocotb"))

from common.runner import hdl, run  # noqa: E402

TOPS = {
    "pluto_servo": [
        "pluto_epp",
        "pluto_quad",
        "pluto_pwm_counter",
        "pluto_pwm",
        "pluto_wdt",
        "pluto_servo",
    ],
    "pluto_step": ["pluto_epp", "pluto_stepgen", "pluto_wdt", "pluto_step"],
}


def main() -> int:
    out = Path(tempfile.mkstemp(prefix="pluto_bench_", suffix=".jsonl")[1])
    try:
        for top, mods in TOPS.items():
            run(
                sim="verilator",
                toplevel=top,
                sources=[hdl("pluto", f"{m}.v") for m in mods],
                test_module="bench_pluto_cocotb",
                test_dir=Path(__file__).parent,
                extra_env={"PLUTO_BENCH_OUT": str(out)},
            )
        rows = [json.loads(line) for line in out.read_text().splitlines()]
    finally:
        out.unlink(missing_ok=True)

    print(
        "EPP traffic per servo cycle (driver read + write), Verilated firmware, "
        "pin-level host model"
    )
    print(
        f"  {'firmware':12} {'host pace':22} {'cycles':>14} {'bus time':>10}   "
        f"{'ack latency':>12}  anchor"
    )
    for r in (r for r in rows if r["kind"] == "epp"):
        cyc = r["read_cycles"] + r["write_cycles"]
        us = (r["read_ns"] + r["write_ns"]) / 1000
        print(
            f"  {r['fw']:12} {r['profile']:22} {r['read_cycles']:>3} R +{r['write_cycles']:>3} W"
            f" ={cyc:>3} {us:>8.2f} us   {r['ack_min']:.0f}-{r['ack_max']:.0f} ns"
            f"     LinuxCNC: ~100 us per servo cycle on real ports, ~1 us per EPP cycle"
            f" ({cyc} cycles ~ {cyc} us)"
        )
        if r["timeouts"]:
            print(f"  !! {r['timeouts']} EPP timeouts")
    w = next(r for r in rows if r["kind"] == "epp" and r["fw"] == "pluto_servo")
    s = next(r for r in rows if r["kind"] == "epp" and r["fw"] == "pluto_step")
    print(f"  pluto_servo.write: {w['trace_write']}")
    print(f"  pluto_servo.read : {w['trace_read']}")
    print(f"  pluto_step.write : {s['trace_write']}")
    print(f"  pluto_step.read  : {s['trace_read']}")
    print("Rates measured on the output pins")
    for r in (r for r in rows if r["kind"] == "rate"):
        print(
            f"  {r['fw']:12} {r['what']:16} {r['hz'] / 1e3:9.3f} kHz   "
            f"spec {r['spec_hz'] / 1e3:.3f} kHz"
            f"   ({100 * (r['hz'] / r['spec_hz'] - 1):+.3f} %)"
        )
    for r in (r for r in rows if r["kind"] == "wdt"):
        print(
            f"  {r['fw']:12} {'watchdog bite':16} {r['bite_ms']:9.3f} ms    spec 126-127 ticks ="
            f" {r['spec_lo']:.3f}-{r['spec_hi']:.3f} ms (seed: ~6.5 ms)"
        )
    return 0


if __name__ == "__main__":
    os.chdir(ROOT)
    sys.exit(main())
