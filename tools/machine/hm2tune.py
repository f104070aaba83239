#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2tune: step and trapezoid response of one servo axis, PID tuning (docs/hm2tune.md).

    hm2tune EXAMPLE_DIR --axis X [--step MM] [--move MM] [--auto] [--out DIR]

Runs the example machine on the simulated clock: a step of --step mm (the
move shaping of limit3 opened up, feed-forward off) and then a trapezoid
of --move mm at the example's limit3 speed and acceleration (feed-forward
on), and reports rise time (10-90 %), overshoot, settling time (2 %) and
the max following error (pid.error) of the trapezoid, with a PNG.
--auto tunes first: it identifies the axis from an open-loop voltage test
(two voltage levels: gain K in mm/s per V, time constant tau, friction
voltage), sets FF1 = 1/K and FF2 = tau/K, places the closed loop's poles
(critically damped, natural frequency wn: P = tau wn^2 / K, D = (2 tau wn
- 1) / K, I = P wn / 20 with maxerrorI = 1.5 x the friction voltage / I)
for a range of wn, keeps the candidates with at
most 1 % overshoot and picks the one with the smallest following error;
it prints the gains and the figures before and after.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from machinelib import Board, Example, expand_moves, halrun, read_samples, run_script

GAINS = ("Pgain", "Igain", "Dgain", "FF1", "FF2", "bias", "maxerrorI")


@dataclass
class Response:
    rise_s: float
    overshoot_pct: float
    settle_s: float
    max_fe: float
    rms_fe: float
    t: list[float]
    cmd: list[float]
    fb: list[float]
    err: list[float]
    split: int  # first sample of the trapezoid part


def hal_gains(ex: Example, axis: str) -> dict[str, float]:
    g = {k: 0.0 for k in GAINS}
    for ln in ex.hal.read_text().splitlines():
        m = re.match(rf"\s*setp\s+pid-{axis}\.(\w+)\s+(\S+)", ln)
        if m and m.group(1) in g:
            g[m.group(1)] = float(m.group(2))
    return g


def limits(ex: Example, axis: str) -> tuple[float, float]:
    v = a = 0.0
    for ln in ex.hal.read_text().splitlines():
        m = re.match(rf"\s*setp\s+lim-{axis}\.(maxv|maxa)\s+(\S+)", ln)
        if m:
            v, a = (float(m.group(2)), a) if m.group(1) == "maxv" else (v, float(m.group(2)))
    return v, a


def targets(ex: Example, axis: str, value: float) -> list[float]:
    return [value if a.name == axis else 0.0 for a in ex.axes]


def run_moves(
    ex: Example,
    out: Path,
    moves: list[list[float]],
    events: list[tuple[float, str]],
) -> list[list[float]]:
    lines = expand_moves(moves, ex.period_ns)
    out.mkdir(parents=True, exist_ok=True)
    (out / "moves.txt").write_text("\n".join(lines) + "\n")
    with Board(ex.board, ex.machine, out) as b:
        script, _ = run_script(ex, b.sock, lines, events)
        halrun(script, out, {"MACHINE_SOCKET": b.sock})
    return read_samples(out / "samples.txt", ex.columns)


