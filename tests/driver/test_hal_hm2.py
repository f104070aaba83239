# SPDX-License-Identifier: GPL-2.0-or-later
"""hostmot2 + hm2_test under our halrun: loadrt like LinuxCNC, the hm2_test
patterns with LinuxCNC 2.9's messages and nothing left in HAL, a 5i20 image
with the seed config (pin report, names, functions), and the per-period
functions in a thread (watchdog armed and petted, stepgen rate, GPIO),
checked through the raw register pins."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import uuid
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from conftest_paths import BUILD, bin_path  # noqa: E402
from hm2image import build_image, expected_pin_lines  # noqa: E402

HALRUN = bin_path("halrun")
RTLIB = BUILD / "lib" / "rtlib"
pytestmark = pytest.mark.requires_build(HALRUN, RTLIB / "hostmot2.so", RTLIB / "hm2_test.so")

# LinuxCNC 2.9 messages for `loadrt hm2_test test_pattern=N` (captured from
# its halrun; spec §15.1).
PATTERN_MSG = {
    0: "invalid cookie, got 0x00000000, expected 0x55AACAFE",
    1: "invalid config name, got '????????', expected 'HOSTMOT2'",
    2: "invalid IDROM type 0, expected 2 or 3, aborting load",
    3: "invalid IDROM type 4660, expected 2 or 3, aborting load",
    4: "invalid IDROM PortWidth 0, this board has 24 pins per connector, aborting load",
    5: "invalid IDROM PortWidth 29, this board has 24 pins per connector, aborting load",
    6: "IDROM IOPorts is 0 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
    7: "IDROM IOWidth is 99, but IDROM IOPorts is 1 and IDROM PortWidth is 24 (inconsistent "
    "firmware), aborting driver load",
    8: "IDROM IOPorts is 2 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
    9: "IDROM ClockLow is 12345, that's too low, aborting driver load",
    10: "IDROM ClockHigh is 0, that's too low, aborting driver load",
    11: "pin 0 primary tag is 0 (end-of-list sentinel), expected 144 pins!",
    12: "hm2_set_pin_source: invalid pin number 0",
    13: "invalid IDROM PortWidth 24, this board has 5 pins per connector, aborting load",
    14: "IDROM IOPorts is 0 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
}


def halrun(tmp_path: Path, script: str, *opts: str) -> subprocess.CompletedProcess[str]:
    f = tmp_path / "test.hal"
    f.write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = "hm2-hal-" + uuid.uuid4().hex[:10]
    env["HM_BUILD"] = str(BUILD)
    return subprocess.run(
        [str(HALRUN), *opts, "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        cwd=tmp_path,
    )


@pytest.mark.parametrize("n", sorted(PATTERN_MSG))
def test_hm2_test_pattern(tmp_path: Path, n: int) -> None:
    r = halrun(
        tmp_path,
        "loadrt hostmot2\n"
        f"loadrt hm2_test test_pattern={n}\n"
        "show pin hm2\nshow param hm2\nshow funct hm2\n",
        "-k",
    )
    out = r.stdout + r.stderr
    assert f"hm2_test: loading HostMot2 test driver with test pattern {n}" in out
    assert f"hm2/hm2_test.0: {PATTERN_MSG[n]}\n" in out
    assert "hm2_test.0: hm2_test fails HM2 registration" in out
    # nothing of the board is left in HAL
    assert "hm2_test.0." not in out
    assert r.returncode != 0  # the failed loadrt is reported


def test_unknown_pattern(tmp_path: Path) -> None:
    r = halrun(tmp_path, "loadrt hostmot2\nloadrt hm2_test test_pattern=15\n")
    assert "hm2_test: unknown test pattern 15" in r.stdout + r.stderr
    assert r.returncode != 0


@pytest.fixture()
def img(tmp_path: Path) -> Path:
    p = tmp_path / "5i20.img"
    p.write_bytes(build_image("5i20", "PIN_SVST8_4_72.csv", "PIN_SVST8_4_72.modules.csv"))
    return p


SEED_CONFIG = "firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=3"


def test_seed_config_load(tmp_path: Path, img: Path) -> None:
    r = halrun(
        tmp_path,
        "loadrt hostmot2\n"
        f'loadrt hm2_test image={img} config="{SEED_CONFIG}"\n'
        "show funct\nshow param hm2_5i20.0.watchdog\n",
        "-s",
    )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    lines = [re.sub(" +", " ", x).strip() for x in out.splitlines()]
    want = expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 1, 6: 1, 5: 3})
    got_pins = [x for x in lines if "IO Pin " in x]
    assert got_pins == [re.sub(" +", " ", w).strip() for w in want]
    assert "hm2/hm2_5i20.0: 72 I/O Pins used:" in lines
    assert "hm2/hm2_5i20.0: registered" in lines
    for f in ("read", "write", "pet_watchdog", "read_gpio", "write_gpio"):
        assert re.search(rf"\bhm2_5i20\.0\.{f}$", out, re.M), f
    assert re.search(r"0x3B9ACA00\s+hm2_5i20\.0\.watchdog\.timeout_ns", out)


def test_functions_in_a_thread(tmp_path: Path, img: Path) -> None:
    # The image llio stores writes, so what write() puts into a register
    # read() reads back: GPIO data loops back to gpio.NNN.in.
    script = f"""loadrt hostmot2
