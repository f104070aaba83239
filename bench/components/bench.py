# SPDX-License-Identifier: GPL-2.0-or-later
"""Per-call cost of the servo components' realtime functions (pid, stepgen,
encoder, pwmgen), ours vs LinuxCNC 2.9, on the same HAL file (see run.sh
for the method)."""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

PERIOD = 100000  # ns, the measured thread (the other two 1 and 3 us slower)
WARMUP = 500  # first samples left out


def drive_siggen() -> list[str]:
    return [
        "loadrt siggen",
        "setp siggen.0.frequency 7",
        "setp siggen.0.amplitude 2",
        "net sine siggen.0.sine",
        "net cosine siggen.0.cosine",
    ]


def case_pid() -> tuple[str, int, list[str], list[str], list[str]]:
    """16 pid loops (2.9's maximum), enabled, every term and limit in use,
    command a sine, feedback a cosine."""
    setup = ["loadrt pid num_chan=16", *drive_siggen()]
    for k in range(16):
        setup += [
            f"net sine pid.{k}.command",
            f"net cosine pid.{k}.feedback",
            f"setp pid.{k}.enable 1",
            f"setp pid.{k}.Pgain {1 + k}",
            f"setp pid.{k}.Igain 0.5",
            f"setp pid.{k}.Dgain 0.01",
            f"setp pid.{k}.FF1 0.2",
            f"setp pid.{k}.FF2 0.001",
            f"setp pid.{k}.deadband 0.001",
            f"setp pid.{k}.maxerror 5",
            f"setp pid.{k}.maxerrorI 2",
            f"setp pid.{k}.maxoutput 10",
        ]
    measured = [f"pid.{k}.do-pid-calcs" for k in range(16)]
    return "pid.N.do-pid-calcs (16 loops, one call each)", 16, setup, measured, ["siggen.0.update"]


def case_stepgen() -> tuple[str, int, list[str], list[str], list[str]]:
    """One make-pulses serving 16 channels (2.9's maximum): step/dir,
    up/down, quadrature and 5-phase types, half in velocity mode at
    different speeds, half following a sine in position mode."""
    types = [0, 1, 2, 3, 0, 2, 10, 14] * 2
    ctrl = ["v"] * 8 + ["p"] * 8
    setup = [
        f"loadrt stepgen step_type={','.join(map(str, types))} ctrl_type={','.join(ctrl)}",
        *drive_siggen(),
    ]
    for k in range(16):
        setup += [f"setp stepgen.{k}.enable 1", f"setp stepgen.{k}.maxaccel 20000"]
        if types[k] <= 1:
            setup += [f"setp stepgen.{k}.steplen 1", f"setp stepgen.{k}.stepspace 1"]
        if ctrl[k] == "v":
            setup.append(f"setp stepgen.{k}.velocity-cmd {500 + 300 * k}")
        else:
            setup += [
                f"setp stepgen.{k}.position-scale {1000 + 100 * k}",
                f"net sine stepgen.{k}.position-cmd",
            ]
    drive = ["siggen.0.update", "stepgen.update-freq", "stepgen.capture-position"]
    return "stepgen.make-pulses (16 channels)", 1, setup, ["stepgen.make-pulses"], drive


def case_encoder() -> tuple[str, int, list[str], list[str], list[str]]:
    """One update-counters serving 8 channels (2.9's maximum), counting the
    quadrature of 8 stepgens (type 2) running in the other thread; index
    and latch inputs wired."""
    setup = [
        "loadrt encoder num_chan=8",
        "loadrt stepgen step_type=2,2,2,2,2,2,2,2 ctrl_type=v,v,v,v,v,v,v,v",
    ]
    for k in range(8):
        setup += [
            f"setp stepgen.{k}.enable 1",
            f"setp stepgen.{k}.maxaccel 0",
            f"setp stepgen.{k}.velocity-cmd {(-1) ** k * (400 + 250 * k)}",
            f"net a{k} stepgen.{k}.phase-A => encoder.{k}.phase-A",
            f"net b{k} stepgen.{k}.phase-B => encoder.{k}.phase-B encoder.{k}.phase-Z",
            f"net a{(k + 1) % 8} encoder.{k}.latch-input",
            f"setp encoder.{k}.position-scale {100 + k}",
        ]
    drive = ["stepgen.update-freq", "stepgen.make-pulses", "encoder.capture-position"]
    return "encoder.update-counters (8 channels)", 1, setup, ["encoder.update-counters"], drive


PWM_OUTS = {0: ["pwm"], 1: ["pwm", "dir"], 2: ["up", "down"]}


def case_pwmgen() -> tuple[str, int, list[str], list[str], list[str]]:
    """One make-pulses serving 8 channels (2.9's maximum): pure PWM,
    dithered PWM and PDM on all three output types, values from a sine."""
    types = [0, 1, 2, 0, 1, 2, 1, 2]
    freqs = [1000, 1000, 2000, 0, 0, 0, 1300, 700]
    dither = [0, 0, 0, 0, 0, 0, 1, 1]
    setup = [f"loadrt pwmgen output_type={','.join(map(str, types))}", *drive_siggen()]
    for k in range(8):
        setup += [
            f"setp pwmgen.{k}.enable 1",
            f"setp pwmgen.{k}.pwm-freq {freqs[k]}",
            f"setp pwmgen.{k}.dither-pwm {dither[k]}",
            f"setp pwmgen.{k}.scale 2.5",
            f"net sine pwmgen.{k}.value",
        ]
        setup += [f"net pw{k}-{o} pwmgen.{k}.{o}" for o in PWM_OUTS[types[k]]]
    drive = ["siggen.0.update", "pwmgen.update"]
    return "pwmgen.make-pulses (8 channels)", 1, setup, ["pwmgen.make-pulses"], drive