def measure(
    ex: Example, axis: str, gains: dict[str, float], step: float, move: float, out: Path
) -> Response:
    """A step (limit3 open, no feed-forward) then a trapezoid (FF on)."""
    a = next(x for x in ex.axes if x.name == axis)
    if a.err is None:
        raise RuntimeError(f"axis {axis} of {ex.name} samples no pid.error (err): not a servo axis")
    vmax, amax = limits(ex, axis)
    t_step, t_move = 0.25, move / vmax + vmax / amax + 0.1
    moves = [
        targets(ex, axis, 0) + [0.01],
        targets(ex, axis, step) + [t_step],
        targets(ex, axis, step + move) + [t_move],
    ]
    ev: list[tuple[float, str]] = [(0.0, f"setp pid-{axis}.{k} {gains[k]!r}") for k in GAINS]
    ev += [(0.0, f"setp pid-{axis}.FF1 0"), (0.0, f"setp pid-{axis}.FF2 0")]
    ev += [(0.0, f"setp lim-{axis}.maxv 1e9"), (0.0, f"setp lim-{axis}.maxa 1e12")]
    t1 = 0.01 + t_step - 0.005
    ev += [(t1, f"setp lim-{axis}.maxv {vmax!r}"), (t1, f"setp lim-{axis}.maxa {amax!r}")]
    ev += [
        (t1, f"setp pid-{axis}.FF1 {gains['FF1']!r}"),
        (t1, f"setp pid-{axis}.FF2 {gains['FF2']!r}"),
    ]
    rows = run_moves(ex, out, moves, ev)
    period = ex.period_ns * 1e-9
    t = [k * period for k in range(len(rows))]
    cmd = [r[a.cmd] for r in rows]
    fb = [r[a.fb] for r in rows]
    err = [r[a.err] for r in rows]
    k0 = next(k for k, c in enumerate(cmd) if c != 0)
    split = round((0.01 + t_step) / period)
    seg = fb[k0:split]
    rise = crossing(seg, 0.9 * step) - crossing(seg, 0.1 * step)
    # rounded: the feedback moves in encoder counts (1 % of a 0.5 mm step
    # is exactly one 5 um count)
    over = round(max(0.0, (max(seg) - step) / step * 100), 6)
    out_band = [k for k, y in enumerate(seg) if abs(y - step) > 0.02 * step]
    settle = (out_band[-1] + 1) if out_band else 0
    tr = err[split:]
    return Response(
        rise * period,
        over,
        settle * period,
        max(abs(e) for e in tr),
        math.sqrt(sum(e * e for e in tr) / len(tr)),
        t,
        cmd,
        fb,
        err,
        split,
    )


def crossing(y: list[float], level: float) -> float:
    for k in range(1, len(y)):
        if y[k] >= level > y[k - 1] or y[k] >= level and k == 0:
            return k - 1 + (level - y[k - 1]) / (y[k] - y[k - 1])
    return float("nan")


def identify(ex: Example, axis: str, out: Path) -> dict[str, float]:
    """Open loop: the PID outputs only its bias (all gains 0), V1 then V2."""
    a = next(x for x in ex.axes if x.name == axis)
    v1, v2, hold = 2.0, 4.0, 0.15
    moves = [targets(ex, axis, 0) + [2 * hold + 0.01]]
    ev = [(0.0, f"setp pid-{axis}.{k} 0") for k in GAINS]
    ev += [(0.0, line.replace("{axis}", axis)) for line in ex.tune_open_loop]
    ev += [(0.0, f"setp pid-{axis}.maxerror 0"), (0.0, f"setp pid-{axis}.bias {v1}")]
    ev += [(hold, f"setp pid-{axis}.bias {v2}"), (2 * hold, f"setp pid-{axis}.bias 0")]
    rows = run_moves(ex, out, moves, ev)
    period = ex.period_ns * 1e-9
    x = [r[a.fb] for r in rows]
    n = round(hold / period)
    w = 10  # speeds over 10 periods (encoder quantisation)

    def speed(k: int) -> float:
        return (x[k] - x[k - w]) / (w * period)

    s1, s2 = speed(n - 1), speed(2 * n - 1)
    if not 0 < s1 < s2:
        raise RuntimeError(
            f"open-loop test: speeds {s1:.3g} and {s2:.3g} mm/s at {v1} and {v2} V do not rise "
            "(did a fault stop the axis? see example.toml tune_open_loop)"
        )
    k_gain = (s2 - s1) / (v2 - v1)
    v_friction = v1 - s1 / k_gain
    # time constant: 63 % of the way from s1 to s2 after the second level
    level = s1 + 0.632 * (s2 - s1)
    k63 = next(k for k in range(n + w, 2 * n) if speed(k) >= level)
    tau = (k63 - w / 2 - n) * period
    return {"K": k_gain, "tau": max(tau, period), "friction_v": v_friction}


def design(plant: dict[str, float], wn: float) -> dict[str, float]:
    """Pole placement on K / (s (tau s + 1)): critically damped at wn; a
    slow integrator (wn / 20) whose state is limited to 1.5 times what the
    friction needs, so it cannot wind up into an overshoot."""
    k, tau = plant["K"], plant["tau"]
    p = tau * wn * wn / k
    i = p * wn / 20
    return {
        "Pgain": p,
        "Igain": i,
        "Dgain": max(0.0, (2 * tau * wn - 1) / k),
        "FF1": 1 / k,
        "FF2": tau / k,
        "bias": 0.0,
        "maxerrorI": 1.5 * abs(plant["friction_v"]) / i,
    }


