# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2pinout: the pin report without HAL, against the seed's 5i20 printout,
a CSV-derived expectation for every pin, hm2gen's IDROM images, bad input."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from conftest_paths import BUILD, ROOT, bin_path  # noqa: E402
from hm2image import build_image, expected_pin_lines  # noqa: E402

TOOL = bin_path("hm2pinout")
pytestmark = pytest.mark.requires_build(TOOL)

SEED = """\
hm2/hm2_5i20.0: 72 I/O Pins used:
hm2/hm2_5i20.0: IO Pin 000 (P2-01): IOPort
hm2/hm2_5i20.0: IO Pin 001 (P2-03): IOPort
hm2/hm2_5i20.0: IO Pin 002 (P2-05): Encoder #0, pin B (Input)
hm2/hm2_5i20.0: IO Pin 003 (P2-07): Encoder #0, pin A (Input)
hm2/hm2_5i20.0: IO Pin 004 (P2-09): IOPort
hm2/hm2_5i20.0: IO Pin 005 (P2-11): Encoder #0, pin Index (Input)
hm2/hm2_5i20.0: IO Pin 006 (P2-13): IOPort
hm2/hm2_5i20.0: IO Pin 007 (P2-15): PWMGen #0, pin Out0 (PWM or Up) (Output)
hm2/hm2_5i20.0: IO Pin 008 (P2-17): IOPort
hm2/hm2_5i20.0: IO Pin 009 (P2-19): PWMGen #0, pin Out1 (Dir or Down) (Output)
hm2/hm2_5i20.0: IO Pin 010 (P2-21): IOPort
hm2/hm2_5i20.0: IO Pin 011 (P2-23): PWMGen #0, pin Not-Enable (Output)
hm2/hm2_5i20.0: IO Pin 060 (P4-25): StepGen #2, pin Step (Output)
hm2/hm2_5i20.0: IO Pin 061 (P4-27): StepGen #2, pin Direction (Output)
hm2/hm2_5i20.0: IO Pin 062 (P4-29): StepGen #2, pin (unused) (Output)
hm2/hm2_5i20.0: IO Pin 063 (P4-31): StepGen #2, pin (unused) (Output)
hm2/hm2_5i20.0: IO Pin 064 (P4-33): StepGen #2, pin (unused) (Output)
hm2/hm2_5i20.0: IO Pin 065 (P4-35): StepGen #2, pin (unused) (Output)
hm2/hm2_5i20.0: IO Pin 066 (P4-37): IOPort
hm2/hm2_5i20.0: IO Pin 067 (P4-39): IOPort
hm2/hm2_5i20.0: IO Pin 068 (P4-41): IOPort
hm2/hm2_5i20.0: IO Pin 069 (P4-43): IOPort
hm2/hm2_5i20.0: IO Pin 070 (P4-45): IOPort
hm2/hm2_5i20.0: IO Pin 071 (P4-47): IOPort
"""


def squeeze(s: str) -> str:
    return re.sub(r" +", " ", s).strip()


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(TOOL), *args], capture_output=True, text=True, timeout=60)


@pytest.fixture(scope="module")
def img5i20(tmp_path_factory: pytest.TempPathFactory) -> Path:
    p = tmp_path_factory.mktemp("img") / "svst8_4.img"
    p.write_bytes(build_image("5i20", "PIN_SVST8_4_72.csv", "PIN_SVST8_4_72.modules.csv"))
    return p


def pin_lines(out: str) -> list[str]:
    return [squeeze(line) for line in out.splitlines() if "IO Pin " in line]


def test_seed_5i20_printout(img5i20: Path) -> None:
    r = run("-b", "5i20", "-c", "num_encoders=1 num_pwmgens=1 num_stepgens=3", str(img5i20))
    assert r.returncode == 0, r.stderr
    got = {squeeze(line) for line in r.stdout.splitlines()}
    for line in SEED.splitlines():
        assert squeeze(line) in got, line