loadrt hm2_test image={img} config="num_encoders=1 num_pwmgens=1 num_stepgens=2 enable_raw"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.gpio.012.is_output 1
setp hm2_5i20.0.gpio.012.out 1
setp hm2_5i20.0.stepgen.00.position-scale 100
setp hm2_5i20.0.stepgen.00.steplen 1000
setp hm2_5i20.0.stepgen.00.stepspace 1000
setp hm2_5i20.0.stepgen.00.control-type 1
setp hm2_5i20.0.stepgen.00.maxaccel 0
setp hm2_5i20.0.stepgen.00.velocity-cmd 2
setp hm2_5i20.0.stepgen.00.enable 1
setp hm2_5i20.0.raw.read_address 0x0C00
start
loadusr -w sleep 0.3
stop
getp hm2_5i20.0.raw.read_data
getp hm2_5i20.0.stepgen.00.dbg_step_rate
getp hm2_5i20.0.gpio.012.in
getp hm2_5i20.0.gpio.013.in
getp hm2_5i20.0.stepgen.00.velocity-fb
getp hm2_5i20.0.io_error
getp hm2_5i20.0.watchdog.has_bit
"""
    r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    vals = [x.strip() for x in r.stdout.splitlines() if x.strip()]
    vals = [v for v in vals if not v.startswith("hm2")][-7:]
    # watchdog armed by write(): 1 s at 33.333333 MHz - 1
    assert int(vals[0], 0) == 33333332, out
    # 2 units/s * 100 steps/unit = 200 steps/s -> 200 * 2^32 / 33333333
    assert int(vals[1], 0) == int(200 * 2**32 / 33333333), out
    assert vals[2:4] == ["TRUE", "FALSE"], out
    assert float(vals[4]) == pytest.approx(2.0)
    assert vals[5:] == ["FALSE", "FALSE"], out


def test_watchdog_bite_and_recovery(tmp_path: Path, img: Path) -> None:
    """A bite (status bit set through the raw pins) sets has_bit; clearing
    has_bit recovers, as the seed describes."""
    script = f"""loadrt hostmot2
loadrt hm2_test image={img} config="num_encoders=1 enable_raw"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
addf hm2_5i20.0.pet_watchdog servo
start
loadusr -w sleep 0.1
getp hm2_5i20.0.watchdog.has_bit
setp hm2_5i20.0.raw.write_address 0x0D00
setp hm2_5i20.0.raw.write_data 1
setp hm2_5i20.0.raw.write_strobe 1
loadusr -w sleep 0.1
setp hm2_5i20.0.raw.write_strobe 0
getp hm2_5i20.0.watchdog.has_bit
setp hm2_5i20.0.watchdog.has_bit 0
loadusr -w sleep 0.1
getp hm2_5i20.0.watchdog.has_bit
setp hm2_5i20.0.raw.read_address 0x0D00
loadusr -w sleep 0.1
getp hm2_5i20.0.raw.read_data
stop
"""
    r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    vals = [x.strip() for x in r.stdout.splitlines() if x.strip()]
    vals = [v for v in vals if not v.startswith("hm2")][-4:]
    assert vals[:3] == ["FALSE", "TRUE", "FALSE"], out
    assert int(vals[3], 0) == 0, out
    assert "hm2/hm2_5i20.0: Watchdog has bit! (set the .has-bit pin to False to resume)" in out
    assert "hm2/hm2_5i20.0: trying to recover from IO error or Watchdog bite" in out
    assert "hm2/hm2_5i20.0: error recover successful!" in out


# What LinuxCNC 2.9 exports for a full GPIO pin and for the board functions
# (captured from its halrun with `loadrt hm2_test test_pattern=12`, `show`).
LINUXCNC_GPIO = {
    "in": ("bit", "OUT"),
    "in_not": ("bit", "OUT"),
    "out": ("bit", "IN"),
    "invert_output": ("bit", "RW"),
    "is_opendrain": ("bit", "RW"),
    "is_output": ("bit", "RW"),
}
LINUXCNC_FUNCTS_FP = {"read": "YES", "write": "YES", "read_gpio": "YES", "write_gpio": "YES"}


def test_gpio_objects_match_linuxcnc(tmp_path: Path, img: Path) -> None:
    r = halrun(
        tmp_path,
        "loadrt hostmot2\n"
        f'loadrt hm2_test image={img} config="num_encoders=0 num_pwmgens=0 '
        'num_stepgens=0"\nshow pin\nshow param\nshow funct\n',
    )
    out = r.stdout
    assert r.returncode == 0, out + r.stderr
    objs: dict[str, dict[str, tuple[str, str]]] = {}
    for m in re.finditer(
        r"^\s*\d+\s+(bit|s32|u32|float)\s+(IN|OUT|I/O|RO|RW)\s+\S+\s+"
        r"hm2_5i20\.0\.gpio\.(\d{3})\.(\S+)$",
        out,
        re.M,
    ):
        objs.setdefault(m.group(3), {})[m.group(4)] = (m.group(1), m.group(2))
    assert sorted(objs) == [f"{i:03d}" for i in range(72)]
    for pin, o in objs.items():
        assert o == LINUXCNC_GPIO, pin
    for name, fp in LINUXCNC_FUNCTS_FP.items():
        assert re.search(rf"\s{fp}\s+\d+\s+hm2_5i20\.0\.{name}$", out, re.M), name
