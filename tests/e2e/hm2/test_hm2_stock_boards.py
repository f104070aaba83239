# SPDX-License-Identifier: GPL-2.0-or-later
"""The other Anything-I/O boards and stock firmwares LinuxCNC 2.9's sample
configurations name (5i23, 4i65, 4i68, 5i22-1, 5i22-1.5, 3x20-1; 5i20
SVST2_4_7I47), each loaded through hostmot2 + hm2_sim onto its virtual
board with debug_idrom=1.

References, none of them the firmware descriptions themselves:
* SVST8_4 on the 5i23/4i65/4i68: Mesa's pin map (tests/data/pinmaps,
  PIN_SVST8_4_72.csv), connectors as the hostmot2 driver names them;
* the firmwares without a Mesa pin file here: the module and GPIO counts of
  the hostmot2 driver doc's firmware tables (shared/seeds/hostmot2-driver-
  doc.txt), the board facts (I/O width, connectors, FPGA part) of the same
  doc and spec section 16, and for SVST2_4_7I47 the pins LinuxCNC's Smithy
  configurations use (step outputs on I/O 0, 2, 16, 18; I/O 22 a GPIO with
  one PWM generator; 16, 18, 19 GPIO with two step generators).
"""

from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from hm2e2e import BUILD, halrun, needs_vboard, vboard

from hm2image import expected_pin_lines  # noqa: E402  (tests/driver, on sys.path by hm2e2e)

pytestmark = needs_vboard


@dataclass(frozen=True)
class Case:
    board: str  # vboard --board, = the firmware directory hm2/<board>/
    firmware: str
    llio: str  # hm2_<llio>.0
    part: str
    connectors: tuple[str, ...]
    clocks: tuple[int, int]  # ClockLow, ClockHigh in Hz
    size: int  # IDROM FPGA Size (K gates)
    counts: tuple[int, int, int]  # encoders, PWM generators, step generators
    gpio: int  # pins left to GPIO with every instance enabled
    enable_pin: bool = True  # PWM generators have a Not-Enable pin


P5I22 = ("P2", "P3", "P4", "P5")
P3X20 = ("P4", "P5", "P6", "P9", "P8", "P7")
CLK48, CLK33, CLK50 = (48_000_000, 96_000_000), (33_333_333, 100_000_000), (50_000_000, 100_000_000)
# The driver doc's tables: 5i22 SVST8_8 8/8/8 GPIO 0, SV16 16/16/0 GPIO 0;
# 3x20 SV24 24/24/0, SVST16_24 16/16/24 GPIO 0; SVST2_4_7I47 4/2/4, GPIO 48
# on the 72-pin boards.
OWN = [
    Case("5i20", "SVST2_4_7I47", "5i20", "2s200pq208", ("P2", "P3", "P4"), CLK33, 200,
         (4, 2, 4), 48, enable_pin=False),
    Case("5i22-1", "SVST8_8", "5i22", "3s1000fg320", P5I22, CLK48, 1000, (8, 8, 8), 0),
    Case("5i22-1.5", "SVST8_8", "5i22", "3s1500fg320", P5I22, CLK48, 1500, (8, 8, 8), 0),
    Case("5i22-1", "SV16", "5i22", "3s1000fg320", P5I22, CLK48, 1000, (16, 16, 0), 0),
    Case("3x20-1", "SV24", "3x20", "3s1000fg456", P3X20, CLK50, 1000, (24, 24, 0), 0),
    Case("3x20-1", "SVST16_24", "3x20", "3s1000fg456", P3X20, CLK50, 1000, (16, 16, 24), 0),
]  # fmt: skip
# SVST8_4 (Mesa's pin file) on the other 72-pin boards
MESA = [
    Case("5i23", "SVST8_4", "5i23", "3s400pq208", ("P2", "P3", "P4"), CLK48, 400, (8, 8, 4), 0),
    Case("4i65", "SVST8_4", "4i65", "2s200pq208", ("P1", "P3", "P4"), CLK33, 200, (8, 8, 4), 0),
    Case("4i68", "SVST8_4", "4i68", "3s400pq208", ("P1", "P2", "P4"), CLK48, 400, (8, 8, 4), 0),
]  # fmt: skip


def squeeze(s: str) -> str:
    return re.sub(r" +", " ", s).strip()


