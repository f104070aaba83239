# SPDX-License-Identifier: GPL-2.0-or-later
"""A virtual 7I76E: the 7i76e_7i76x1D firmware behind the LBP16 responder
(vboard --board 7i76e --udp, lockstep) with its built-in 7I76 on Smart
Serial channel 0 (--sserial 0.0=7i76), loaded by hm2_eth.  The board
answers to LBP16 as "7I76E-16", the driver registers it as hm2_7i76e.0
(spec 17.3 naming) and exports LinuxCNC's names: the five stepgens and the
spindle encoder on the on-card port, the 7I76 field I/O as
hm2_7i76e.0.7i76.0.0.* (sserial(9)), P1/P2 as GPIO.  Data goes both ways:
remote inputs reach HAL, HAL outputs reach the remote, a stepgen's steps
reach its on-card pin."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from hm2e2e import BUILD, PROBE, halrun, num, tag, values, vboard
from test_hm2_sim_load import pin_lines
from test_sserial import remote

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
import lbp16  # noqa: E402

pytestmark = pytest.mark.requires_build(BUILD / "lib" / "rtlib" / "hm2_eth.so")
PFX = "hm2_7i76e.0"
R = f"{PFX}.7i76.0.0"
PORT = f"{PFX}.sserial.port-0"
SG0_STEP = 1  # on-card pin 1: StepGen 0 Step (7I76 layout, PIN_7I76x2_34 port 0)
CONFIG = "num_encoders=1 num_stepgens=5 sserial_port_0=0xxxxx"


def ss(sock: Path, key: str, cmd: str) -> str:
    return f"loadusr -w {sys.executable} {PROBE} {sock} sserial {key} {cmd}\n"


def test_7i76e_with_its_7i76_over_lbp16(tmp_path: Path) -> None:
    sock, ip = tmp_path / "b.sock", lbp16.unique_loopback()
    args = ["--udp", ip, "--udp-tick", "1000", "--sserial", "0.0=7i76"]
    ins, outs = 0xC3A5965A, 0x5AA5
    with vboard.VBoardProcess(sock, "7i76e", "7i76e_7i76x1D", args) as vb:
        script = (
            "loadrt hostmot2\n"
            f'loadrt hm2_eth board_ip={ip} config="{CONFIG}"\n'
            f"setp {PFX}.packet-read-timeout 2000000000\n"
            "loadrt threads name1=servo period1=1000000\n"
            f"addf {PFX}.read servo\naddf {PFX}.write servo\n"
            f"setp {PFX}.stepgen.00.control-type 1\n"
            f"setp {PFX}.stepgen.00.position-scale 100\n"
            f"setp {PFX}.stepgen.00.maxaccel 0\n"
            f"setp {PFX}.stepgen.00.velocity-cmd 10\n"
            f"setp {PFX}.stepgen.00.enable 1\n"
            f"setp {R}.spinout 50\nsetp {R}.spinena 1\n"
        )
        script += ss(sock, "in", f"set 0.0 inputs {ins:#x}")
        script += "".join(f"setp {R}.output-{i:02d} {(outs >> i) & 1}\n" for i in range(16))
        script += "simrun 20ms\n"
        script += tag("in", *[f"{R}.input-{i:02d}" for i in range(32)])
        script += ss(sock, "st", "status")
        script += tag("sg", f"{PFX}.stepgen.00.counts", f"{PORT}.run_state")
        script += tag("eth", f"{PFX}.packet-error-total", f"{PFX}.io_error")
        script += f"show pin {PFX}.gpio.017\nshow pin {PFX}.encoder.00.count\n"
        r = halrun(tmp_path, script, timeout=300)
        out = r.stdout + r.stderr
        assert r.returncode == 0, out
        with vb.client() as c:
            steps = c.pin(SG0_STEP).rising
        assert "Sanitizer" not in vb.stderr_text
    assert "hm2_eth: discovered 7I76E-16" in out, out
    assert f"{PFX}: Smart Serial port 0 channel 0: found 7i76" in out, out
    lines = pin_lines(out)
    assert len(lines) == 51, lines
    assert lines[0] == f"hm2/{PFX}: IO Pin 000 (on-card-01): StepGen #0, pin Direction (Output)"
    assert lines[1] == f"hm2/{PFX}: IO Pin 001 (on-card-14): StepGen #0, pin Step (Output)"
    assert "Smart Serial Interface #0, pin tx0 (Output)" in lines[10], lines[10]
    assert "Encoder #0, pin A (Input)" in lines[16], lines[16]
    assert lines[17] == f"hm2/{PFX}: IO Pin 017 (P1-01): IOPort"
    assert lines[34] == f"hm2/{PFX}: IO Pin 034 (P2-01): IOPort"
    v = values(out)
    for i in range(32):
        assert num(v, "in", i) == (ins >> i) & 1, f"input-{i:02d}"
    st = remote(r.stdout, "st")
    assert st["outputs"] == outs and st["spinena"] and st["bad"] == 0, st
    assert st["spinout_raw"] == round(50 / 100 * 65535), st
    # 1000 steps/s for 20 periods of 1 ms (the first only loads the rate)
    counts = num(v, "sg", 0)
    assert 17 <= counts <= 20 and abs(steps - counts) <= 1, (counts, steps)
    assert num(v, "sg", 1) == 3  # port running
    assert v["eth"][:2] == ["0", "FALSE"], out
    assert f"{PFX}.gpio.017.in" in out and f"{PFX}.encoder.00.count" in out
