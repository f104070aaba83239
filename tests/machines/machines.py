# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers of the example-machine tests: run an example through
tools/machine/hm2machine.py (vboard --machine + halrun -S) into a
directory, and the reference figures derived from its machine file."""

from __future__ import annotations

import math
import re
import sys
import tomllib
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "machines"
sys.path.insert(0, str(ROOT / "tools" / "machine"))

import hm2machine  # noqa: E402
from machinelib import Example, build_dir  # noqa: E402

NEEDS = [build_dir() / "bin" / p for p in ("vboard", "halrun", "vbplant", "halsampler")]


def example(name: str) -> Example:
    return Example.load(EXAMPLES / name)


def run(
    name: str,
    out: Path,
    events: list[tuple[float, str]] = [],
    after: list[str] = [],
    moves: list[list[float]] | None = None,
    machine_edit: tuple[str, str] | list[tuple[str, str]] | None = None,
    before: list[str] = [],
) -> dict[str, Any]:
    """The example's short run into out; machine_edit: (old, new) (or a
    list of them) replaced once in a copy of its machine file; before: HAL
    lines after the example's HAL file, before the e-stop reset."""
    ex = example(name)
    if moves is not None:
        ex.moves["short"] = moves
    ex.before = ex.before + before
    if machine_edit is not None:
        out.mkdir(parents=True, exist_ok=True)
        text = ex.machine.read_text()
        for old, new in machine_edit if isinstance(machine_edit, list) else [machine_edit]:
            assert old in text, old
            text = text.replace(old, new, 1)
        ex.machine = out / "machine.toml"
        ex.machine.write_text(text)
    return hm2machine.run(ex, out, True, events, after)


def tagged(out: Path, tag: str) -> list[str]:
    """Lines printed after 'loadusr -w echo @@tag' in the run's halrun.log."""
    lines = (out / "halrun.log").read_text().splitlines()
    i = lines.index(f"@@{tag}")
    vals = []
    for ln in lines[i + 1 :]:
        if ln.startswith("@@"):
            break
        if re.fullmatch(r"-?[0-9.e+-]+|TRUE|FALSE", ln.strip()):  # getp output only
            vals.append(ln.strip())
    return vals


def hal_setp(hal: Path) -> dict[str, float]:
    """The numeric setp values of a HAL file."""
    out = {}
    for ln in hal.read_text().splitlines():
        m = re.match(r"\s*setp\s+(\S+)\s+(-?[0-9.eE+-]+)\s*$", ln)
        if m:
            out[m.group(1)] = float(m.group(2))
    return out


def servo_fe_bound(name: str, axis: str, maxa: float) -> float:
    """Largest following error (pid.error, mm) a PID + FF1/FF2 loop should
    show on a trapezoid, derived from the plant:

    * the load torque the feed-forward does not know (Coulomb friction of
      motor and slide, gravity) needs V = tau R / Kt from the P term
      before the integrator takes it over: V / P;
    * the armature's current lags the FF2 voltage by tau_e = L / R: at the
      acceleration's step the velocity falls behind by a * tau_e, which the
      loop (natural frequency wn = sqrt(K P / tau_m)) works off in ~1/wn:
      a tau_e / wn;
    * the encoder's quantum (one count)."""
    ex = example(name)
    m = tomllib.loads(ex.machine.read_text())
    ax = next(a for a in m["axis"] if a["name"] == axis)
    mot = ax["motor"]
    gear = ax.get("gear", 1.0)
    r = ax["lead_mm"] * 1e-3 / (2 * math.pi * gear)  # m per motor rad
    R, L, kt, ke = (
        mot["resistance_ohm"],
        mot["inductance_h"],
        mot["kt_nm_per_a"],
        mot["ke_v_s_per_rad"],
    )
    j = mot["inertia_kg_m2"] + ax.get("mass_kg", 0) * r * r
    b = mot.get("viscous_nm_s_per_rad", 0) + ax.get("viscous_n_s_per_m", 0) * r * r
    tau = mot.get("friction_nm", 0) + ax.get("friction_n", 0) * r + abs(ax.get("gravity_n", 0)) * r
    k = kt * r * 1e3 / (R * b + kt * ke)  # mm/s per V
    tau_m = R * j / (R * b + kt * ke)
    gains = hal_setp(ex.hal)
    p = gains[f"pid-{axis}.Pgain"]
    wn = math.sqrt(k * p / tau_m)
    count = ax["lead_mm"] / ax["encoder"]["counts_per_rev"]
    return tau * R / kt / p + maxa * (L / R) / wn + count


def read_trace_axis(out: Path, axis: str, what: str) -> list[float]:
    """One column (pos, vel, current, steps, taken) of the run's trace."""
    lines = (out / "trace.csv").read_text().splitlines()
    col = lines[0].split(",").index(f"{axis}.{what}")
    return [float(ln.split(",")[col]) for ln in lines[1:]]
