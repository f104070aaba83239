#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2machine: run an example machine and print its figures (docs/hm2machine.md).

    hm2machine [--short] [--out DIR] [--no-plot] EXAMPLE_DIR

Starts a virtual board with the example's machine, runs its HAL file under
halrun -S (the simulated clock: the run is deterministic), streams the
moves, samples every servo period and traces the machine, then prints per
axis the max and RMS following error (command - feedback, what the PID
sees), the largest distance between command and where the slide really
is, steps commanded vs taken and timing violations, and writes
DIR/figures.json and a plot DIR/<example>.png.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any

from machinelib import (
    Axis,
    Board,
    Example,
    expand_moves,
    halrun,
    read_samples,
    read_trace,
    run_script,
)


def following_error(a: Axis, samples: list[list[float]]) -> list[float]:
    """pid.error where the axis has a PID (LinuxCNC's pid compares the
    previous period's command by default: the delay of one period is not
    an error), else command - feedback (a stepgen's position-fb)."""
    if a.err is not None:
        return [r[a.err] for r in samples]
    return [r[a.cmd] - r[a.fb] for r in samples]


def figures(
    ex: Example,
    samples: list[list[float]],
    trace: list[list[float]],
    head: list[str],
    status: dict[str, Any],
) -> dict[str, Any]:
    axes: dict[str, Any] = {}
    total_viol = 0
    for a in ex.axes:
        cmd = [r[a.cmd] for r in samples]
        fb = [r[a.fb] for r in samples]
        fe = following_error(a, samples)
        pos = [r[head.index(f"{a.name}.pos")] for r in trace]
        phys = [c - p for c, p in zip(cmd, pos)]
        st = next(s for s in status["axes"] if s["name"] == a.name)
        f: dict[str, Any] = {
            "kind": a.kind,
            "unit": a.unit,
            "max_fe": max(abs(e) for e in fe),
            "rms_fe": math.sqrt(sum(e * e for e in fe) / len(fe)),
            "max_cmd_minus_pos": max(abs(e) for e in phys),
            "final_cmd": cmd[-1],
            "final_fb": fb[-1],
            "final_pos": st["position"],
            "fault": st["fault"],
            "enabled": st["enabled"],
            "stop_hits": st["stop_hits"],
        }
        if "steps" in st:
            s = st["steps"]
            f["steps"] = {
                k: s[k] for k in ("commanded", "accepted", "taken", "missed", "violations")
            }
            total_viol += s["violations"]
        axes[a.name] = f
    return {
        "example": ex.name,
        "cycles": len(samples),
        "period_ns": ex.period_ns,
        "axes": axes,
        "violations": total_viol,
    }


def report(ex: Example, fig: dict[str, Any]) -> str:
    t = fig["cycles"] * fig["period_ns"] * 1e-9
    lines = [f"{ex.title}: {t:.3f} s simulated, {fig['cycles']} servo periods"]
    lines.append(
        f"{'axis':<5}{'max|FE|':>10}{'RMS FE':>10}{'max|cmd-pos|':>14}"
        f"{'final cmd':>11}{'final pos':>11}{'steps cmd':>11}{'steps taken':>12}"
        f"{'violations':>11}"
    )
    for name, a in fig["axes"].items():
        s = a.get("steps")
        lines.append(
            f"{name:<5}{a['max_fe']:>10.4f}{a['rms_fe']:>10.4f}{a['max_cmd_minus_pos']:>14.4f}"
            f"{a['final_cmd']:>11.4f}{a['final_pos']:>11.4f}"
            + (
                f"{s['commanded']:>11d}{s['taken']:>12d}{s['violations']:>11d}"
                if s
                else f"{'-':>11}{'-':>12}{'-':>11}"
            )
        )
    lines.append(
        f"(errors in {ex.axes[0].unit}; FE: the following error the loop sees (pid.error, "
        "or command - stepgen feedback); cmd-pos: command - where the slide really is)"
    )
    lines.append(f"timing violations: {fig['violations']}")
    return "\n".join(lines)


