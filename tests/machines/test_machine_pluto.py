# SPDX-License-Identifier: GPL-2.0-or-later
"""The Pluto-P servo lathe's other paths, end to end (pluto_servo, the
Verilog pluto_servo firmware, the machine models, simulated clock):

* pwm+dir output (`pwmdir 1`: UP = PWM, DN = direction, high when
  negative) into a `pwm_dir` bridge closes X's loop under the same
  following-error bound derived from the plant as up/down;
* the Pluto's watchdog: the host stops writing, the firmware floats its
  outputs 126-127 PWM periods (6.45-6.5 ms) after the last pet
  (docs/pluto-servo-firmware.md), the active-low amplifier enables go
  inactive, the axes coast to a stop over the distance Coulomb and
  viscous friction give (analytic, from the machine file);
* the spindle encoder's index where the machine file puts it: with
  index-enable set, pluto_servo's count restarts at the index, so the
  machine's count minus pluto's is index_count modulo the counts per
  turn."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path
from typing import Any

import pytest
from machines import NEEDS, example, read_trace_axis, run, servo_fe_bound, tagged

pytestmark = pytest.mark.requires_build(*NEEDS)

MAXA = 1000.0  # mm/s^2, the examples' limit3 maxa


def _axis(name: str) -> dict[str, Any]:
    m = tomllib.loads(example("pluto-lathe").machine.read_text())
    return next(a for a in m["axis"] if a["name"] == name)


def coast_distance(ax: dict[str, Any], v0: float) -> float:
    """How far (mm) a linear DC axis coasts from v0 mm/s with its bridge
    open: Coulomb deceleration c and viscous time constant tau (referred
    to the motor shaft, r = lead / 2 pi): tau v0 - c tau^2 ln(1 + v0/(c tau))."""
    mot = ax["motor"]
    r = ax["lead_mm"] * 1e-3 / (2 * math.pi)
    j = mot["inertia_kg_m2"] + ax["mass_kg"] * r * r
    tc = mot.get("friction_nm", 0) + ax["friction_n"] * r
    b = mot.get("viscous_nm_s_per_rad", 0) + ax["viscous_n_s_per_m"] * r * r
    c = tc / j * r * 1e3  # mm/s^2
    tau = j / b
    return tau * v0 - c * tau * tau * math.log(1 + v0 / (c * tau))


def test_pwm_dir_output_closes_the_loop(tmp_path: Path) -> None:
    before = ["setp pluto-servo.pwm.0.pwmdir 1"]
    edit = (
        'input = "up_down"\na = "UP0"\nb = "DN0"',
        'input = "pwm_dir"\na = "UP0"\nb = "DN0"\nnegative = "high"',
    )
    fig = run("pluto-lathe", tmp_path, before=before, machine_edit=edit)
    for a in "xz":
        f = fig["axes"][a]
        bound = servo_fe_bound("pluto-lathe", a, MAXA)
        assert 0 < f["max_fe"] < bound, (a, f, bound)
        assert f["enabled"] and not f["fault"]
        assert abs(f["final_pos"] - f["final_cmd"]) < 0.01, (a, f)
    v = read_trace_axis(tmp_path, "x", "vel")[80:190]
    assert sum(v) / len(v) == pytest.approx(-50, rel=0.01)


def test_pluto_watchdog_bite_coasts(tmp_path: Path) -> None:
    # pluto_servo.write leaves the thread during the -50 mm/s cruise
    events = [(0.1, "delf pluto-servo.write servo")]
    moves = [[0, 0, 0.01], [-30, -30, 0.45]]
    fig = run("pluto-lathe", tmp_path, events=events, moves=moves)
    for a in ("x", "z", "spindle"):
        cur = read_trace_axis(tmp_path, a, "current")
        vel = read_trace_axis(tmp_path, a, "vel")
        bite = next(i for i, c in enumerate(cur) if i > 100 and c == 0)
        # the last pet went out in period 100; 6.45-6.5 ms later it bites,
        # seen at the next servo period
        assert 106 <= bite <= 108, (a, bite)
        assert all(c == 0 for c in cur[bite:])
        speed = [abs(x) for x in vel[bite:]]
        assert all(b <= s for s, b in zip(speed, speed[1:])), a  # never driven again
    st = json.loads((tmp_path / "status.json").read_text())
    assert not any(a["enabled"] for a in st["axes"])
    for a in "xz":
        vel = read_trace_axis(tmp_path, a, "vel")
        pos = read_trace_axis(tmp_path, a, "pos")
        bite = next(
            i for i, c in enumerate(read_trace_axis(tmp_path, a, "current")) if i > 100 and c == 0
        )
        assert vel[bite] < -40 and vel[-1] == 0
        dist = coast_distance(_axis(a), -vel[bite])
        assert pos[bite] - pos[-1] == pytest.approx(dist, rel=0.01), a
        assert fig["axes"][a]["final_pos"] > -30  # it never got there


def test_spindle_index_where_the_machine_puts_it(tmp_path: Path) -> None:
    events = [(0.1, "setp pluto-servo.encoder.2.index-enable 1")]
    after = ["loadusr -w echo @@idx"] + [
        "getp pluto-servo.encoder.2.count",
        "getp pluto-servo.encoder.2.index-enable",
    ]
    edit = ('index = "QZ2"\n', 'index = "QZ2"\nindex_count = 700\n')
    run("pluto-lathe", tmp_path, events=events, after=after, machine_edit=edit)
    count, enable = tagged(tmp_path, "idx")
    assert enable == "FALSE"  # the index came and cleared it
    turns = read_trace_axis(tmp_path, "spindle", "pos")
    model = turns[-1] * 2000  # the spindle encoder's count at the last servo read
    assert turns[100] * 2000 < model - 2000  # it turned more than once since
    assert 0 < int(count) < model
    # the count was restarted at count 700 of some turn (+-1: where in
    # the index count the firmware's latch took it, the read's timing)
    latched = (model - int(count)) % 2000
    assert abs(latched - 700) <= 1.5, (model, count)
