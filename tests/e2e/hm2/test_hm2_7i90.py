# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_7i90 end to end on the virtual 7i90 (`vboard --board 7i90`): the
driver (the hm2_7i43 source built for the 7i90) over the sim: EPP port.

References: Mesa's 72-pin SVST8_4 pin file (tests/data/pinmaps, the
virtual 7i90's flash firmware has its layout) with the 7i90's connectors
P1, P2, P3 as man hm2_7i90 and LinuxCNC's driver name them; the hostmot2
IDROM fields of spec sections 3 and 16; the messages of docs/hm2_7i90.md."""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from pathlib import Path

import pytest

from hm2e2e import BUILD, halrun, probe, vboard

from hm2image import expected_pin_lines  # noqa: E402  (tests/driver, on sys.path by hm2e2e)

HM2_7I90 = BUILD / "lib" / "rtlib" / "hm2_7i90.so"
pytestmark = pytest.mark.requires_build(HM2_7I90, BUILD / "bin" / "vboard")
PFX = "hm2_7i90.0"
SG0_STEP = 48  # P3-01 (SVST8_4: StepGen 0 Step on the third connector, bit 0)
GPIO_LAST = 71  # StepGen 3's Table5 pin: GPIO with num_stepgens=3


def squeeze(s: str) -> str:
    return re.sub(r" +", " ", s).strip()


def load(sock: Path, config: str = "") -> str:
    return (
        "loadrt hostmot2 debug_idrom=1\n"
        f'loadrt hm2_7i90 port=sim:{sock} config="{config}"\n'
        "loadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read servo\n"
        f"addf {PFX}.write servo\n"
    )


@pytest.fixture
def board(tmp_path: Path) -> Iterator[vboard.VBoardProcess]:
    with vboard.VBoardProcess(tmp_path / "b.sock", "7i90") as vb:
        yield vb


def test_loads_with_an_empty_config(tmp_path: Path, board: vboard.VBoardProcess) -> None:
    sock = Path(board.socket_path)
    r = halrun(tmp_path, load(sock))
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    lines = [squeeze(s) for s in out.splitlines()]
    assert "hm2_7i90: loading HostMot2 Mesa 7i90 driver version 0.1" in lines
    idrom = {
        "Board Name: MESA7I90",
        "IO Ports: 3",
        "IO Width: 72",
        "Port Width: 24",
        "Clock Low: 100000000 Hz (100000 KHz, 100 MHz)",
        "Clock High: 200000000 Hz (200000 KHz, 200 MHz)",
    }
    for want in idrom:
        assert f"hm2/{PFX}: {want}" in lines, want
    rename = {"P2": "P1", "P3": "P2", "P4": "P3"}
    want = []
    for line in expected_pin_lines("5i20", "PIN_SVST8_4_72.csv", {4: 8, 6: 8, 5: 4}):
        line = line.replace("hm2/hm2_5i20.0:", f"hm2/{PFX}:")
        want.append(squeeze(re.sub(r"\((P\d)-", lambda m: f"({rename[m.group(1)]}-", line)))
    assert [s for s in lines if "IO Pin " in s] == want
    assert f"{PFX}: board at (ioaddr=0x0000, ioaddr_hi=0x0000, epp_wide ON) found" in lines
    assert f"{PFX}: releasing board" in lines
    assert "hm2_7i90: driver unloaded" in lines


def test_stepgen_and_gpio_through_the_board(tmp_path: Path, board: vboard.VBoardProcess) -> None:
    """A firmware= is ignored (flash board); a step generator runs and its
    feedback comes back; a freed pin is a GPIO output the board drives."""
    sock = Path(board.socket_path)
    script = load(sock, "firmware=hm2/7i90/SVST8_4.BIT num_stepgens=3")
    script += (
        f"setp {PFX}.stepgen.00.control-type 1\n"
        f"setp {PFX}.stepgen.00.position-scale 1\n"
        f"setp {PFX}.stepgen.00.maxaccel 0\n"
        f"setp {PFX}.stepgen.00.velocity-cmd 2000\n"
        f"setp {PFX}.stepgen.00.enable 1\n"
        f"setp {PFX}.gpio.{GPIO_LAST:03d}.is_output 1\n"
        f"setp {PFX}.gpio.{GPIO_LAST:03d}.out 1\n"
    )
    script += probe(sock, "reset", SG0_STEP)
    script += "simrun 20ms\n"
    script += probe(sock, "probe", "p", f"{SG0_STEP},{GPIO_LAST}")
    script += f"getp {PFX}.stepgen.00.counts\n"
    r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    m = re.search(r"^%%p (.*)$", out, re.M)
    assert m, out
    step, gpio = json.loads(m.group(1))
    # 2000 steps/s for ~20 ms: tens of step pulses on the step pin
    assert 20 <= step["rising"] <= 45, step
    assert (gpio["level"], gpio["oe"]) == (1, 1)
    counts = [int(s) for s in out.splitlines() if re.fullmatch(r"-?\d+", s.strip())]
    assert counts and abs(counts[-1] - step["rising"]) <= 2, (counts, step)


def test_no_board_fails_cleanly(tmp_path: Path) -> None:
    r = halrun(
        tmp_path,
        "loadrt hostmot2\n" f"loadrt hm2_7i90 port=sim:{tmp_path / 'none.sock'}\n" "show comp\n",
    )
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert "hm2_7i90: board 0: cannot open the parallel port" in out
    assert "hm2_7i90" not in "".join(
        s for s in out.splitlines() if s.strip().startswith(("hm2_7i90.", "rtapi"))
    )


ADDR_WRITE, DATA_WRITE, DATA_READ, DELAY = 1, 3, 4, 10  # enum epp_op_kind


def read_cookie(c: vboard.VBoardClient) -> int:
    """The word at 0x0100 (address 0x8100: auto-increment), 4 byte cycles."""
    ops = [vboard.EppOp(ADDR_WRITE, val=0x00), vboard.EppOp(ADDR_WRITE, val=0x81)]
    ops.append(vboard.EppOp(DATA_READ, n=4))
    return int.from_bytes(c.epp(ops)[-4:], "little")


def test_reconfig_reloads_the_flash_firmware(tmp_path: Path) -> None:
    """The board comes up running its flash firmware; 0x5A at 0x7F7F
    (RECONFIG) reloads it and it answers again (a 7i43 would be blank)."""
    with vboard.VBoardProcess(tmp_path / "b.sock", "7i90") as vb:
        with vboard.VBoardClient(vb.socket_path) as c:
            h = c.hello()
            assert (h.state, h.firmware, h.board) == (vboard.STATE_CONFIGURED, "SVST8_4", "7i90")
            assert h.fpga_part == "6slx9tqg144"
            assert read_cookie(c) == 0x55AACAFE
            c.epp(
                [
                    vboard.EppOp(ADDR_WRITE, val=0x7F),
                    vboard.EppOp(ADDR_WRITE, val=0x7F),
                    vboard.EppOp(DATA_WRITE, n=1, data=b"\x5a"),
                    vboard.EppOp(DELAY, val=10_000),
                ]
            )
            assert c.hello().state == vboard.STATE_CONFIGURED
            assert read_cookie(c) == 0x55AACAFE
        assert "vboard: 7i90: RECONFIG from firmware SVST8_4: reloaded from flash" in (
            vb.stderr_so_far()
        )
        # the configuration port takes no image: the firmware is in the flash
        with vboard.VBoardClient(vb.socket_path) as c:
            with pytest.raises(vboard.VBoardError, match="7i90 loads its firmware from its flash"):
                c.program(b"\0" * 68)
