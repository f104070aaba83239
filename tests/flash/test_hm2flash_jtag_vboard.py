# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash --jtag sim:SOCKET: the GPIO cable engine's line sequence (TCK,
TMS, TDI set, TDO read, as it drives libgpiod lines) sent to a virtual
board's JTAG port (vboard's VB_JTAG request), where a TAP model of its
Spartan-6 answers: IDCODE scan, volatile configuration through JPROGRAM /
CFG_IN / JSTART with the board's own image checks, refusals.

References: the XC6SLX9's IDCODE (bits 27..0 0x4001093, the engine's part
table), the Xilinx IR capture bits (...01, INIT bit 4, DONE bit 5) and the
board itself: after a configuration it must run the firmware (cookie and
IDROM read over its bus)."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

from flashhelpers import firmware_bit, hm2flash_binary, make_bit, run, vboard


def blank_5i25(sockdir: Path) -> vboard.VBoardProcess:
    # a new flash and no --firmware: nothing to boot, the FPGA stays blank
    return vboard.VBoardProcess(
        sockdir / "j.sock", "5i25", None, args=["--flash", str(sockdir / "blank.bin")]
    )


def test_scan_and_program_a_blank_board(sockdir: Path) -> None:
    cable = f"sim:{sockdir / 'j.sock'}"
    with blank_5i25(sockdir) as b:
        r = run("--jtag", cable, "--scan")
        assert "  0: IDCODE 0x04001093 XC6SLX9" in r.stdout
        with b.client() as c:
            assert c.hello().state == vboard.STATE_BLANK
        bit = sockdir / "fw.bit"
        bit.write_bytes(firmware_bit())
        r = run("--jtag", cable, "--program", str(bit))
        assert "Programming device 0 through JTAG (JPROGRAM, CFG_IN 68 bytes, JSTART)" in r.stdout
        assert "Board configured: DONE high (IR capture 0x31)" in r.stdout
        with b.client() as c:
            h = c.hello()
            assert h.state == vboard.STATE_CONFIGURED and h.firmware == "7I76x2"
            assert c.read(0x100)[0] == 0x55AACAFE
        # the firmware it runs, read over the bus
        r = run("--device", "5i25", "--addr", f"sim:{sockdir / 'j.sock'}", "--readhmid")
        assert "  BoardName : MESA5I25\n" in r.stdout


def test_bad_bitstreams_are_refused(sockdir: Path) -> None:
    cable = f"sim:{sockdir / 'j.sock'}"
    with blank_5i25(sockdir) as b:
        # another FPGA: nothing is sent
        r = run("--jtag", cable, "--program", str(vboard.firmware_file("5i20", "SV12")), check=1)
        assert "wrong chain" in r.stderr and "the FPGA was not touched" in r.stderr
        # a corrupt image reaches the FPGA, which refuses it: DONE low, INIT low
        img = bytearray(vboard.bit_payload(firmware_bit()))
        img[40] ^= 1
        bad = sockdir / "bad.bit"
        bad.write_bytes(make_bit(bytes(img)))
        r = run("--jtag", cable, "--program", str(bad), check=1)
        assert "did not assert DONE after configuration (IR capture 0x01, INIT low: CRC error)" in (
            r.stderr
        )
        with b.client() as c:
            assert c.hello().state == vboard.STATE_BLANK
        # a good one afterwards configures it
        good = sockdir / "fw.bit"
        good.write_bytes(firmware_bit())
        run("--jtag", cable, "--program", str(good))


def test_no_port_and_board_gone(sockdir: Path) -> None:
    with vboard.VBoardProcess(sockdir / "p.sock", "5i20", None):
        r = run("--jtag", f"sim:{sockdir / 'p.sock'}", "--scan", check=1)
        assert "board 5i20 (2s200pq208) has no JTAG port model" in r.stderr
    r = run("--jtag", f"sim:{sockdir / 'none.sock'}", "--scan", check=1)
    assert "cannot connect" in r.stderr
    # the board disappears in the middle of a configuration: an error, no hang
    b = blank_5i25(sockdir)
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    tool = subprocess.Popen(
        [str(hm2flash_binary()), "--jtag", f"sim:{sockdir / 'j.sock'}", "--program", str(bit)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        # the JPROGRAM wait alone is 10,000 TCK, four line changes each: the
        # board goes while the tool is connecting or clocking
        time.sleep(0.15)
        b.kill()
        t0 = time.monotonic()
        out, err = tool.communicate(timeout=30)
        assert time.monotonic() - t0 < 10
    finally:
        if tool.poll() is None:
            tool.kill()
    assert tool.returncode == 1
    assert "hm2flash:" in err
