# SPDX-License-Identifier: GPL-2.0-or-later
"""The example machines (examples/machines) end to end: the real drivers
(hostmot2 + hm2_sim / hm2_7i43, pluto_servo, pluto_step) and the real
Verilog on virtual boards with machine models, on the simulated clock,
with shortened moves.

References: the following-error bound derived from each servo axis's
plant (machines.servo_fe_bound: load torque over P, current lag over the
loop's natural frequency, one count); for steppers the step count a target
asks for, floor(target * steps/mm), since the targets sit half a step off
the step boundaries; the drive's timing data (G203V); for faults the
safety chain of the HAL files (estop_latch drops the enables, the
amplifiers open, the axis coasts: its speed falls monotonically to 0)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from machines import EXAMPLES, NEEDS, ROOT, read_trace_axis, run, servo_fe_bound, tagged

TOOLS = ROOT / "tools" / "machine"

pytestmark = pytest.mark.requires_build(*NEEDS)

MAXA = 1000.0  # mm/s^2, the examples' limit3 maxa


@pytest.mark.parametrize("name,axes", [("servo-mill", "xyz"), ("pluto-lathe", "xz")])
def test_servo_trapezoid_following_error(tmp_path: Path, name: str, axes: str) -> None:
    fig = run(name, tmp_path)
    for a in axes:
        f = fig["axes"][a]
        bound = servo_fe_bound(name, a, MAXA)
        print(f"{name} {a}: max FE {f['max_fe'] * 1000:.1f} um, bound {bound * 1000:.1f} um")
        assert f["max_fe"] < bound, (a, f, bound)
        assert f["max_fe"] > 0  # it moved through a real loop
        assert f["enabled"] and not f["fault"]
        assert abs(f["final_pos"] - f["final_cmd"]) < 0.01, (a, f)
        assert abs(f["final_cmd"]) == 10  # the whole 10 mm move at 50 mm/s was made
    # the move had a 50 mm/s cruise (60..200 ms): the slide really went at it
    for a in axes:
        v = read_trace_axis(tmp_path, a, "vel")[80:190]
        assert abs(sum(v) / len(v)) == pytest.approx(50, rel=0.01)


def test_hm2_stepper_ends_on_the_step(tmp_path: Path) -> None:
    after = ["loadusr -w echo @@counts"] + [
        f"getp hm2_7i43.0.stepgen.0{i}.counts" for i in range(3)
    ]
    fig = run("stepper-7i43", tmp_path, after=after)
    counts = [int(c) for c in tagged(tmp_path, "counts")]
    assert fig["violations"] == 0
    for i, a in enumerate("xyz"):
        f = fig["axes"][a]
        s = f["steps"]
        want = math.floor(f["final_cmd"] * 400)
        assert s["taken"] == want == counts[i], (a, f, counts)
        assert s["commanded"] == want and s["missed"] == 0 and s["violations"] == 0
        # the glass scale (1 um) sees the slide where the steps put it
        scale = json.loads((tmp_path / "status.json").read_text())
        st = next(x for x in scale["axes"] if x["name"] == a)
        assert st["scale"]["count"] == pytest.approx(f["final_pos"] * 1000, abs=1.5)


def test_pluto_stepper_ends_on_its_step(tmp_path: Path) -> None:
    fig = run("pluto-step-mill", tmp_path)
    assert fig["violations"] == 0
    for a in "xyz":
        f = fig["axes"][a]
        s = f["steps"]
        # the drive took exactly the steps the firmware put out (the
        # firmware's own position, position-fb); pluto_step's position loop
        # stops within one step of the command (its deadband), and its
        # position-fb says so
        assert s["taken"] == s["commanded"] == math.floor(f["final_fb"] * 400), (a, f)
        assert abs(f["final_fb"] - f["final_cmd"]) * 400 < 1
        assert s["missed"] == 0 and s["violations"] == 0


def test_dirsetup_too_short_loses_position(tmp_path: Path) -> None:
    # X's drive needs its direction 3 ms before a step (a slow opto input),
    # the stepgen's dirsetup stays at the G203V's 200 ns: at each reversal
    # the first step comes ~1-2 ms after the direction change (limit3's
    # ramp through zero speed), so the drive steps the old way once.
    fig = run(
        "stepper-7i43",
        tmp_path,
        machine_edit=('model = "G203V"', 'model = "G203V"\ndir_setup_ns = 3000000'),
    )
    x = fig["axes"]["x"]["steps"]
    assert x["violations"] >= 1 and x["missed"] != 0
    assert x["taken"] != math.floor(fig["axes"]["x"]["final_cmd"] * 400)
    # a step taken the wrong way is 2 off; a violation may also fall on a
    # step whose old and new direction agree (the direction flickered)
    assert x["missed"] % 2 == 0 and abs(x["missed"]) <= 2 * x["violations"]
    for a in "yz":  # the other drives have the G203V's data: exact
        assert fig["axes"][a]["steps"]["violations"] == 0
        assert fig["axes"][a]["steps"]["missed"] == 0


SHORT_X = [[0, 0, 0, 0.01], [10, 0, 0, 0.2]]


def test_pwm_saturation_trips_the_estop(tmp_path: Path) -> None:
    # A command the motor cannot follow (limit3 opened up): the PID output
    # saturates at maxoutput, the error passes pid maxerror (1 mm), the
    # window comparator faults estop_latch, the amplifiers are disabled.
    after = ["loadusr -w echo @@chain"] + [
        "getp estop.fault-out",
        "getp hm2_5i20.0.pwmgen.00.enable",
    ]
    events = [(0.0, "setp lim-x.maxv 5000"), (0.0, "setp lim-x.maxa 1000000")]
    fig = run("servo-mill", tmp_path, events=events, after=after, moves=SHORT_X)
    fault, enable = tagged(tmp_path, "chain")
    assert fault == "TRUE" and enable == "FALSE"
    # the PID output (sampled: x.out) sat at maxoutput (48 V) before the trip
    out = [float(r.split()[3]) for r in (tmp_path / "samples.txt").read_text().splitlines()]
    assert max(out) == 48 and out[-1] == 0
    x = fig["axes"]["x"]
    assert not x["enabled"] and x["max_fe"] > 1.0
    v = read_trace_axis(tmp_path, "x", "vel")
    cur = read_trace_axis(tmp_path, "x", "current")
    assert max(abs(c) for c in cur) > 10  # it was pushing hard
    assert cur[-1] == 0 and v[-1] == 0  # amp open, axis stopped
    assert x["final_pos"] < 10  # it never got there


def test_watchdog_bite_disables_and_coasts(tmp_path: Path) -> None:
    # The host stops writing (hm2 write removed) during the 50 mm/s cruise:
    # no more pets, the watchdog bites 5 ms later, every hm2 pin floats
    # high: NotEnable high = amplifiers off; the axes coast to a stop.
    after = ["loadusr -w echo @@wd", "getp hm2_5i20.0.watchdog.has_bit"]
    events = [(0.1, "delf hm2_5i20.0.write servo")]
    moves = [[0, 0, 0, 0.01], [30, 0, 0, 0.45]]
    fig = run("servo-mill", tmp_path, events=events, after=after, moves=moves)
    assert tagged(tmp_path, "wd") == ["TRUE"]
    for a in "xyz":
        assert not fig["axes"][a]["enabled"]
    v = read_trace_axis(tmp_path, "x", "vel")
    cur = read_trace_axis(tmp_path, "x", "current")
    pos = read_trace_axis(tmp_path, "x", "pos")
    bite = next(i for i, c in enumerate(cur) if i > 100 and c == 0)
    assert 100 < bite <= 107  # 5 ms timeout (+ the period it takes to see it)
    assert v[bite] > 40  # it was cruising
    coast = v[bite:]
    assert all(b <= a for a, b in zip(coast, coast[1:]))  # slows down, never back
    assert coast[-1] == 0 and pos[-1] < 30
    # Coasting against Coulomb (deceleration c) and viscous friction (time
    # constant tau): it stops after tau v0 - c tau^2 ln(1 + v0 / (c tau)).
    r = 5e-3 / (2 * math.pi)
    j = 1.5e-4 + 60 * r * r
    c = (0.01 + 40 * r) / j * r * 1e3  # mm/s^2
    tau = j / (200 * r * r)
    v0 = v[bite]
    dist = tau * v0 - c * tau * tau * math.log(1 + v0 / (c * tau))
    assert pos[-1] - pos[bite] == pytest.approx(dist, rel=0.01)


def test_runs_are_byte_identical(tmp_path: Path) -> None:
    run("pluto-lathe", tmp_path / "a")
    run("pluto-lathe", tmp_path / "b")
    for f in ("samples.txt", "trace.csv", "status.json", "figures.json"):
        assert (tmp_path / "a" / f).read_bytes() == (tmp_path / "b" / f).read_bytes(), f
    # The lathe's spindle at 40 % of 36 V, through a 2:1 belt: steady speed
    # w = (Kt V - R Tc) / (R b + Kt Ke) on the motor (Tc, b referred to it),
    # reached after ~6 mechanical time constants; its encoder (2000 counts
    # per spindle turn) counted the turns.
    st = json.loads((tmp_path / "a" / "status.json").read_text())
    sp = next(a for a in st["axes"] if a["name"] == "spindle")
    tc, b = 0.02 + 0.1 / 2, 1e-3 / 4
    w = (0.1 * 14.4 - 0.8 * tc) / (0.8 * b + 0.1 * 0.1)
    assert sp["unit"] == "rev" and sp["velocity"] == pytest.approx(w / 2 / (2 * math.pi), rel=0.005)
    assert sp["scale"]["count"] == pytest.approx(sp["position"] * 2000, abs=2)


def test_hm2tune_auto_tunes_a_servo_axis(tmp_path: Path) -> None:
    # The Pluto lathe's X: identification, pole placement over three
    # natural frequencies, the pick with <= 1 % overshoot and the smallest
    # following error; the identified plant against the machine file's
    # numbers (K = Kt r / (R b + Kt Ke) in mm/s per V, tau = R J / (R b + Kt Ke)).
    r = subprocess.run(
        [sys.executable, str(TOOLS / "hm2tune.py"), str(EXAMPLES / "pluto-lathe"), "--axis", "x"]
        + ["--auto", "--wn", "90,130,250", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    res = json.loads((tmp_path / "tune.json").read_text())
    rr = 5e-3 / (2 * math.pi)
    b = 100 * rr * rr
    k = 0.06 * rr * 1e3 / (1.5 * b + 0.06 * 0.06)
    tau = 1.5 * (8e-5 + 10 * rr * rr) / (1.5 * b + 0.06 * 0.06)
    assert res["plant"]["K"] == pytest.approx(k, rel=0.05)
    assert res["plant"]["tau"] == pytest.approx(tau, rel=0.15)
    after = res["after"]
    assert after["overshoot_pct"] <= 1.0
    assert after["max_fe"] <= res["before"]["max_fe"]
    assert res["wn"] in (90, 130, 250)
    assert (tmp_path / "tune-pluto-lathe-x.png").stat().st_size > 10000
    assert "tuned (wn" in r.stdout and "Pgain=" in r.stdout


def test_hm2machine_errors(tmp_path: Path) -> None:
    bad = tmp_path / "ex"
    bad.mkdir()
    (bad / "example.toml").write_text('title = "x"\nboard = "5i20"\n')
    r = subprocess.run(
        [sys.executable, str(TOOLS / "hm2machine.py"), str(bad)], capture_output=True, text=True
    )
    assert r.returncode == 1 and "example.toml: missing or bad key" in r.stderr
    r = subprocess.run(
        [sys.executable, str(TOOLS / "hm2tune.py"), str(EXAMPLES / "stepper-7i43"), "--axis", "x"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 1 and "samples no pid.error" in r.stderr