@pytest.mark.parametrize(
    "config,counts,width",
    [
        ("num_encoders=1 num_pwmgens=1 num_stepgens=3", {4: 1, 6: 1, 5: 3}, None),
        ("", {4: 8, 6: 8, 5: 4}, None),
        ("num_encoders=0 num_pwmgens=0 num_stepgens=0", {}, None),
        ("num_stepgens=4 stepgen_width=2 num_encoders=5", {4: 5, 6: 8, 5: 4}, 2),
        ("num_stepgens=1 stepgen_width=3 num_pwmgens=7", {4: 8, 6: 7, 5: 1}, 3),
    ],
)
def test_every_pin(img5i20: Path, config: str, counts: dict[int, int], width: int | None) -> None:
    r = run("-c", config, str(img5i20))
    assert r.returncode == 0, r.stderr
    want = [squeeze(s) for s in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", counts, width)]
    assert pin_lines(r.stdout) == want


@pytest.mark.parametrize(
    "board,pins,mods",
    [
        ("7i43", "PIN_SV8_48.csv", "PIN_SV8_48.modules.csv"),
        ("5i25", "PIN_7I76x2_34.csv", "PIN_7I76x2_34.modules.csv"),
    ],
)
def test_other_boards(tmp_path: Path, board: str, pins: str, mods: str) -> None:
    p = tmp_path / "x.img"
    p.write_bytes(build_image(board, pins, mods))
    r = run("-b", board, "-c", "num_encoders=2 num_pwmgens=1 num_stepgens=3", str(p))
    assert r.returncode == 0, r.stderr
    want = [squeeze(s) for s in expected_pin_lines(board, pins, {4: 2, 6: 1, 5: 3})]
    assert pin_lines(r.stdout) == want


HM2GEN_CASES = [
    (
        "5i20",
        "SVST8_4",
        "PIN_SVST8_4_72.csv",
        "num_encoders=3 num_pwmgens=2 num_stepgens=1",
        {4: 3, 6: 2, 5: 1},
    ),
    ("7i43", "SV8", "PIN_SV8_48.csv", "num_encoders=3 num_pwmgens=2", {4: 3, 6: 2}),
    ("5i25", "7I76x2", "PIN_7I76x2_34.csv", "num_encoders=1 num_stepgens=7", {4: 1, 5: 7}),
]


@pytest.mark.parametrize("board,fw,pins,config,counts", HM2GEN_CASES)
def test_hm2gen_idrom_cross_check(
    tmp_path: Path, board: str, fw: str, pins: str, config: str, counts: dict[int, int]
) -> None:
    """hm2gen's IDROM image (an independent generator) must give the
    same report as the image built here from the stock CSV."""
    hexfile = BUILD / "generated" / board / fw / f"{fw}.idrom.hex"  # made by the build
    if not hexfile.exists():
        desc = ROOT / "hdl" / "hostmot2" / "firmware" / board / f"{fw}.toml"
        assert (
            ROOT / "tools" / "hm2gen"
        ).is_dir() and desc.exists(), f"{desc}: hm2gen input missing"
        out = tmp_path / "gen"
        g = subprocess.run(
            [sys.executable, "-m", "hm2gen", "-q", "-o", str(out), str(desc)],
            cwd=ROOT / "tools",
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert g.returncode == 0, g.stderr
        hexfile = out / board / fw / f"{fw}.idrom.hex"
    r = run("-b", board, "-c", config, str(hexfile))
    assert r.returncode == 0, r.stderr
    want = [squeeze(s) for s in expected_pin_lines(board, pins, counts)]
    assert pin_lines(r.stdout) == want


def test_pin_file(img5i20: Path) -> None:
    r = run("-p", str(img5i20))
    assert r.returncode == 0, r.stderr
    assert "IO Connections for P4" in r.stdout
    assert "Low Level init" not in r.stdout
    # mesaflash --readhmid's layout and names (hm2flash --readhmid prints the same)
    rows = [
        line.split() for line in r.stdout.splitlines() if re.match(r"^P\d-\d\d +\d+ +IOPort", line)
    ]
    assert len(rows) == 72
    assert rows[60][:6] == ["P4-25", "60", "IOPort", "StepGen", "2", "Step/Table1"]
    assert rows[7][:5] == ["P2-15", "7", "IOPort", "PWM", "0"]


def test_bad_input(tmp_path: Path, img5i20: Path) -> None:
    small = tmp_path / "small.img"
    small.write_bytes(b"\x00" * 100)
    r = run(str(small))
    assert r.returncode == 1
    assert "expected 65536 (register space), 1024 (IDROM)" in r.stderr
    bad = bytearray(img5i20.read_bytes())
    bad[0x100:0x104] = b"\x00\x00\x00\x00"
    p = tmp_path / "nocookie.img"
    p.write_bytes(bytes(bad))
    r = run(str(p))
    assert r.returncode == 1
    assert "hm2/hm2_5i20.0: invalid cookie, got 0x00000000, expected 0x55AACAFE" in r.stderr
    r = run("-b", "7i43", str(img5i20))  # 3 ports of 24 on a 2-port board
    assert r.returncode == 1
    assert "IDROM IOPorts is 3 but llio num_ioport_connectors is 2" in r.stderr
    r = run("-c", "num_encoders=9", str(img5i20))
    assert r.returncode == 1
    assert "config.num_encoders=9, but only 8 are available, not loading driver" in r.stderr
    assert run("-b", "9z99", str(img5i20)).returncode == 2
    assert run("usb:/tmp/x").returncode == 2  # unknown source (sim: is a source now)
    assert run("sim:/tmp/no-such-board.sock").returncode == 1
    assert run().returncode == 2
    assert run(str(tmp_path / "missing")).returncode == 1
