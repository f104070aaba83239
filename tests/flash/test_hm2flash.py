# SPDX-License-Identifier: GPL-2.0-or-later
"""bin/hm2flash against a virtual 5i25 whose SPI configuration flash lives
in a file: write / verify / reload / fallback, refusals that leave the
flash untouched, and a power loss in the middle of an erase.

The reference is the flash layout Mesa's Spartan-6 boards use (boot block
at 0, fallback image at 0x10000, user image at 0x100000; flashhelpers.py)
and the .BIT rules of the spec: the tests read the flash file itself."""

from __future__ import annotations

import struct
import subprocess
import time
from pathlib import Path

import pytest
from flashhelpers import StartBoard
from flashhelpers import (
    BOOT,
    BOOT_BLOCK,
    FALLBACK,
    FLASH_SIZE,
    SECTOR,
    USER,
    firmware_bit,
    hm2flash_binary,
    make_bit,
    run,
    vbfw_image,
    vboard,
)


def payload() -> bytes:
    return vboard.bit_payload(firmware_bit())


def addr(sockdir: Path) -> str:
    return f"sim:{sockdir / 'b.sock'}"


def flash(sockdir: Path) -> bytes:
    return (sockdir / "flash.bin").read_bytes()


def test_factory_flash_layout_and_info(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    img = payload()
    f = flash(sockdir)
    assert len(f) == FLASH_SIZE
    assert f[BOOT : BOOT + len(BOOT_BLOCK)] == BOOT_BLOCK
    assert f[FALLBACK : FALLBACK + len(img)] == img
    assert f[USER : USER + len(img)] == img
    p = run("--device", "5i25", "--addr", addr(sockdir))
    assert "Flash size: 16 Mbit (id: 0x14, JEDEC 20 20 15)" in p.stdout
    assert "FPGA type: 6slx9tqg144" in p.stdout
    assert "Firmware: 7I76x2" in p.stdout
    assert "Boot status: 0x01 valid\n" in p.stdout


def test_other_part_is_identified(sockdir: Path, start_board: StartBoard) -> None:
    start_board(part="m25p32")
    assert (sockdir / "flash.bin").stat().st_size == 4 << 20
    p = run("--device", "5i25", "--addr", addr(sockdir))
    assert "Flash size: 32 Mbit (id: 0x15, JEDEC 20 20 16)" in p.stdout


def test_write_verify_reload(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    before = flash(sockdir)
    # Scribble over the user image first so that the write has to change it.
    (sockdir / "flash.bin").open("r+b").write(b"")  # file exists, mapped by the board
    p = run("--device", "5i25", "--addr", addr(sockdir), "--write", str(bit))
    assert "Boot sector OK" in p.stdout
    assert "FLASH memory sectors to write: 1, max sectors in area: 16" in p.stdout
    assert "Erasing FLASH memory sectors starting from 0x100000..." in p.stdout
    assert "Programming FLASH memory sectors starting from 0x100000..." in p.stdout
    assert "You must power cycle the hardware or use the --reload command" in p.stdout
    assert "Board configuration updated successfully." in p.stdout
    assert "Board FLASH memory verified successfully." in p.stdout
    assert "Erasing     [########################################] 100% 65536 bytes" in p.stdout
    img = payload()
    after = flash(sockdir)
    # The user sector holds the image and is erased after it; nothing else moved.
    assert after[USER : USER + len(img)] == img
    assert after[USER + len(img) : USER + SECTOR] == b"\xff" * (SECTOR - len(img))
    assert after[:USER] == before[:USER]
    assert after[USER + SECTOR :] == before[USER + SECTOR :]
    p = run("--device", "5i25", "--addr", addr(sockdir), "--verify", str(bit))
    assert "Board FLASH memory verified successfully." in p.stdout
    p = run("--device", "5i25", "--addr", addr(sockdir), "--reload")
    assert "Board reloaded from the flash image: firmware 7I76x2" in p.stdout
    assert "Boot status: 0x05 valid reloaded" in p.stdout


def test_verify_reports_first_difference(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    with (sockdir / "flash.bin").open("r+b") as f:  # the board maps this file
        f.seek(USER + 33)
        f.write(b"\x00")
    p = run("--device", "5i25", "--addr", addr(sockdir), "--verify", str(bit), check=1)
    want = payload()[33]
    assert f"verification failed at 0x100021 (file: 0x{want:02X}, flash: 0x00)" in p.stderr


def bad_bits(sockdir: Path) -> dict[str, tuple[bytes, str]]:
    good = firmware_bit()
    img = payload()
    crc = struct.unpack_from("<I", img, 12)[0]
    corrupt = bytearray(img)
    corrupt[40] ^= 0xFF  # inside the CRC-protected header
    return {
        "other FPGA": (
            vboard.firmware_file("5i20", "SV12").read_bytes(),
            "wrong bitfile destination device: 2s200pq208, should be 6slx9tqg144",
        ),
        "another board's image": (
            make_bit(vbfw_image("6i25", "7I76x2", crc)),
            "the bitfile is a firmware for a 6i25, not for a 5i25",
        ),
        "corrupt image": (make_bit(bytes(corrupt)), "corrupt (CRC-32 mismatch)"),
        "not a bitstream": (make_bit(b"\x00" * 4096), "no sync word (0xAA995566)"),
        "truncated file": (good[:-10], "bitfile chunk extends past end of firmware"),
        "bad header": (b"\x01" + good[1:], "bitfile has invalid header"),
        "too big": (make_bit(b"\xaa\x99\x55\x66" * (0x180004 // 4)), "does not fit"),
    }


def test_bad_bitfiles_are_refused_and_flash_untouched(
    sockdir: Path, start_board: StartBoard
) -> None:
    start_board()
    before = flash(sockdir)
    for what, (data, message) in bad_bits(sockdir).items():
        bit = sockdir / "bad.bit"
        bit.write_bytes(data)
        for extra in ([], ["--fallback"]):
            p = run(
                "--device", "5i25", "--addr", addr(sockdir), *extra, "--write", str(bit), check=1
            )
            assert message in p.stderr, (what, p.stderr)
            assert "Erasing" not in p.stdout, what
            assert flash(sockdir) == before, what
    p = run("--device", "5i25", "--addr", addr(sockdir))
    assert "Firmware: 7I76x2" in p.stdout


def test_corrupt_user_image_boots_fallback_and_is_recovered(
    sockdir: Path, start_board: StartBoard
) -> None:
    b = start_board()
    b.stop()
    with (sockdir / "flash.bin").open("r+b") as f:
        f.seek(USER + 33)
        f.write(b"\x00\x00")  # inside the image's CRC-protected header
    start_board()
    p = run("--device", "5i25", "--addr", addr(sockdir))
    assert "Firmware: 7I76x2" in p.stdout  # the fallback holds the same firmware
    assert "Boot status: 0x23 valid fallback-used crc-error" in p.stdout
    assert "runs its FALLBACK image: the user image is corrupt or missing" in p.stdout
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    run("--device", "5i25", "--addr", addr(sockdir), "--write", str(bit))
    p = run("--device", "5i25", "--addr", addr(sockdir), "--reload")
    assert "Boot status: 0x05 valid reloaded" in p.stdout


def test_reload_fallback(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    p = run("--device", "5i25", "--addr", addr(sockdir), "--fallback", "--reload")
    assert "Board reloaded from the fallback image: firmware 7I76x2" in p.stdout


def test_both_images_bad_leaves_blank_board(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board()
    b.stop()
    with (sockdir / "flash.bin").open("r+b") as f:
        for a in (USER, FALLBACK):
            f.seek(a)
            f.write(b"\xff" * 68)
    start_board()
    p = run("--device", "5i25", "--addr", addr(sockdir), check=1)
    assert "is not configured (blank FPGA" in p.stderr


def test_boot_block_missing(sockdir: Path, start_board: StartBoard) -> None:
    b = start_board()
    b.stop()
    with (sockdir / "flash.bin").open("r+b") as f:
        f.seek(BOOT)
        f.write(b"\xff" * len(BOOT_BLOCK))
    # Without a boot block the FPGA configures from address 0: nothing there.
    start_board()
    p = run("--device", "5i25", "--addr", addr(sockdir), check=1)
    assert "blank FPGA" in p.stderr


def test_write_without_boot_block_needs_fix(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    with (sockdir / "flash.bin").open("r+b") as f:  # live: the board maps the file
        f.seek(BOOT + 14)
        f.write(b"\x00")
    before = flash(sockdir)
    p = run("--device", "5i25", "--addr", addr(sockdir), "--write", str(bit), check=1)
    assert "BootSector is invalid" in p.stderr
    assert flash(sockdir) == before
    p = run("--device", "5i25", "--addr", addr(sockdir), "--fix-boot-block", "--write", str(bit))
    assert "Writing boot block..." in p.stdout
    assert flash(sockdir)[: len(BOOT_BLOCK)] == BOOT_BLOCK


def test_fallback_write_keeps_user_image(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    before = flash(sockdir)
    p = run("--device", "5i25", "--addr", addr(sockdir), "--fallback", "--write", str(bit))
    assert "starting from 0x10000..." in p.stdout
    after = flash(sockdir)
    assert after[USER:] == before[USER:]
    assert after[FALLBACK : FALLBACK + 68] == payload()


def test_power_loss_mid_erase_then_recovery(sockdir: Path, start_board: StartBoard) -> None:
    # The part's own timing: a sector erase takes 0.6 s of board time, so
    # the board is killed while the user sector is being erased.
    b = start_board(speedup=1)
    bit = sockdir / "fw.bit"
    bit.write_bytes(firmware_bit())
    with (sockdir / "flash.bin").open("r+b") as f:  # a mark at the sector's end
        f.seek(USER + SECTOR - 1)
        f.write(b"\x00")
    tool = subprocess.Popen(
        [str(hm2flash_binary()), "--device", "5i25", "--addr", addr(sockdir), "--write", str(bit)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            # the erase has started once the user sector's first half is blank
            if flash(sockdir)[USER : USER + 68] == b"\xff" * 68:
                break
            time.sleep(0.02)
        else:
            pytest.fail("the erase never started")
        b.kill()  # power loss
        out, err = tool.communicate(timeout=60)
    finally:
        if tool.poll() is None:
            tool.kill()
    assert tool.returncode == 1
    assert "Board configuration updated successfully" not in out
    f = flash(sockdir)
    assert f[USER : USER + 68] == b"\xff" * 68  # the image is gone ...
    assert f[USER + SECTOR - 1] == 0x00  # ... and the erase never finished
    # Power back: the half-erased user image is bad, the fallback comes up.
    start_board()
    p = run("--device", "5i25", "--addr", addr(sockdir))
    assert "fallback-used" in p.stdout
    run("--device", "5i25", "--addr", addr(sockdir), "--write", str(bit))
    p = run("--device", "5i25", "--addr", addr(sockdir), "--reload")
    assert "Boot status: 0x05 valid reloaded" in p.stdout


def test_usage_errors(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    assert "--device NAME is required" in run("--reload", check=2).stderr
    assert "give one command" in run("--device", "5i25", "--reload", "--info", "x", check=2).stderr
    p = run("--device", "5i20", "--addr", addr(sockdir), check=1)
    assert "the 5i20 has no configuration flash" in p.stderr
    p = run("--device", "5i99", "--addr", addr(sockdir), check=1)
    assert "No 5i99 board found" in p.stderr
    p = run("--device", "5i25", "--addr", f"sim:{sockdir / 'none.sock'}", check=1)
    assert "cannot connect" in p.stderr
    p = run(
        "--device", "5i25", "--addr", addr(sockdir), "--write", str(sockdir / "nope.bit"), check=1
    )
    assert "cannot read" in p.stderr


def test_info_file() -> None:
    p = run("--info", str(vboard.firmware_file("5i25", "7I76x2")))
    assert p.stdout == (
        "Checking file... OK\n"
        "  File type: Xilinx bit file\n"
        "  Design name: 7I76x2.ncd;UserID=0xFFFFFFFF\n"
        "  Part name: 6slx9tqg144\n"
        "  Design date: 2026/01/01\n"
        "  Design time: 00:00:00\n"
        "  Config Length: 68\n"
    )