def plot(
    ex: Example, samples: list[list[float]], trace: list[list[float]], head: list[str], png: Path
) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    period = ex.period_ns * 1e-9
    t = [k * period for k in range(len(samples))]
    n = len(ex.axes)
    fig, ax = plt.subplots(n, 2, figsize=(11, 2.6 * n), squeeze=False)
    for i, a in enumerate(ex.axes):
        cmd = [r[a.cmd] for r in samples]
        fb = [r[a.fb] for r in samples]
        pos = [r[head.index(f"{a.name}.pos")] for r in trace][: len(t)]
        ax[i][0].plot(t, cmd, label="commanded", lw=1.2)
        ax[i][0].plot(t[: len(pos)], pos, "--", label="actual (machine)", lw=1.0)
        ax[i][0].set_ylabel(f"{a.name} [{a.unit}]")
        ax[i][0].legend(loc="best", fontsize=8)
        ax[i][0].grid(alpha=0.3)
        fe = [e * 1000 for e in following_error(a, samples)]
        ph = [(c - p) * 1000 for c, p in zip(cmd, pos)]
        ax[i][1].plot(
            t,
            fe,
            label="following error" + (" (pid.error)" if a.err is not None else " (cmd - fb)"),
            lw=1.0,
        )
        ax[i][1].plot(t[: len(ph)], ph, ":", label="cmd - actual", lw=1.0)
        ax[i][1].set_ylabel(f"{a.name} error [µ{a.unit}]")
        ax[i][1].legend(loc="best", fontsize=8)
        ax[i][1].grid(alpha=0.3)
    ax[-1][0].set_xlabel("time [s]")
    ax[-1][1].set_xlabel("time [s]")
    fig.suptitle(ex.title)
    fig.tight_layout()
    fig.savefig(png, dpi=80, metadata={"Software": None})
    plt.close(fig)


def run(
    ex: Example,
    out: Path,
    short: bool,
    events: list[tuple[float, str]] = [],
    after: list[str] = [],
    board_args: list[str] = [],
) -> dict[str, Any]:
    """One recorded run; returns the figures (and leaves the files in out)."""
    moves = expand_moves(ex.moves["short" if short else "run"], ex.period_ns)
    out.mkdir(parents=True, exist_ok=True)
    (out / "moves.txt").write_text("\n".join(moves) + "\n")
    with Board(ex.board, ex.machine, out, board_args) as b:
        script, _ = run_script(ex, b.sock, moves, events, after)
        halrun(script, out, {"MACHINE_SOCKET": b.sock})
    # the machine as the recording ended (before the HAL session was torn down)
    status = json.loads((out / "status.json").read_text())
    samples = read_samples(out / "samples.txt", ex.columns)
    head, trace = read_trace(out / "trace.csv")
    if len(samples) != len(moves) or len(trace) != len(moves):
        raise RuntimeError(
            f"{len(moves)} servo periods, but {len(samples)} samples and "
            f"{len(trace)} trace rows"
        )
    fig = figures(ex, samples, trace, head, status)
    (out / "figures.json").write_text(json.dumps(fig, indent=1) + "\n")
    return fig


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="hm2machine", description=__doc__.splitlines()[0])
    ap.add_argument("example", type=Path, help="example directory (with example.toml)")
    ap.add_argument("--short", action="store_true", help="the short moves (what make test runs)")
    ap.add_argument("--out", type=Path, help="output directory (default: ./hm2machine-NAME)")
    ap.add_argument("--no-plot", action="store_true", help="skip the PNG")
    args = ap.parse_args(argv)
    try:
        ex = Example.load(args.example.resolve())
        out = (args.out or Path(f"hm2machine-{ex.name}")).resolve()
        fig = run(ex, out, args.short)
        print(report(ex, fig))
        if not args.no_plot:
            samples = read_samples(out / "samples.txt", ex.columns)
            head, trace = read_trace(out / "trace.csv")
            png = out / f"{ex.name}.png"
            plot(ex, samples, trace, head, png)
            print(f"plot: {png}")
    except (RuntimeError, OSError) as exc:
        print(f"hm2machine: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
