#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Write the inputs of the limit3 regression tests (tests/hal/limit3-*).

Dev tool, not run by `make test`: it writes test.hal and in.txt; `expected`
is then recorded from LinuxCNC 2.9 (tests/hal/gen/record_linuxcnc.sh).
Every instance's output goes through scale with gain 2^40 (exact) before the
sampler, so the sampler's 6 decimals show the output to ~1e-18: the test
compares LinuxCNC's and our outputs bit for bit, not to a tolerance.
"""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
GAIN = 2.0**40


def track_cases(rng: random.Random, n: int) -> list[tuple[dict[str, str], list[tuple[float, int]]]]:
    """(setp values, rows of (in, load)) for the tracking test."""
    cases = []
    kinds = ["steps", "steps", "ramp", "sine", "steps-maxv", "mixed"]
    for k in range(10):
        kind = kinds[k % len(kinds)]
        smooth = [0, 2, 3, 1, 2, 5, 0, 2, 8, 2][k]
        maxa = round(rng.uniform(150, 4000), 3)
        maxv = 1e20 if "maxv" not in kind else round(rng.uniform(0.5, 3), 4)
        if k in (7, 9):
            maxv = round(rng.uniform(1, 4), 4)
        base = rng.choice([0.0, 1.5, -2.25, 10.0])
        rows: list[tuple[float, int]] = [(base, 1)] * 3
        val = base
        vel = rng.uniform(-2.5, 2.5) * 1e-3
        amp, freq = rng.uniform(0.2, 2.0), rng.uniform(1.0, 15.0)
        for i in range(n):
            t = i * 1e-3
            if kind.startswith("steps"):
                if rng.random() < 0.03:
                    val = base + rng.uniform(-3, 3)
                rows.append((val, 0))
            elif kind == "ramp":
                seg = (i // 80) % 3
                val = val + (vel if seg == 0 else -vel if seg == 1 else 0.0)
                rows.append((val, 0))
            elif kind == "sine":
                rows.append((base + amp * math.sin(2 * math.pi * freq * t), 0))
            else:
                r = rng.random()
                if r < 0.02:
                    val = base + rng.uniform(-2, 2)
                if i % 97 == 50:
                    rows.append((val + 0.3, 1))
                    continue
                if k == 5 and 300 <= i < 303:
                    rows.append((math.nan, 0))
                    continue
                rows.append((val + 0.05 * math.sin(2 * math.pi * 3 * t), 0))
        if k == 0 and n >= 420:
            # NaN and +-inf inputs with smooth-steps 0: the output coasts
            for i in (200, 201, 350, 420):
                rows[i] = (math.nan if i < 300 else math.inf if i < 400 else -math.inf, 0)
        setp = {"maxv": repr(maxv), "maxa": repr(maxa), "smooth-steps": str(smooth)}
        cases.append((setp, rows))
    return cases


def fmt(x: float) -> str:
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(x)


def write_track(d: Path, n: int, seed: int, period: int = 1000000, k: int = 10) -> None:
    rng = random.Random(seed)
    cases = track_cases(rng, n)[:k]
    hal = [
        f"# limit3: {k} instances following stepped, ramped, sine and mixed inputs",
        "# (load pulses, NaN/inf) with different maxv, maxa and smooth-steps, one",
        f"# {period} ns thread.  Each output is scaled by 2^40 (exact) before the",
        "# sampler so that its 6 decimals compare the outputs bit for bit.",
        f"loadrt limit3 count={k}",
        f"loadrt threads name1=t period1={period}",
        f"loadrt streamer depth={n + 8} cfg={'fb' * k}",
        f"loadrt sampler depth={n + 8} cfg={'f' * k}",
        f"loadrt scale count={k}",
        "addf streamer.0 t",
    ]
    for i, (setp, _) in enumerate(cases):
        hal.append(f"net in{i} streamer.0.pin.{2 * i} => limit3.{i}.in")
        hal.append(f"net ld{i} streamer.0.pin.{2 * i + 1} => limit3.{i}.load")
        for p, v in setp.items():
            hal.append(f"setp limit3.{i}.{p} {v}")
        hal.append(f"addf limit3.{i} t")
    for i in range(k):
        hal.append(f"net o{i} limit3.{i}.out => scale.{i}.in")
        hal.append(f"net s{i} scale.{i}.out => sampler.0.pin.{i}")
        hal.append(f"setp scale.{i}.gain {GAIN!r}")
        hal.append(f"addf scale.{i} t")
    hal += [
        "addf sampler.0 t",
        "loadusr -w halstreamer in.txt",
        "start",
        f"loadusr -w halsampler -n {n + 3}",
    ]
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    with open(d / "in.txt", "w") as f:
        for j in range(n + 3):
            f.write(" ".join(f"{fmt(rows[j][0])} {rows[j][1]}" for _, rows in cases) + "\n")


def limits_cases(n: int) -> list[tuple[dict[str, str], list[tuple[float, float, float, int]]]]:
    """(setp values, rows of (in, min, max, enable)) for the limits test."""
    big = 1e20
    cases = []
    # 0: the input steps around a fixed max; approaches are to max
    rows = []
    for i in range(n):
        x = [0.5, 3.0, 1.2, 5.0, -1.0][(i // 60) % 5]
        rows.append((x, -big, 2.0, 1))
    cases.append(({"maxv": "4.0", "maxa": "900.0", "smooth-steps": "2"}, rows))
    # 1: the output starts below min (out is 0 at start): min is reached first
    rows = [(3.0 if i < 150 else 0.2, 1.0, big, 1) for i in range(n)]
    cases.append(({"maxv": "1e+20", "maxa": "1000.0", "smooth-steps": "0"}, rows))
    # 2: the output starts above max; the target is below min
    rows = [(-5.0, -1.5, -0.5, 1) for i in range(n)]
    cases.append(({"maxv": "2.5", "maxa": "750.5", "smooth-steps": "3"}, rows))
    # 3: enable toggles: out returns to 0 and back, per constraints
    rows = []
    for i in range(n):
        en = 0 if 100 <= i < 180 or 260 <= i < 262 else 1
        rows.append((1.75 if i < 220 else -0.6, -big, big, en))
    cases.append(({"maxv": "3.0", "maxa": "1200.0", "smooth-steps": "2"}, rows))
    # 4: min and max move while the input rests: the output follows the
    # clamped target, also from outside the new range
    rows = []
    for i in range(n):
        lo, hi = [(-big, big), (0.8, big), (0.8, 1.0), (-big, -0.25), (-0.5, 0.5)][(i // 64) % 5]
        rows.append((0.6, lo, hi, 1))
    cases.append(({"maxv": "1e+20", "maxa": "1500.0", "smooth-steps": "2"}, rows))
    return cases


def write_limits(d: Path, n: int) -> None:
    cases = limits_cases(n)
    k = len(cases)
    pins = ["in", "min", "max", "enable"]
    hal = [
        "# limit3: min/max and enable: approaches to a clamped target, an output",
        "# starting outside min..max, enable toggling, min/max moving while the",
        "# input rests.  Outputs scaled by 2^40 (exact) before the sampler.",
        f"loadrt limit3 count={k}",
        "loadrt threads name1=t period1=1000000",
        f"loadrt streamer depth={n + 8} cfg={'fffb' * k}",
        f"loadrt sampler depth={n + 8} cfg={'f' * k}",
        f"loadrt scale count={k}",
        "addf streamer.0 t",
    ]
    for i, (setp, _) in enumerate(cases):
        for j, p in enumerate(pins):
            hal.append(f"net {p}{i} streamer.0.pin.{4 * i + j} => limit3.{i}.{p}")
        for p, v in setp.items():
            hal.append(f"setp limit3.{i}.{p} {v}")
        hal.append(f"addf limit3.{i} t")
    for i in range(k):
        hal.append(f"net o{i} limit3.{i}.out => scale.{i}.in")
        hal.append(f"net s{i} scale.{i}.out => sampler.0.pin.{i}")
        hal.append(f"setp scale.{i}.gain {GAIN!r}")
        hal.append(f"addf scale.{i} t")
    hal += [
        "addf sampler.0 t",
        "loadusr -w halstreamer in.txt",
        "start",
        f"loadusr -w halsampler -n {n}",
    ]
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    with open(d / "in.txt", "w") as f:
        for j in range(n):
            f.write(
                " ".join(
                    " ".join(fmt(v) if isinstance(v, float) else str(v) for v in rows[j])
                    for _, rows in cases
                )
                + "\n"
            )


def main() -> None:
    root = HERE.parent
    write_track(root / "limit3-track", 500, 3)
    write_track(root / "limit3-period", 400, 11, period=250000, k=4)
    write_limits(root / "limit3-limits", 320)


if __name__ == "__main__":
    main()
