# SPDX-License-Identifier: GPL-2.0-or-later
"""The example machines' other inputs and failure modes, end to end (real
driver, Verilog firmware, machine models, simulated clock):

* the hm2 PWMGen's other output types into the amplifier model: PDM/dir
  (type 3), dir/PWM (type 4, the machine's pins swapped) and up/down
  (type 2) close the same loops as PWM/dir, under the same
  following-error bound derived from the plant (machines.servo_fe_bound);
* a limit switch reached: the machine's switch pin goes active at its
  at_mm, the HAL file's safety chain (estop_latch) drops the enables, the
  slide coasts to a stop short of the hard stop; the home switch reads
  active inside its window;
* a stepgen accelerating beyond what the stepper's torque can give the
  load: the rotor slips (counted), the slide loses position although every
  step arrived with the drive's timing.  Reference: the largest
  acceleration the motor gives the load at standstill,
  (T_pullout(0) - T_friction) / J, from the machine file."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import pytest
from machines import NEEDS, example, read_trace_axis, run, servo_fe_bound, tagged

pytestmark = pytest.mark.requires_build(*NEEDS)

MAXA = 1000.0  # mm/s^2, the examples' limit3 maxa


def test_pdm_dir_pwm_and_up_down_close_the_loop(tmp_path: Path) -> None:
    # X: PDM + direction at 2 MHz; Y: direction on Out0, PWM on Out1 (the
    # amplifier's inputs rewired to match); Z: up/down into an up/down
    # bridge (hm2's Out1 carries the PWM for positive values, Out0 for
    # negative ones: Out1 is the bridge's + input).
    before = [
        "setp hm2_5i20.0.pwmgen.pdm_frequency 2000000",
        "setp hm2_5i20.0.pwmgen.00.output-type 3",
        "setp hm2_5i20.0.pwmgen.01.output-type 4",
        "setp hm2_5i20.0.pwmgen.02.output-type 2",
    ]
    edits = [
        ('a = "PWMGen 1 Out0"\nb = "PWMGen 1 Out1"', 'a = "PWMGen 1 Out1"\nb = "PWMGen 1 Out0"'),
        (
            'input = "pwm_dir"\na = "PWMGen 2 Out0"\nb = "PWMGen 2 Out1"',
            'input = "up_down"\na = "PWMGen 2 Out1"\nb = "PWMGen 2 Out0"',
        ),
    ]
    fig = run("servo-mill", tmp_path, machine_edit=edits, before=before)
    for a in "xyz":
        f = fig["axes"][a]
        bound = servo_fe_bound("servo-mill", a, MAXA)
        assert 0 < f["max_fe"] < bound, (a, f, bound)
        assert f["enabled"] and not f["fault"]
        assert abs(f["final_cmd"]) == 10
        assert abs(f["final_pos"] - f["final_cmd"]) < 0.01, (a, f)
    # the cruise really was at 50 mm/s on every axis
    for a in "xyz":
        v = read_trace_axis(tmp_path, a, "vel")[80:190]
        assert abs(sum(v) / len(v)) == pytest.approx(50, rel=0.01)


def coast_distance(v0: float, mass: float, friction_n: float, viscous: float) -> float:
    """How far (mm) a servo-mill axis (5 mm lead, the motor's 1.5e-4 kg m^2
    and 0.01 N m) coasts from v0 mm/s against Coulomb (deceleration c) and
    viscous friction (time constant tau): tau v0 - c tau^2 ln(1 + v0/(c tau))."""
    r = 5e-3 / (2 * math.pi)
    j = 1.5e-4 + mass * r * r
    c = (0.01 + friction_n * r) / j * r * 1e3  # mm/s^2
    tau = j / (viscous * r * r)
    return tau * v0 - c * tau * tau * math.log(1 + v0 / (c * tau))


def test_limit_switch_trips_the_estop(tmp_path: Path) -> None:
    # X starts at 145 mm (its encoder counts from there): the 10 mm move
    # runs into limit_max at 150 mm, 10 mm before the hard stop.
    after = ["loadusr -w echo @@io"] + [
        "getp estop.fault-out",
        "getp hm2_5i20.0.pwmgen.00.enable",
        "getp hm2_5i20.0.gpio.025.in_not",
        "getp hm2_5i20.0.gpio.026.in",
        "getp hm2_5i20.0.gpio.024.in_not",
    ]
    moves = [[0, 0, 0, 0.01], [10, 0, 0, 0.45]]  # 0.3 s of coasting
    fig = run(
        "servo-mill",
        tmp_path,
        machine_edit=('name = "x"\n', 'name = "x"\nposition_mm = 145\n'),
        moves=moves,
        after=after,
    )
    fault, enable, lim_max, home, lim_min = tagged(tmp_path, "io")
    assert (fault, enable, lim_max, lim_min) == ("TRUE", "FALSE", "TRUE", "FALSE")
    assert home == "TRUE"  # inside 130..160 mm
    x = fig["axes"]["x"]
    assert not x["enabled"] and x["stop_hits"] == 0
    pos = read_trace_axis(tmp_path, "x", "pos")
    vel = read_trace_axis(tmp_path, "x", "vel")
    cur = read_trace_axis(tmp_path, "x", "current")
    hit = next(i for i, p in enumerate(pos) if p >= 150)
    assert all(c != 0 for c in cur[hit - 20 : hit])  # driven up to the switch
    # the switch is read at the next servo period, the latch and the
    # disable are written in it: the amplifier is open within 2 periods
    off = next(i for i, c in enumerate(cur) if i > hit and c == 0)
    assert off - hit <= 2, (hit, off)
    assert all(c == 0 for c in cur[off:])
    # then it coasts, slower and slower, as far as friction lets it
    assert all(b <= a for a, b in zip(vel[off:], vel[off + 1 :])) and vel[-1] == 0
    dist = coast_distance(vel[off], 60, 40, 200)
    assert pos[-1] - pos[off] == pytest.approx(dist, rel=0.01)
    assert x["final_pos"] < 160


def _stall_accel(axis: str) -> float:
    """Largest acceleration (mm/s^2) the stepper gives its slide from rest."""
    m = tomllib.loads(example("stepper-7i43").machine.read_text())
    ax = next(a for a in m["axis"] if a["name"] == axis)
    mot = ax["motor"]
    r = ax["lead_mm"] * 1e-3 / (2 * math.pi)  # m per motor rad
    j = mot["inertia_kg_m2"] + ax["mass_kg"] * r * r
    tf = mot["friction_nm"] + ax["friction_n"] * r
    return (mot["torque_curve"][0][1] - tf) / j * r * 1e3


def test_stepper_accelerating_beyond_its_torque_stalls(tmp_path: Path) -> None:
    amax = _stall_accel("x")  # ~22000 mm/s^2
    before = [
        f"setp hm2_7i43.0.stepgen.00.maxaccel {4 * amax:.0f}",
        "setp lim-x.maxa 10000000",
        "setp lim-x.maxv 5000",
    ]
    fig = run("stepper-7i43", tmp_path, before=before)
    x = fig["axes"]["x"]["steps"]
    status = json.loads((tmp_path / "status.json").read_text())
    sx = next(a for a in status["axes"] if a["name"] == "x")["steps"]
    assert sx["stall_slips"] != 0
    assert x["violations"] == 0  # every step arrived in time: the motor lost them
    # the drive took every step (its count of the pin's edges), the rotor
    # did not follow: what is missing is whole electrical periods, 4 full
    # steps (40 microsteps) per slip counted
    assert x["accepted"] == sx["edges"] and sx["drive_position"] == x["commanded"]
    assert x["missed"] != 0 and x["taken"] != x["commanded"]
    assert x["missed"] == 40 * sx["stall_slips"]
    assert abs(fig["axes"]["x"]["final_pos"] - fig["axes"]["x"]["final_cmd"]) > 1
    # Y and Z kept the example's 2000 mm/s^2: exact
    for a in "yz":
        s = fig["axes"][a]["steps"]
        assert s["missed"] == 0 and s["taken"] == s["commanded"]
