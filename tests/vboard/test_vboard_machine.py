# SPDX-License-Identifier: GPL-2.0-or-later
"""vboard --machine: a DC servo axis behind the 5i20's Verilog PWMGen and
Encoder, driven through registers only (no driver): the motor turns at the
speed its linear model gives for the PWM duty, the firmware's encoder
counts what the model's encoder put on the pins, the trace has one row per
host time, and bad machine files or requests fail with their reasons.

References: the DC motor's steady state w = Kt V / (R b + Kt Ke) (here
b = 0: w = V / Ke) and the hm2 PWMGen/Encoder register layout
(docs/hm2-pwmgen.md, docs/hm2-encoder.md)."""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from vbhelpers import stop_clean, vboard

AXIS = """board = "5i20"
firmware = "SVST8_4"
[[axis]]
name = "x"
lead_mm = 5
mass_kg = 10
hard_stops_mm = [-1000, 1000]
limit_max = { pin = "IO 24", at_mm = 2, active = "low" }
[axis.motor]
type = "dc"
resistance_ohm = 1.0
inductance_h = 1e-3
kt_nm_per_a = 0.08
ke_v_s_per_rad = 0.08
inertia_kg_m2 = 2e-5
[axis.amplifier]
a = "PWMGen 0 Out0"
b = "PWMGen 0 Out1"
bus_v = 24
enable = { pin = "PWMGen 0 NotEnable", active = "low" }
[axis.encoder]
a = "Encoder 0 A"
b = "Encoder 0 B"
index = "Encoder 0 Index"
counts_per_rev = 400
"""
ENC0_A, ENC0_B, ENC0_IDX = 3, 2, 5


@pytest.fixture
def machine_board(sockdir: Path) -> Iterator[vboard.VBoardProcess]:
    f = sockdir / "m.toml"
    f.write_text(AXIS)
    p = vboard.VBoardProcess(sockdir / "m.sock", "5i20", "SVST8_4", args=["--machine", str(f)])
    try:
        yield p
    finally:
        stop_clean(p)


def status(c: vboard.VBoardClient) -> dict[str, Any]:
    return json.loads(c.plant("status"))


def test_pwm_turns_the_motor_and_the_encoder_counts(machine_board: vboard.VBoardProcess) -> None:
    # 150 ms of board time in one request: a sanitized board on a loaded
    # machine needs more than the client's default 10 s for it
    with machine_board.client(timeout=300) as c:
        pins = c.probe(0, 6)
        assert pins[ENC0_A].ext == vboard.EXT_PLANT and pins[ENC0_B].ext == vboard.EXT_PLANT
        assert pins[ENC0_IDX].ext == vboard.EXT_PLANT
        st = status(c)["axes"][0]
        assert st["enabled"] is False and st["position"] == 0
        # PWMGen 0's pins (IO 7, 9, 11) driven by the module: DDR + AltSource.
        c.write(0x1100, 1 << 7 | 1 << 9 | 1 << 11)
        c.write(0x1200, 1 << 7 | 1 << 9 | 1 << 11)
        # 20 kHz, 12 bit, PWM/dir, double buffered; 25 % duty positive; enable.
        c.write(0x4200, 53687)
        c.write(0x4100, 0x3 | 1 << 5)
        c.write(0x4000, 1024 << 16)
        c.write(0x4400, 1)
        c.advance(150_000_000)  # 150 ms: 6 mechanical time constants
        st = status(c)["axes"][0]
        assert st["enabled"] is True
        # w = V / Ke with V = 24 * 1024/4096 (b = 0, no friction); mm/s
        w = 24 * 1024 / 4096 / 0.08
        want = w / (2 * math.pi) * 5
        assert st["velocity"] == pytest.approx(want, rel=2e-3)
        # the Verilog encoder's 16-bit count vs the model's
        count = c.read32(0x3000) & 0xFFFF
        assert abs(count - (st["encoder"]["count"] & 0xFFFF)) <= 1
        assert st["encoder"]["count"] == pytest.approx(st["position"] / 5 * 400, abs=2)
        # the limit switch beyond 2 mm: active low
        assert st["switches"]["limit_max"] is True
        assert c.pin(24).level == 0
        # disable: the bridge opens, the current is 0, the axis coasts on
        c.write(0x4400, 0)
        c.advance(1_000_000)
        st2 = status(c)["axes"][0]
        assert st2["enabled"] is False and st2["current"] == 0
        assert st2["velocity"] == pytest.approx(st["velocity"], rel=1e-3)  # no friction


def test_trace_rows_per_host_time(machine_board: vboard.VBoardProcess, sockdir: Path) -> None:
    trace = sockdir / "t.csv"
    with machine_board.client() as c, machine_board.client() as probe:
        c.read32(0x100, time_ns=1_000_000)  # takes the epoch
        probe.plant(f"trace {trace}")
        for k in range(1, 6):
            c.read32(0x100, time_ns=1_000_000 + k * 1_000_000)
            c.read32(0x100, time_ns=1_000_000 + k * 1_000_000)  # same cycle: no row
            probe.pin(0)  # a probe client (time 0): no row
        assert json.loads(probe.plant("trace off")) == {"rows": 5}
    rows = trace.read_text().splitlines()
    assert rows[0] == "host_ns,board_ns,x.pos,x.vel,x.current"
    hosts = [int(r.split(",")[0]) for r in rows[1:]]
    assert hosts == [1_000_000 + k * 1_000_000 for k in range(1, 6)]


def test_plant_request_errors(
    machine_board: vboard.VBoardProcess, svst: vboard.VBoardProcess
) -> None:
    with svst.client() as c:
        with pytest.raises(vboard.VBoardError) as e:
            c.plant("status")
        assert e.value.status == -95 and "no machine is attached" in str(e.value)
    with machine_board.client() as c:
        for cmd, text in [
            ("jump", "unknown command 'jump'"),
            ("trace off", "no trace is running"),
            ("trace /nonexistent/dir/t.csv", "cannot open /nonexistent/dir/t.csv"),
        ]:
            with pytest.raises(vboard.VBoardError) as e:
                c.plant(cmd)
            assert text in str(e.value)
        assert status(c)["axes"][0]["name"] == "x"  # still serving


@pytest.mark.parametrize(
    "edit,message",
    [
        (
            ("bus_v = 24", "bus_v = -24"),
            "m.toml:19: axis[0].amplifier.bus_v: value -24 is out of range",
        ),
        (("lead_mm = 5", "lead_mm = 5\nleadmm = 5"), "m.toml:6: axis[0].leadmm: unknown key"),
        (('"Encoder 0 B"', '"Encoder 12 B"'), 'no pin "Encoder 12 B" on board 5i20'),
        (('board = "5i20"', 'board = "5i25"'), "the file is for board 5i25, this board is a 5i20"),
    ],
)
def test_bad_machine_file(sockdir: Path, edit: tuple[str, str], message: str) -> None:
    f = sockdir / "m.toml"
    f.write_text(AXIS.replace(*edit, 1))
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--socket", str(sockdir / "x.sock"), "--board", "5i20"]
        + ["--machine", str(f)],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert r.returncode == 1
    assert message in r.stderr and str(f) in r.stderr
    assert not (sockdir / "x.sock").exists()
