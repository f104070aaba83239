# SPDX-License-Identifier: GPL-2.0-or-later
"""pluto_servo and pluto_step end to end: the real HAL drivers over the sim:
epp_port backend against the Verilated Pluto-P firmwares in bin/vboard
(pin-level EPP, passive-serial upload), on HAL's simulated clock.

Expected values come from spec/pluto.md formulas (PWM duty = value/scale on
UP or DN, step counts = position * scale, the ~6.5 ms watchdog, the 10 us
EPP timeout), not from the implementation."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "hm2"))
import hm2e2e as e2e  # noqa: E402
from hm2e2e import vboard  # noqa: E402

PLUTO_SERVO = e2e.BUILD / "lib" / "rtlib" / "pluto_servo.so"
FIRMWARE = e2e.BUILD / "lib" / "firmware"
pytestmark = pytest.mark.requires_build(
    e2e.HALRUN, e2e.VBOARD, PLUTO_SERVO, FIRMWARE / "pluto_servo.rbf"
)

# Fixed pin numbering of the virtual Pluto-P (docs/vboard.md).
OUT = 0  # OUT0..: pins 0..
SERVO_UP0, SERVO_DN0, SERVO_LED = 10, 11, 18
STEP0, DIR0 = 14, 15
IN0 = 23
QZ0, QB0, QA0 = IN0 + 8, IN0 + 12, IN0 + 16


def servo(sock: Path, extra: str = "") -> str:
    return (
        f"loadrt pluto_servo port=sim:{sock} {extra}\n"
        "loadrt threads name1=servo period1=1000000\n"
        "addf pluto-servo.read servo\n"
        "addf pluto-servo.write servo\n"
    )


def step(sock: Path, extra: str = "") -> str:
    return (
        f"loadrt pluto_step port=sim:{sock} {extra}\n"
        "loadrt threads name1=servo period1=1000000\n"
        "addf pluto-step.read servo\n"
        "addf pluto-step.write servo\n"
    )


def pins(out: str, key: str) -> list[dict[str, int]]:
    v = e2e.values(out)[key]
    return json.loads(v[0])


def getp(out: str, key: str) -> str:
    return e2e.values(out)[key][0]


def board(tmp_path: Path, firmware: str | None = None) -> vboard.VBoardProcess:
    return vboard.VBoardProcess(tmp_path / "pluto.sock", "pluto", firmware)


# ---------------------------------------------------------------- upload


@pytest.mark.parametrize("comp,fw", [("pluto_servo", "pluto_servo"), ("pluto_step", "pluto_step")])
def test_upload_configures_a_blank_board(tmp_path: Path, comp: str, fw: str) -> None:
    with board(tmp_path) as b:
        with b.client() as c:
            h = c.hello()
            assert h.state == 0 and h.firmware == ""
            # blank: every pin floats (LED faint)
            assert all(p.oe == 0 for p in c.probe(0, 43))
        mk = servo if comp == "pluto_servo" else step
        r = e2e.halrun(tmp_path, mk(b.socket_path) + "simrun 2ms\n")
        assert r.returncode == 0, r.stdout + r.stderr
        assert "uploading firmware" in r.stdout + r.stderr
        with b.client() as c:
            h = c.hello()
            assert h.state == 1 and h.firmware == fw
            assert h.clock_low_hz == 40_000_000
        assert f"configured with {fw}" in b.stderr_so_far()


@pytest.mark.parametrize(
    "what,make",
    [
        ("truncated", lambda good: good[:40]),
        ("corrupt", lambda good: good[:20] + bytes([good[20] ^ 0x55]) + good[21:]),
        (
            "other firmware file",
            lambda good: (FIRMWARE / "hm2" / "5i20" / "SVST8_4.BIT").read_bytes(),
        ),
        ("garbage", lambda good: bytes(range(200))),
    ],
)
def test_bad_image_leaves_the_board_unconfigured(tmp_path: Path, what: str, make: object) -> None:
    good = (FIRMWARE / "pluto_servo.rbf").read_bytes()
    (tmp_path / "bad.rbf").write_bytes(make(good))  # type: ignore[operator]
    with board(tmp_path) as b:
        r = e2e.halrun(
            tmp_path, servo(b.socket_path, f"firmware={tmp_path / 'bad.rbf'}") + "show comp\n"
        )
        out = r.stdout + r.stderr
        assert "Failed to communicate with pluto-servo board after programming firmware." in out
        assert (
            "pluto-servo" not in out.split("Loaded HAL Components:")[-1]
            if "Loaded HAL" in out
            else True
        )
        with b.client() as c:
            h = c.hello()
            assert h.state == 0 and h.firmware == "", what
            assert all(p.oe == 0 for p in c.probe(0, 43))
        if what != "truncated":
            assert "configuration failed, board stays blank" in b.stderr_so_far()


def test_reupload_replaces_running_firmware(tmp_path: Path) -> None:
    with board(tmp_path, "pluto_step") as b:
        r = e2e.halrun(tmp_path, servo(b.socket_path) + "simrun 1ms\n")
        assert r.returncode == 0, r.stdout + r.stderr
        with b.client() as c:
            assert c.hello().firmware == "pluto_servo"


# ---------------------------------------------------------------- servo


def test_digital_outputs_and_inputs(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = servo(s) + (
            "setp pluto-servo.dout.00 1\n"
            "setp pluto-servo.dout.03 1\n"
            "setp pluto-servo.dout.04-invert 1\n"
            # dout.10 is XORed into UP0 while PWM 0 is enabled (spec 4.2:
            # value 0 -> UP0 = dout.10); dout.13 has no effect on a
            # disabled channel (word 0)
            "setp pluto-servo.pwm.0.enable 1\n"
            "setp pluto-servo.dout.10 1\n"
            "setp pluto-servo.dout.13 1\n"
            + e2e.probe(s, "drive", IN0, "low")
            + e2e.probe(s, "drive", IN0 + 5, "high")
            + e2e.probe(s, "drive", QA0, "low")  # shared pin: din.16
            + "simrun 3ms\n"
            + e2e.probe(s, "probe", "outs", ",".join(str(p) for p in range(0, 12)))
            + e2e.probe(s, "probe", "up1", "12,13")
            + e2e.tag("in0", "pluto-servo.din.00", "pluto-servo.din.00-not")
            + e2e.tag("in5", "pluto-servo.din.05")
            + e2e.tag("in1", "pluto-servo.din.01")
            + e2e.tag("qa0", "pluto-servo.din.16")
        )
        r = e2e.halrun(tmp_path, script)
        out = r.stdout + r.stderr
        o = pins(out, "outs")
        level = [p["level"] for p in o]
        assert all(p["oe"] == 1 for p in o)
        assert level[0] == 1 and level[3] == 1
        assert level[1] == 0 and level[2] == 0
        assert level[4] == 1  # inverted 0
        assert level[SERVO_UP0] == 1 and level[SERVO_DN0] == 0
        up1 = pins(out, "up1")
        assert [p["level"] for p in up1] == [0, 0]
        v = e2e.values(out)
        assert v["in0"] == ["FALSE", "TRUE"]
        assert v["in5"] == ["TRUE"]
        assert v["in1"] == ["TRUE"]  # undriven input: pulled up
        assert v["qa0"] == ["FALSE"]


@pytest.mark.parametrize(
    "value,pwmdir", [(0.25, 0), (-0.6, 0), (0.4, 1), (-0.75, 1), (0.0, 0), (1.0, 0)]
)
def test_pwm_duty_on_the_pins(tmp_path: Path, value: float, pwmdir: int) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = servo(s) + (
            f"setp pluto-servo.pwm.0.value {value}\n"
            "setp pluto-servo.pwm.0.enable 1\n"
            f"setp pluto-servo.pwm.0.pwmdir {pwmdir}\n"
            "simrun 2ms\n"
            + e2e.probe(s, "reset", f"{SERVO_UP0},{SERVO_DN0}")
            + "simrun 4ms\n"
            + e2e.probe(s, "probe", "pwm", f"{SERVO_UP0},{SERVO_DN0}")
        )
        r = e2e.halrun(tmp_path, script)
        up, dn = pins(r.stdout + r.stderr, "pwm")
        duty = [p["high_total_ns"] / p["total_ns"] for p in (up, dn)]
        want = min(abs(value), 1.0)
        if pwmdir == 0:
            # up/down: the magnitude on UP for positive values, on DN for negative
            hot, cold = (0, 1) if value >= 0 else (1, 0)
            assert duty[hot] == pytest.approx(want, abs=0.01)
            assert duty[cold] == pytest.approx(0.0, abs=0.001)
        else:
            # pwm+dir: PWM on UP, direction on DN (1 = negative)
            assert duty[0] == pytest.approx(want, abs=0.01)
            assert duty[1] == pytest.approx(1.0 if value < 0 else 0.0, abs=0.001)
        if 0 < want < 1:
            # ~19.5 kHz: 40 MHz / 2047 (spec 3.2), on the pin that pulses
            pulsing = dn if (pwmdir == 0 and value < 0) else up
            assert pulsing["period_ns"] == pytest.approx(2047 * 25, abs=50)


def test_encoder_counts_and_index(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = servo(s) + (
            "setp pluto-servo.encoder.0.scale 4\n"
            + e2e.probe(s, "quad", QA0, QB0, 20000, QZ0, 100)
            + "simrun 10ms\n"
            + e2e.tag(
                "a",
                "pluto-servo.encoder.0.count",
                "pluto-servo.encoder.0.position",
                "pluto-servo.encoder.0.velocity",
            )
            + "setp pluto-servo.encoder.0.index-enable 1\n"
            + "simrun 10ms\n"
            + e2e.tag("b", "pluto-servo.encoder.0.index-enable", "pluto-servo.encoder.0.count")
            + e2e.probe(s, "quad", QA0, QB0, -20000, QZ0, 100)
            + "simrun 10ms\n"
            + e2e.tag("c", "pluto-servo.encoder.0.count", "pluto-servo.encoder.0.velocity")
        )
        r = e2e.halrun(tmp_path, script)
        v = e2e.values(r.stdout + r.stderr)
        count = int(v["a"][0])
        # 20000 counts/s for ~10 ms (the last read sees up to one period less)
        assert 170 <= count <= 210
        assert float(v["a"][1]) == pytest.approx(count / 4)
        assert float(v["a"][2]) == pytest.approx(20000 / 4, rel=0.1)
        # the first index after index-enable cleared it and zeroed the count
        # there: it came within one index period (100 counts) plus a servo
        # period (20 counts) of enabling, so ~200 counts later the count is
        # 80..215 (without the reset it would be ~400)
        assert v["b"][0] == "FALSE"
        assert 80 <= int(v["b"][1]) <= 215
        assert float(v["c"][1]) == pytest.approx(-20000 / 4, rel=0.1)


def test_watchdog_bites_after_the_host_stops(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = servo(s) + (
            "setp pluto-servo.dout.00 1\n"
            "simrun 3ms\n"
            "delf pluto-servo.write servo\n"
            "simrun 5ms\n"
            + e2e.probe(s, "probe", "at5", "0")
            + "simrun 3ms\n"
            + e2e.probe(s, "probe", "at8", "0")
        )
        r = e2e.halrun(tmp_path, script)
        out = r.stdout + r.stderr
        # the last pet was at ~3 ms; the watchdog is ~6.5 ms (spec 3.3)
        assert pins(out, "at5")[0]["oe"] == 1
        assert pins(out, "at8")[0]["oe"] == 0


def test_epp_timeout_sets_communication_error(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = servo(s) + (
            "simrun 2ms\n"
            + e2e.tag("before", "pluto-servo.communication-error")
            + e2e.probe(s, "stall", "on")
            + "simrun 3ms\n"
            + e2e.tag("stalled", "pluto-servo.communication-error")
            + e2e.probe(s, "stall", "off")
            + "simrun 2ms\n"
            + e2e.tag("frozen", "pluto-servo.communication-error")
            + "setp pluto-servo.communication-error 0\n"
            + "simrun 2ms\n"
            + e2e.tag("after", "pluto-servo.communication-error")
        )
        r = e2e.halrun(tmp_path, script)
        v = e2e.values(r.stdout + r.stderr)
        assert v["before"] == ["0"]
        assert int(v["stalled"][0]) >= 1
        assert int(v["frozen"][0]) >= 1  # stays until the user clears it
        assert v["after"] == ["0"]


# ---------------------------------------------------------------- step


def test_stepgen_steps_and_timing_on_the_pins(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        s = b.socket_path
        script = step(s) + (
            "setp pluto-step.stepgen.0.scale 1000\n"
            "setp pluto-step.stepgen.0.enable 1\n"
            "setp pluto-step.stepgen.steplen 5000\n"
            "setp pluto-step.stepgen.stepspace 5000\n"
            "setp pluto-step.stepgen.dirtime 20000\n"
            "setp pluto-step.stepgen.0.position-cmd 0.05\n"
            "simrun 30ms\n"
            + e2e.probe(s, "probe", "s1", f"{STEP0},{DIR0}")
            + e2e.tag("fb1", "pluto-step.stepgen.0.counts", "pluto-step.stepgen.0.position-fb")
            + "setp pluto-step.stepgen.0.position-cmd 0.02\n"
            "simrun 30ms\n"
            + e2e.probe(s, "probe", "s2", f"{STEP0},{DIR0}")
            + e2e.tag("fb2", "pluto-step.stepgen.0.counts")
        )
        r = e2e.halrun(tmp_path, script)
        out = r.stdout + r.stderr
        st, d = pins(out, "s1")
        v = e2e.values(out)
        c1, c2 = int(v["fb1"][0]), int(v["fb2"][0])
        # the driver closes the position loop in velocity (spec 6.2): it
        # ends within a step of the command, and its feedback counts are
        # exactly the steps that came out of the STEP pin
        assert abs(c1 - 50) <= 1 and abs(c2 - 20) <= 1
        assert st["rising"] == c1
        # steplen/stepspace 5000 ns round up to 4 x 1.6 us = 6.4 us (spec 6.2)
        assert st["min_high_ns"] >= 6400 - 25
        assert st["min_low_ns"] >= 6400 - 25
        st2, d2 = pins(out, "s2")
        assert st2["rising"] - st["rising"] == c1 - c2  # every step went back
        assert d2["rising"] >= 1  # DIR went high for the negative move


def test_killed_board_is_a_communication_error(tmp_path: Path) -> None:
    with board(tmp_path) as b:
        script = servo(b.socket_path) + (
            "simrun 2ms\n"
            f"loadusr -w kill -9 {b.proc.pid}\n"
            "simrun 5ms\n"
            + e2e.tag("err", "pluto-servo.communication-error")
            + "unloadrt pluto_servo\n"
            + "loadusr -w echo @@unloaded\n"
        )
        r = e2e.halrun(tmp_path, script, timeout=60)
        out = r.stdout + r.stderr
        v = e2e.values(out)
        # every read failed; HAL kept running and the driver unloads
        assert int(v["err"][0]) >= 1
        assert "unloaded" in v
        # the transport failure is reported once, not once per period
        assert out.count("EPP request failed") == 1, out
        # nothing left behind: the socket the killed board could not remove
        # is removed at unload, no process runs on it
        assert out.count("removed the socket left by the dead board") == 1, out
        assert not Path(b.socket_path).exists()
        assert b.proc.poll() is not None
        assert e2e.processes_mentioning(b.socket_path) == []


def test_lockstep_board_in_wall_clock_session(tmp_path: Path) -> None:
    """The sim: port refuses a lockstep board in a wall-clock session at once,
    saying what to do (halrun -S or vboard --freerun)."""
    with board(tmp_path) as b:
        r = e2e.halrun(tmp_path, servo(b.socket_path) + "show comp\n", simclock=False)
        out = r.stdout + r.stderr
        assert r.returncode != 0, out
        assert (
            "pluto_servo: cannot open the parallel port: the virtual board at "
            f"{b.socket_path} runs in lockstep (the vboard default) but this HAL session runs "
            "on the wall clock"
        ) in out
        assert "halrun -S" in out and "vboard --freerun" in out
        with b.client() as c:
            assert c.hello().state == vboard.STATE_BLANK
