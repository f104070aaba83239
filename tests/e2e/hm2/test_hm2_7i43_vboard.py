# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_7i43 end to end on the virtual 7i43: the real hostmot2 + hm2_7i43
drivers over the sim: epp_port backend, the board's CPLD model and the
Verilated hm2 EPP firmware (hm2_top_epp), on HAL's simulated clock.  The
driver resets the FPGA through the CPLD, sends the .BIT bitstream
bit-reversed, reads the IDROM over EPP and runs its servo cycle there."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from hm2e2e import BUILD, halrun, probe, tag, values, vboard
from hm2image import expected_pin_lines  # noqa: E402  (tests/driver, put on sys.path by hm2e2e)
from test_hm2_sim_load import pin_lines, squeeze

HM2_7I43 = BUILD / "lib" / "rtlib" / "hm2_7i43.so"
pytestmark = pytest.mark.requires_build(
    HM2_7I43, BUILD / "bin" / "vboard", BUILD / "lib" / "firmware" / "hm2" / "7i43" / "SVST4_4.BIT"
)
PFX = "hm2_7i43.0"


def load(sock: Path, config: str) -> str:
    return (
        "loadrt hostmot2\n"
        f'loadrt hm2_7i43 port=sim:{sock} config="{config}"\n'
        "loadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read servo\n"
        f"addf {PFX}.write servo\n"
    )


def hello(sock: Path) -> vboard.Hello:
    with vboard.VBoardClient(sock) as c:
        return c.hello()


@pytest.fixture
def blank(tmp_path: Path) -> Iterator[vboard.VBoardProcess]:
    with vboard.VBoardProcess(tmp_path / "b.sock", "7i43") as vb:
        yield vb


def test_load_through_the_cpld_and_pinout(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    sock = Path(blank.socket_path)
    assert hello(sock).state == vboard.STATE_BLANK
    config = "firmware=hm2/7i43/SVST4_4.BIT num_encoders=2 num_pwmgens=1 num_stepgens=3"
    r = halrun(tmp_path, load(sock, config) + "simrun 2ms\n" + tag("wd", f"{PFX}.watchdog.has_bit"))
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    # Mesa's 7i43 firmwares list their TranslationRAM (GTag 11, spec 9.7);
    # the driver leaves it alone, as LinuxCNC 2.9 does with modules it has
    # no code for
    assert "MD 5: 1x TranslationRAM v0: ignored" in out, out
    # the firmware's watchdog bites at configuration (Timer powers up at 0,
    # like Mesa's); the driver's load sequence clears that bite
    assert values(out)["wd"] == ["FALSE"], out
    want = [
        squeeze(s) for s in expected_pin_lines("7i43", "PIN_SVST4_4_48.csv", {4: 2, 6: 1, 5: 3})
    ]
    assert pin_lines(out) == want
    h = hello(sock)
    assert (h.state, h.firmware) == (vboard.STATE_CONFIGURED, "SVST4_4")
    assert "configured with SVST4_4" in blank.stderr_so_far()
    # loading again: the driver's RECONFIG (0x5A at 0x7F7F) clears the
    # running FPGA and the CPLD takes it from there
    r = halrun(tmp_path, load(sock, config) + "simrun 1ms\n")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "RECONFIG from firmware SVST4_4" in blank.stderr_so_far()


def test_gpio_round_trip_over_epp(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    sock = Path(blank.socket_path)
    # no stepgens: their pins (the last ones of each connector) are GPIO
    config = "firmware=hm2/7i43/SVST4_4.BIT num_encoders=4 num_pwmgens=4 num_stepgens=0"
    lines = expected_pin_lines("7i43", "PIN_SVST4_4_48.csv", {4: 4, 6: 4, 5: 0})
    gpio = [int(s.split("IO Pin ")[1][:3]) for s in lines if s.rstrip().endswith("IOPort")]
    assert len(gpio) >= 2
    out_pin, in_pin = gpio[0], gpio[1]
    script = load(sock, config) + (
        f"setp {PFX}.gpio.{out_pin:03d}.is_output 1\n"
        f"setp {PFX}.gpio.{out_pin:03d}.out 1\n"
        + probe(sock, "drive", in_pin, "low")
        + "simrun 3ms\n"
        + probe(sock, "probe", "o1", out_pin)
        + tag("i1", f"{PFX}.gpio.{in_pin:03d}.in")
        + f"setp {PFX}.gpio.{out_pin:03d}.out 0\n"
        + probe(sock, "drive", in_pin, "release")
        + "simrun 3ms\n"
        + probe(sock, "probe", "o2", out_pin)
        + tag("i2", f"{PFX}.gpio.{in_pin:03d}.in")
    )
    r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    import json

    p1, p2 = json.loads(v["o1"][0])[0], json.loads(v["o2"][0])[0]
    assert (p1["oe"], p1["level"]) == (1, 1)
    assert (p2["oe"], p2["level"]) == (1, 0)
    assert v["i1"] == ["FALSE"] and v["i2"] == ["TRUE"]


def test_bad_image_leaves_the_7i43_blank(tmp_path: Path, blank: vboard.VBoardProcess) -> None:
    sock = Path(blank.socket_path)
    fwdir = tmp_path / "fw" / "hm2" / "7i43"
    fwdir.mkdir(parents=True)
    good = (BUILD / "lib" / "firmware" / "hm2" / "7i43" / "SVST4_4.BIT").read_bytes()
    bad = bytearray(good)
    bad[-10] ^= 0x40  # inside the image: its CRC no longer matches
    (fwdir / "X.BIT").write_bytes(bytes(bad))
    r = halrun(
        tmp_path,
        load(sock, "firmware=hm2/7i43/X.BIT"),
        extra_env={"HM2_FIRMWARE_PATH": str(tmp_path / "fw")},
    )
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "hm2_7i43" in out
    assert hello(sock).state == vboard.STATE_BLANK
    assert "configuration failed, board stays blank" in blank.stderr_so_far()
