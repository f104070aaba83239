# SPDX-License-Identifier: GPL-2.0-or-later
"""Build and run the HDL speed measurements (bench_hdl.py) on Verilator
and print every figure next to Mesa's anchor at the same clock.

Anchors (see docs/hm2-stepgen.md, hm2-encoder.md, hm2-pwmgen.md):
* step rate: Mesa's timing registers give a step period of
  (PulseWidth+1)+(PulseIdle+1) ClockLow clocks; Mesa's regmap forbids
  PulseWidth = 0, so the fastest legal Mesa setting is 1/0 = 3 clocks
  (ClockLow/3); 0/0 = 2 clocks is shown as the register-level bound.
  Timing resolution: one ClockLow period (the registers count clocks).
* encoder: the hostmot2 documentation states the filter needs 3 (off) or
  15 (on) sample clocks to register a change; a quadrature phase holds each
  level for two count edges, so the 4x count-rate bound derived from that
  is 2*ClockLow/3 (off) and 2*ClockLow/15 (on).
* PWM: spec §10.3 (LinuxCNC's own resolution table):
  f = ClockHigh*65535/65536/2^bits; 100 MHz: 24.4/48.8/97.7/195.3 kHz.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tests" / "cocotb"))

from common.runner import hdl, run  # noqa: E402


def main() -> int:
    """Print the table on stdout; the simulators' chatter goes to stderr
    (fd 2), which run.sh keeps in a log file."""
    table = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)  # runner/make/simulator output -> stderr
    out = Path(tempfile.mkstemp(prefix="hm2-bench-", suffix=".jsonl")[1])
    env = {"HM_BENCH_OUT": str(out), "COCOTB_LOG_LEVEL": "WARNING"}
    builds = [
        (
            "hm2_stepgen_bank",
            [hdl("hostmot2", "hm2_stepgen.v"), hdl("hostmot2", "hm2_stepgen_bank.v")],
            {"NUM": 1, "TABLE_WIDTH": 2},
        ),
        (
            "hm2_encoder_bank",
            [
                hdl("common", "sync_ff.v"),
                hdl("hostmot2", "hm2_encoder.v"),
                hdl("hostmot2", "hm2_encoder_bank.v"),
            ],
            {"NUM": 1},
        ),
        (
            "hm2_pwmgen_bank",
            [
                hdl("common", "sync_ff.v"),
                hdl("hostmot2", "hm2_pwmgen.v"),
                hdl("hostmot2", "hm2_pwmgen_bank.v"),
            ],
            {"NUM": 2},
        ),
    ]
    for top, srcs, params in builds:
        run(
            sim="verilator",
            toplevel=top,
            sources=srcs,
            test_module="bench_hdl",
            test_dir=HERE,
            parameters=params,
            extra_env=env,
        )
    figs = [json.loads(line) for line in out.read_text().splitlines()]
    out.unlink()
    ok = True

    def print(*a: object) -> None:  # noqa: A001 - the table goes to the saved stdout
        table.write(" ".join(str(x) for x in a) + "\n")
        table.flush()

    print("hm2 firmware (simulated, Verilator; anchors derived from Mesa register semantics)")
    print(f"{'figure':<44}{'ours':>16}{'Mesa anchor':>16}  verdict")

    def row(name: str, ours: float, anchor: float, unit: str, higher_better: bool = True) -> None:
        nonlocal ok
        good = ours >= anchor * 0.999 if higher_better else ours <= anchor * 1.001
        ok &= good
        print(
            f"{name:<44}{ours:>12.4g} {unit:<3}{anchor:>12.4g} {unit:<3}  "
            f"{'>= Mesa' if good else 'BELOW Mesa'}"
        )

    for f in figs:
        mhz = f.get("clock_mhz") or f.get("clock_high_mhz")
        if f["kind"] == "step_rate":
            anchor = mhz * 1e6 / ((f["pulsewidth"] + 1) + (f["pulseidle"] + 1))
            row(
                f"stepgen max rate @{mhz:.2f} MHz, PW/PI={f['pulsewidth']}/{f['pulseidle']}",
                f["rate_hz"] / 1e6,
                anchor / 1e6,
                "MHz",
            )
        elif f["kind"] == "step_resolution":
            row(
                f"stepgen timing resolution @{mhz:.2f} MHz",
                f["resolution_ns"],
                1e3 / mhz,
                "ns",
                higher_better=False,
            )
        elif f["kind"] == "encoder_rate":
            anchor = 2 * mhz * 1e6 / f["filter"]
            row(
                f"encoder max 4x count rate @{mhz:.2f} MHz, filter {f['filter']}",
                f["rate_hz"] / 1e6,
                anchor / 1e6,
                "MHz",
            )
        elif f["kind"] == "pwm":
            anchor = mhz * 1e6 * 65535 / 65536 / (1 << f["bits"])
            row(
                f"PWM {f['bits']}-bit max frequency @{mhz:.0f} MHz",
                f["freq_hz"] / 1e3,
                anchor / 1e3,
                "kHz",
            )
            if f["bits"] == 9 and f["pdm_slot_ns"]:
                row(
                    f"PDM slot (min pulse) @{mhz:.0f} MHz",
                    f["pdm_slot_ns"],
                    1e3 / mhz,
                    "ns",
                    higher_better=False,
                )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
