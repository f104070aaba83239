# SPDX-License-Identifier: GPL-2.0-or-later
"""A power loss in the middle of page programming (the erase is done, some
pages of the new user image are written, the rest are still blank): the
virtual 5i25 then boots its fallback image, says so, and hm2flash puts a
good user image back.

The reference is the flash file itself (the model maps it shared, so a
killed board leaves what a power loss would) and the Spartan-6 layout in
flashhelpers.py."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import pytest
from flashhelpers import (
    FALLBACK,
    PAGE_SIZE,
    SECTOR,
    USER,
    StartBoard,
    firmware_bit,
    hm2flash_binary,
    make_bit,
    run,
    vboard,
)

PAGES = 32  # 8 KiB: about a second of simulation to program, plenty to stop it in


def test_power_loss_mid_program_then_recovery(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board(speedup=1000)
    addr = f"sim:{sockdir / 'b.sock'}"
    stock = vboard.bit_payload(firmware_bit())
    # a Spartan-6 configuration (sync word) of 32 pages without 0xFF bytes,
    # so a programmed page shows in the flash file
    data = b"\xaa\x99\x55\x66" + bytes(i % 251 for i in range(PAGES * PAGE_SIZE - 4))
    bit = sockdir / "big.bit"
    bit.write_bytes(make_bit(data))
    flash = sockdir / "flash.bin"
    last = USER + (PAGES - 1) * PAGE_SIZE
    tool = subprocess.Popen(
        [str(hm2flash_binary()), "--device", "5i25", "--addr", addr, "--write", str(bit)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            f = flash.read_bytes()
            # erased, the first page programmed, the last one not yet
            if f[USER : USER + PAGE_SIZE] == data[:PAGE_SIZE] and f[last] == 0xFF:
                break
            time.sleep(0.005)
        else:
            pytest.fail("never saw the programming half done")
        b.kill()  # power loss
        out, err = tool.communicate(timeout=60)
    finally:
        if tool.poll() is None:
            tool.kill()
    assert tool.returncode == 1
    assert "Board configuration updated successfully" not in out
    f = flash.read_bytes()
    done = [f[USER + i * PAGE_SIZE : USER + (i + 1) * PAGE_SIZE] for i in range(PAGES)]
    programmed = sum(1 for i, page in enumerate(done) if page == data[i * PAGE_SIZE :][:PAGE_SIZE])
    blank = sum(1 for page in done if page == b"\xff" * PAGE_SIZE)
    assert 1 <= programmed < PAGES and programmed + blank == PAGES, (programmed, blank)
    assert f[USER + PAGES * PAGE_SIZE : USER + SECTOR] == b"\xff" * (SECTOR - PAGES * PAGE_SIZE)
    assert f[FALLBACK : FALLBACK + len(stock)] == stock  # the fallback never touched
    # Power back: the half-written user image does not configure the FPGA;
    # the fallback does, and the board says so.
    start_board()
    p = run("--device", "5i25", "--addr", addr)
    assert "fallback-used" in p.stdout
    assert "Firmware: 7I76x2" in p.stdout
    assert "the board runs its FALLBACK image" in p.stdout
    # Recovery: a good user image written and loaded, no fallback any more.
    stock_bit = sockdir / "stock.bit"
    stock_bit.write_bytes(firmware_bit())
    run("--device", "5i25", "--addr", addr, "--write", str(stock_bit))
    p = run("--device", "5i25", "--addr", addr, "--reload")
    assert "Boot status: 0x05 valid reloaded" in p.stdout
    assert flash.read_bytes()[USER : USER + len(stock)] == stock