def run(tmp: Path, c: Case, counts: tuple[int, int, int], extra: str = "") -> str:
    """Load c's firmware on its virtual board; the session's output."""
    enc, pwm, sg = counts
    cfg = (
        f"firmware=hm2/{c.board}/{c.firmware}.BIT num_encoders={enc} num_pwmgens={pwm} "
        f"num_stepgens={sg}"
    )
    with vboard.VBoardProcess(tmp / "b.sock", c.board) as vb:
        script = (
            "loadrt hostmot2 debug_idrom=1\n"
            f'loadrt hm2_sim socket={vb.socket_path} board={c.board} config="{cfg}"\n' + extra
        )
        r = halrun(tmp, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert f"initialized virtual AnyIO board at {vb.socket_path} ({c.firmware})" in out
    return out


def report(out: str, llio: str) -> dict[int, str]:
    """IO pin number -> what the pin report says it is."""
    pins = {}
    for line in out.splitlines():
        m = re.match(rf"hm2/hm2_{llio}\.0: +IO Pin (\d+) \((\S+)\): (.*)$", line)
        if m:
            pins[int(m.group(1))] = f"{m.group(2)} {m.group(3)}"
    return pins


def check_idrom(out: str, c: Case, io_width: int) -> None:
    lines = {squeeze(s) for s in out.splitlines()}
    pfx = f"hm2/hm2_{c.llio}.0:"
    want = [
        f"Part Name: {c.part}",
        f"FPGA Size: {c.size}",
        f"IO Ports: {len(c.connectors)}",
        f"IO Width: {io_width}",
        f"Port Width: 24",
        f"Clock Low: {c.clocks[0]} Hz ({c.clocks[0] // 1000} KHz, {c.clocks[0] // 10**6} MHz)",
        f"Clock High: {c.clocks[1]} Hz ({c.clocks[1] // 1000} KHz, {c.clocks[1] // 10**6} MHz)",
    ]
    for w in want:
        assert f"{pfx} {w}" in lines, w


@pytest.mark.parametrize("c", OWN, ids=lambda c: f"{c.board}-{c.firmware}")
def test_own_layout_counts(tmp_path: Path, c: Case) -> None:
    out = run(tmp_path, c, c.counts)
    io_width = 24 * len(c.connectors)
    check_idrom(out, c, io_width)
    pins = report(out, c.llio)
    assert sorted(pins) == list(range(io_width))
    for i, con in enumerate(c.connectors):  # header pins 1, 3, ... 47 per connector
        assert pins[24 * i].startswith(f"{con}-01 ") and pins[24 * i + 23].startswith(f"{con}-47 ")
    enc, pwm, sg = c.counts
    text = "\n".join(pins.values())
    for n in range(enc):
        for sig in ("A", "B", "Index"):
            assert text.count(f"Encoder #{n}, pin {sig} (Input)") == 1, (n, sig)
    pwm_sigs = ["Out0 (PWM or Up)", "Out1 (Dir or Down)"] + (["Not-Enable"] * c.enable_pin)
    for n in range(pwm):
        for sig in pwm_sigs:
            assert text.count(f"PWMGen #{n}, pin {sig} (Output)") == 1, (n, sig)
    for n in range(sg):
        for sig in ("Step", "Direction"):
            assert text.count(f"StepGen #{n}, pin {sig} (Output)") == 1, (n, sig)
    assert sum(v.endswith(" IOPort") for v in pins.values()) == c.gpio
    for kind, n in zip(("Encoder", "PWMGen", "StepGen"), c.counts):
        md = re.findall(rf"MD \d+: (\d+)x {kind} v\d+: accepted, using (\d+)", out)
        assert md == ([(str(n), str(n))] if n else []), (kind, md)


@pytest.mark.parametrize("c", MESA, ids=lambda c: c.board)
def test_svst8_4_matches_mesa_pin_file(tmp_path: Path, c: Case) -> None:
    out = run(tmp_path, c, c.counts)
    check_idrom(out, c, 72)
    rename = dict(zip(("P2", "P3", "P4"), c.connectors))
    want = []
    for line in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 8, 6: 8, 5: 4}):
        line = line.replace("hm2/hm2_5i20.0:", f"hm2/hm2_{c.llio}.0:")
        want.append(re.sub(r"\((P\d)-", lambda m: f"({rename[m.group(1)]}-", line))
    got = [squeeze(s) for s in out.splitlines() if "IO Pin " in s]
    assert got == [squeeze(s) for s in want]


