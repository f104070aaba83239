# SPDX-License-Identifier: GPL-2.0-or-later
"""Smart Serial over Ethernet: hm2_eth on the virtual 7i96S (vboard --udp,
lockstep) with a virtual 7I76 on its RS-422 smart-serial port (vboard
--sserial 0.0=7i76).  Discovery runs at load through hm2_eth's board wait
(LBP16 timer space 0x02: the board holds its command processing for that
many microseconds, so board time passes in lockstep too); the remote's
pins get LinuxCNC's names under the Ethernet board
(hm2_7i96s.0.7i76.0.0.input-NN, sserial(9)) and carry data both ways in
the one read and one write datagram of each servo period."""

from __future__ import annotations

import sys
from pathlib import Path

from hm2e2e import BUILD, PROBE, halrun, num, tag, values, vboard
from test_sserial import remote

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "common"))
import lbp16  # noqa: E402

import pytest  # noqa: E402

pytestmark = pytest.mark.requires_build(BUILD / "lib" / "rtlib" / "hm2_eth.so")
PFX = "hm2_7i96s.0"
R = f"{PFX}.7i76.0.0"
PORT = f"{PFX}.sserial.port-0"


def ss(sock: Path, key: str, cmd: str) -> str:
    return f"loadusr -w {sys.executable} {PROBE} {sock} sserial {key} {cmd}\n"


def test_7i76_on_the_7i96s_smart_serial_port(tmp_path: Path) -> None:
    sock, ip = tmp_path / "b.sock", lbp16.unique_loopback()
    args = ["--udp", ip, "--udp-tick", "1000", "--sserial", "0.0=7i76"]
    phases = [(0xA5A55A5A, 0x3C0F), (0x0F0F00F1, 0xC3F0)]
    with vboard.VBoardProcess(sock, "7i96s", "7i96s_d", args) as vb:
        script = (
            "loadrt hostmot2\n"
            f'loadrt hm2_eth board_ip={ip} config="num_encoders=1 num_stepgens=5"\n'
            f"setp {PFX}.packet-read-timeout 2000000000\n"
            "loadrt threads name1=servo period1=1000000\n"
            f"addf {PFX}.read servo\naddf {PFX}.write servo\n"
        )
        for n, (ins, outs) in enumerate(phases):
            script += ss(sock, f"in{n}", f"set 0.0 inputs {ins:#x}")
            script += "".join(f"setp {R}.output-{i:02d} {(outs >> i) & 1}\n" for i in range(16))
            script += "simrun 4ms\n"
            script += tag(f"p{n}", *[f"{R}.input-{i:02d}" for i in range(32)])
            script += ss(sock, f"st{n}", "status")
        script += tag("port", f"{PORT}.run_state", f"{PORT}.error-count")
        script += tag("eth", f"{PFX}.packet-error-total", f"{PFX}.io_error")
        r = halrun(tmp_path, script, timeout=300)
        out = r.stdout + r.stderr
        assert "Sanitizer" not in vb.stderr_text
    assert r.returncode == 0, out
    assert f"{PFX}: Smart Serial port 0 channel 0: found 7i76" in out, out
    v = values(out)
    for n, (ins, outs) in enumerate(phases):
        for i in range(32):
            assert num(v, f"p{n}", i) == (ins >> i) & 1, f"phase {n} input-{i:02d}"
        st = remote(r.stdout, f"st{n}")
        assert st["outputs"] == outs, st
        assert st["bad"] == 0, st
    # run state 3 = running (docs/sserial.md), no errors, no packet errors
    assert v["port"][:2] == ["3", "0"], out
    assert v["eth"][:2] == ["0", "FALSE"], out
