# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash --program: one loader for every bus-configured board, each with
its own method (PCI bridge configuration port, the 7i43's CPLD over EPP, the
Pluto-P's passive serial upload), checked on the virtual boards: the board
reports the firmware that came up (HELLO) and answers on its bus; a file
for another FPGA leaves the board as it was."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from flashhelpers import make_bit, run, vboard


def fw(board: str, name: str) -> str:
    return str(vboard.firmware_file(board, name))


@pytest.mark.parametrize(
    "board, device, file, method, firmware",
    [
        ("5i20", "5i20", ("5i20", "SVST8_4"), "PCI bridge configuration port", "SVST8_4"),
        ("7i43", "7i43", ("7i43", "SV8"), "7i43 CPLD over EPP", "SV8"),
        ("pluto", "pluto", None, "Pluto-P passive serial over EPP", "pluto_servo"),
    ],
)
def test_program_blank_board(
    sockdir: Path,
    board: str,
    device: str,
    file: tuple[str, str] | None,
    method: str,
    firmware: str,
) -> None:
    # the Pluto-P's file as a relative path: taken as it is, not looked up
    rbf = vboard.build_dir() / "lib" / "firmware" / "pluto_servo.rbf"
    path = fw(*file) if file else os.path.relpath(rbf)
    with vboard.VBoardProcess(sockdir / "b.sock", board) as b:
        p = run("--device", device, "--addr", f"sim:{b.socket_path}", "--program", path)
        assert f"Programming FPGA ({method})..." in p.stdout
        assert "  Programming [########################################] 100% 68 bytes" in p.stdout
        with b.client() as c:
            h = c.hello()
            assert h.state == vboard.STATE_CONFIGURED and h.firmware == firmware
            if board == "5i20":
                assert c.read(0x100)[0] == 0x55AACAFE


@pytest.mark.parametrize(
    "board, running, device, file, message",
    [
        (
            "5i20",
            None,
            "5i20",
            ("5i25", "7I76x2"),
            "should be 2s200pq208; the FPGA was not touched",
        ),
        ("7i43", "SV8", "7i43", ("5i20", "SV12"), "should be 3s400tq144; the FPGA was not touched"),
    ],
)
def test_program_wrong_fpga_leaves_board(
    sockdir: Path,
    board: str,
    running: str | None,
    device: str,
    file: tuple[str, str],
    message: str,
) -> None:
    with vboard.VBoardProcess(sockdir / "b.sock", board, running) as b:
        with b.client() as c:
            before = c.hello()
        p = run(
            "--device", device, "--addr", f"sim:{b.socket_path}", "--program", fw(*file), check=1
        )
        assert message in p.stderr
        assert "Programming FPGA" not in p.stdout
        with b.client() as c:
            assert c.hello() == before


def test_program_corrupt_image_refused_by_board(sockdir: Path) -> None:
    img = bytearray(vboard.bit_payload(vboard.firmware_file("5i20", "SVST8_4").read_bytes()))
    img[33] ^= 0xFF
    bad = sockdir / "bad.bit"
    bad.write_bytes(make_bit(bytes(img), part="2s200pq208"))
    with vboard.VBoardProcess(sockdir / "b.sock", "5i20") as b:
        p = run(
            "--device", "5i20", "--addr", f"sim:{b.socket_path}", "--program", str(bad), check=1
        )
        assert "firmware image is corrupt" in p.stderr
        assert "programming the FPGA of hm2_5i20.0 failed" in p.stderr
        with b.client() as c:
            assert c.hello().state == vboard.STATE_BLANK


def test_program_flash_board_and_bad_sources(sockdir: Path) -> None:
    p = run(
        "--device", "5i25", "--addr", "sim:/nowhere", "--program", fw("5i25", "7I76x2"), check=1
    )
    assert "volatile programming needs JTAG" in p.stderr
    p = run("--device", "pluto", "--addr", "sim:/nowhere", "--program", "/no/such.rbf", check=1)
    assert "such.rbf" in p.stderr
    p = run("--device", "7i43", "--addr", "bogus:x", "--program", fw("7i43", "SV8"), check=1)
    assert "bogus" in p.stderr
    p = run("--device", "5i20", "--addr", "usb:0", "--program", fw("5i20", "SV12"), check=1)
    assert "want sim:SOCKET or pci:[ADDR]" in p.stderr