def params(out: str) -> set[str]:
    return {m.group(1) for m in re.finditer(r"\s(hm2_5i20\.0\.[\w.-]+)\s*$", out, re.M)}


STEPS = {0: 0, 2: 1, 16: 2, 18: 3}  # I/O pin -> step generator whose Step it is


def test_svst2_4_7i47_as_smithy_configs_use_it(tmp_path: Path) -> None:
    c = OWN[0]
    # the Smithy configurations invert the step outputs by their GPIO names
    setp = "".join(f"setp hm2_5i20.0.gpio.{io:03d}.invert_output TRUE\n" for io in STEPS)
    getp = "".join(f"getp hm2_5i20.0.stepgen.{n:02d}.step.invert_output\n" for n in STEPS.values())
    out = run(tmp_path, c, (1, 1, 4), setp + getp + "show param hm2_5i20.0.gpio.0*\n")
    assert re.findall(r"^(TRUE|FALSE)$", out, re.M) == ["TRUE"] * 4
    p = params(out)
    for io in STEPS:  # step outputs are no GPIO outputs
        assert f"hm2_5i20.0.gpio.{io:03d}.is_output" not in p
    assert "hm2_5i20.0.gpio.022.is_output" in p  # PWM generator 1 disabled
    assert "hm2_5i20.0.gpio.020.is_output" not in p  # PWM generator 0 Out0
    out = run(tmp_path, c, (2, 1, 2), "show param hm2_5i20.0.gpio.0*\n")
    p = params(out)
    for io in (16, 18, 19):  # step generators 2 and 3 disabled
        assert f"hm2_5i20.0.gpio.{io:03d}.is_output" in p
    assert "hm2_5i20.0.gpio.002.is_output" not in p


def test_bad_board_name(tmp_path: Path) -> None:
    """A firmware directory that is no board: vboard refuses it and says why."""
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--board", "5i22-2", "--socket", str(tmp_path / "x.sock")],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert r.returncode != 0
    assert "5i22-2" in r.stderr
    assert not (tmp_path / "x.sock").exists()


def test_firmware_files_built() -> None:
    fw = BUILD / "lib" / "firmware" / "hm2"
    for c in OWN + MESA:
        assert (fw / c.board / f"{c.firmware}.BIT").is_file(), c


# The 7i43's two sizes (spec section 16: 3s200tq144 / 3s400tq144, FPGASize
# 200 / 400 in the IDROM); hm2/7i43-4/ holds the 400K files.
SIZES = [("7i43", "7i43-4", "3s400tq144", 400), ("7i43-2", "7i43-2", "3s200tq144", 200)]


@pytest.mark.parametrize("firmware", ["SVST4_4", "SVST2_4_7I47"])
@pytest.mark.parametrize("board,fwdir,part,size", SIZES, ids=[s[0] for s in SIZES])
def test_7i43_idrom_says_its_size(
    tmp_path: Path, board: str, fwdir: str, part: str, size: int, firmware: str
) -> None:
    with vboard.VBoardProcess(tmp_path / "b.sock", board) as vb:
        cfg = f"firmware=hm2/{fwdir}/{firmware}.BIT num_encoders=4 num_pwmgens=2 num_stepgens=4"
        r = halrun(
            tmp_path,
            "loadrt hostmot2 debug_idrom=1\n"
            f'loadrt hm2_7i43 port=sim:{vb.socket_path} config="{cfg}"\n',
        )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    lines = {squeeze(s) for s in out.splitlines()}
    for want in (f"Part Name: {part}", f"FPGA Size: {size}", "FPGA Pins: 144", "IO Width: 48"):
        assert f"hm2/hm2_7i43.0: {want}" in lines, want
    if firmware != "SVST2_4_7I47":
        return
    pins = report(out, "7i43")
    # the 7I47 signals on P4 as on the 5i20's P2 (the Smithy layout), P3 all GPIO
    for io, sg in STEPS.items():
        assert pins[io] == f"P4-{2 * io + 1:02d} StepGen #{sg}, pin Step (Output)"
    assert pins[20] == "P4-41 PWMGen #0, pin Out0 (PWM or Up) (Output)"
    assert [pins[i] for i in range(24, 48)] == [f"P3-{2 * b + 1:02d} IOPort" for b in range(24)]
    assert sum("Encoder #" in v for v in pins.values()) == 12
