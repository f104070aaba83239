# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash --jtag: the cable spec and the USB errors a user meets (no
cable plugged in, bad spec, bad file).  The engine itself (TAP, scans,
MPSSE stream, Xilinx configuration) is tested against a model of the FTDI
chip and a TAP chain in tests/unit/jtag (ctest jtag); this machine has no
FTDI cable, so the USB side can only fail cleanly here."""

from __future__ import annotations

import re
from pathlib import Path

from flashhelpers import run, vboard

NO_CABLE = re.compile(r"no FTDI cable 0403:60(10|14)( with serial \w+)? found on USB|libusb")


def test_no_cable() -> None:
    p = run("--jtag", "ftdi", "--scan", check=1)
    assert p.stderr.startswith("hm2flash: jtag ftdi: "), p.stderr
    assert NO_CABLE.search(p.stderr), p.stderr
    p = run("--jtag", "ftdi:0403:6014:FT4XYZ", "--scan", check=1)
    assert NO_CABLE.search(p.stderr), p.stderr


def test_program_checks_file_before_usb(tmp_path: Path) -> None:
    bad = tmp_path / "bad.bit"
    bad.write_bytes(b"\x00\x09" + b"\x00" * 40)
    p = run("--jtag", "ftdi", "--program", str(bad), check=1)
    assert "bitfile has invalid header" in p.stderr
    assert "FTDI" not in p.stderr  # the cable was not even looked for
    p = run("--jtag", "ftdi", "--program", str(vboard.firmware_file("5i25", "7I76x2")), check=1)
    assert p.stdout.startswith("Checking file... OK")
    assert NO_CABLE.search(p.stderr), p.stderr


def test_cable_spec_and_usage_errors() -> None:
    for spec in ("ftdi:0403", "ftdi:xyz:1", "usb", "ftdi:0403:6010x"):
        p = run("--jtag", spec, "--scan", check=1)
        assert "bad JTAG cable" in p.stderr, (spec, p.stderr)
    assert "--scan needs --jtag CABLE" in run("--scan", check=2).stderr
    p = run("--jtag", "ftdi", "--reload", check=2)
    assert "--jtag goes with --scan or --program FILE" in p.stderr


def test_gpiod_cable_errors() -> None:
    p = run("--jtag", "gpiod:gpiochip99:1/2/3/4", "--scan", check=1)
    assert "cannot open GPIO chip 'gpiochip99'" in p.stderr
    p = run("--jtag", "gpiod:gpiochip0:1/2/3", "--scan", check=1)
    assert "want 4 lines TCK/TMS/TDI/TDO, got 3" in p.stderr
    p = run("--jtag", "gpiod:gpiochip0:1/2/2/4", "--scan", check=1)
    assert "used twice" in p.stderr