CASES = {
    "pid": case_pid,
    "stepgen": case_stepgen,
    "encoder": case_encoder,
    "pwmgen": case_pwmgen,
}


def hal_file(
    setup: list[str], measured: list[str], ncalls: int, drive: list[str], samples: int
) -> str:
    """Three threads (LinuxCNC's threads has no more): `f` with the measured
    functions, `base` with as many calls of a trivial function (and2),
    `drive` with what feeds them and a sampler recording both threads' run
    times (the THREAD.time pins) every period.  f - base is the measured
    functions' own cost: HAL's dispatch and the per-function timing
    (bench/hal compares those) cancel out.  The periods differ a little
    (100, 101, 103 us) so that one thread seldom wakes while another runs:
    our threads are SCHED_FIFO with distinct priorities and would preempt
    it, inflating its time."""
    lines = [
        f"loadrt threads name1=f period1={PERIOD} name2=base period2={PERIOD + 1000} "
        f"name3=drive period3={PERIOD + 3000}",
        f"loadrt and2 count={ncalls}",
        *setup,
        f"loadrt sampler depth={samples + WARMUP + 100} cfg=ss",
        "net base-time base.time => sampler.0.pin.0",
        "net f-time f.time => sampler.0.pin.1",
    ]
    lines += [f"addf and2.{k} base" for k in range(ncalls)]
    lines += [f"addf {f} f" for f in measured]
    lines += [f"addf {f} drive" for f in drive]
    lines += ["addf sampler.0 drive", "start", f"loadusr -w halsampler -n {samples + WARMUP}"]
    lines.append("stop")
    return "\n".join(lines) + "\n"


def iq_mean(v: list[int]) -> float:
    """Mean of the middle half: the clocks come in steps of the time-stamp
    read (about 25 on this VM), which a median cannot see through; preempted
    periods are left out."""
    v = sorted(v)
    q = len(v) // 4
    mid = v[q : len(v) - q]
    return sum(mid) / len(mid)


def run(which: str, hal: Path, env_extra: dict[str, str]) -> float:
    """Clocks: f.time - base.time, each the mean of its middle half."""
    env = dict(os.environ, **env_extra)
    if which == "lcnc":
        cmd = ["lcnc-halrun", "-f", str(hal)]
        if os.geteuid() == 0 and shutil.which("unshare"):
            # LinuxCNC's scripts take any rtapi_app on the machine (another
            # project's) for their own realtime: run it in its own namespaces
            cmd = ["unshare", "--pid", "--fork", "--mount-proc", "--ipc", *cmd]
    else:
        cmd = [which, "-f", str(hal)]
        env["HAL_INSTANCE"] = f"compbench{os.getpid()}"
    cpu = os.environ.get("COMP_BENCH_CPU", str(os.cpu_count() - 1))
    if cpu != "any" and shutil.which("taskset"):
        cmd = ["taskset", "-c", cpu, *cmd]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=hal.parent)
    rows = [line.split() for line in r.stdout.splitlines()]
    rows = [(int(a), int(b)) for a, b in (x for x in rows if len(x) == 2) if a.isdigit()]
    rows = rows[WARMUP:]
    if len(rows) < 100:
        sys.stderr.write(f"{which}: no samples\n{r.stdout[-500:]}{r.stderr[-1500:]}\n")
        return float("nan")
    return iq_mean([b for _, b in rows]) - iq_mean([a for a, _ in rows])


def main() -> int:
    halrun, rtlib = sys.argv[1], Path(sys.argv[2])
    samples = int(os.environ.get("HAL_BENCH_SAMPLES", "3000"))
    reps = int(os.environ.get("COMP_BENCH_REPS", "5"))
    have_lcnc = shutil.which("lcnc-halrun") is not None
    wanted = sys.argv[3:] or list(CASES)
    print(
        f"servo components: clocks per call, the function's own (its thread's time minus a thread "
        f"making as many and2 calls); a {PERIOD} ns thread, on one CPU, {samples} periods per run "
        f"(mean of the middle half), median of {reps} runs alternating ours and LinuxCNC (range "
        "in brackets); goal ours <= 0.5x LinuxCNC"
    )
    print(f"  {'function':46s} {'ours':>18s} {'LinuxCNC 2.9':>18s} {'ratio':>6s}")
    status = 0
    nan = float("nan")
    with tempfile.TemporaryDirectory() as tmp:
        os.chmod(tmp, 0o755)
        for name in wanted:
            label, ncalls, setup, measured, drive = CASES[name]()
            if not (rtlib / f"{name}.so").exists():
                print(f"  {label:46s} not built yet (lib/rtlib/{name}.so missing)")
                continue
            hal = Path(tmp) / f"{name}.hal"
            hal.write_text(hal_file(setup, measured, ncalls, drive, samples))
            os.chmod(hal, 0o644)
            ours, lcnc = [], []
            for _ in range(reps):
                ours.append(run(halrun, hal, {}) / ncalls)
                if have_lcnc:
                    lcnc.append(run("lcnc", hal, {}) / ncalls)
            o = statistics.median(ours)
            lc = statistics.median(lcnc) if lcnc else nan
            ratio = o / lc if lc == lc and lc > 0 else nan
            if o != o:
                status = 1

            def cell(m: float, v: list[float]) -> str:
                return f"{m:7.1f} [{min(v):.0f}-{max(v):.0f}]" if v else f"{nan:7.1f}"

            print(f"  {label:46s} {cell(o, ours):>18s} {cell(lc, lcnc):>18s} {ratio:6.2f}")
    if not have_lcnc:
        print("  (LinuxCNC not installed: lcnc-halrun missing)")
    return status


if __name__ == "__main__":
    sys.exit(main())