def fmt(r: Response) -> str:
    return (
        f"rise {r.rise_s * 1e3:.1f} ms, overshoot {r.overshoot_pct:.2f} %, settling "
        f"{r.settle_s * 1e3:.1f} ms, max FE {r.max_fe * 1e3:.1f} um, RMS FE "
        f"{r.rms_fe * 1e3:.1f} um"
    )


def plot(responses: list[tuple[str, Response]], png: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(11, 3.6))
    for label, r in responses:
        s = r.split
        ax[0].plot(r.t[:s], r.fb[:s], label=label, lw=1.0)
        ax[1].plot(r.t[s:], [e * 1e3 for e in r.err[s:]], label=label, lw=1.0)
    r0 = responses[0][1]
    ax[0].plot(r0.t[: r0.split], r0.cmd[: r0.split], "k:", label="command", lw=1.0)
    ax[0].set_title("step response")
    ax[0].set_ylabel("position [mm]")
    ax[1].set_title("following error on the trapezoid")
    ax[1].set_ylabel("pid.error [µm]")
    for a in ax:
        a.set_xlabel("time [s]")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png, dpi=80, metadata={"Software": None})
    plt.close(fig)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="hm2tune", description=__doc__.splitlines()[0])
    ap.add_argument("example", type=Path)
    ap.add_argument("--axis", required=True)
    ap.add_argument("--step", type=float, default=0.5, help="step size, mm (default 0.5)")
    ap.add_argument("--move", type=float, default=10.0, help="trapezoid length, mm (default 10)")
    ap.add_argument("--auto", action="store_true", help="tune the PID first")
    ap.add_argument("--wn", default="60,90,130,180,250", help="natural frequencies to try, rad/s")
    ap.add_argument("--out", type=Path, help="output directory (default ./hm2tune-NAME-AXIS)")
    args = ap.parse_args(argv)
    try:
        ex = Example.load(args.example.resolve())
        out = (args.out or Path(f"hm2tune-{ex.name}-{args.axis}")).resolve()
        before = hal_gains(ex, args.axis)
        r0 = measure(ex, args.axis, before, args.step, args.move, out / "before")
        print(
            f"{ex.name} axis {args.axis}, gains of the HAL file: "
            + " ".join(f"{k}={v:g}" for k, v in before.items())
        )
        print(f"  {fmt(r0)}")
        result: dict[str, Any] = {"before": {"gains": before, **summary(r0)}}
        shown = [("HAL file's gains", r0)]
        if args.auto:
            plant = identify(ex, args.axis, out / "identify")
            print(
                f"plant: K = {plant['K']:.4g} mm/s per V, tau = {plant['tau'] * 1e3:.2f} ms, "
                f"friction {plant['friction_v']:.3f} V"
            )
            best: tuple[float, dict[str, float], Response] | None = None
            for wn in [float(x) for x in args.wn.split(",")]:
                g = design(plant, wn)
                r = measure(ex, args.axis, g, args.step, args.move, out / f"wn{wn:g}")
                ok = r.overshoot_pct <= 1.0
                print(f"  wn {wn:g} rad/s: {fmt(r)}{'' if ok else '  (overshoot > 1 %)'}")
                if ok and (best is None or r.max_fe < best[2].max_fe):
                    best = (wn, g, r)
            if best is None:
                raise RuntimeError("no candidate kept the overshoot at or below 1 %")
            wn, g, r = best
            print(f"tuned (wn {wn:g} rad/s): " + " ".join(f"{k}={v:.5g}" for k, v in g.items()))
            print(f"  {fmt(r)}")
            result.update({"plant": plant, "wn": wn, "after": {"gains": g, **summary(r)}})
            shown.append((f"tuned, wn {wn:g} rad/s", r))
        (out / "tune.json").write_text(json.dumps(result, indent=1) + "\n")
        png = out / f"tune-{ex.name}-{args.axis}.png"
        plot(shown, png, f"{ex.title}: axis {args.axis}")
        print(f"plot: {png}")
    except (RuntimeError, OSError, StopIteration, ValueError) as exc:
        print(f"hm2tune: {exc}", file=sys.stderr)
        return 1
    return 0


def summary(r: Response) -> dict[str, float]:
    return {
        "rise_s": r.rise_s,
        "overshoot_pct": r.overshoot_pct,
        "settle_s": r.settle_s,
        "max_fe": r.max_fe,
        "rms_fe": r.rms_fe,
    }


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
