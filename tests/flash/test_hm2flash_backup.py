# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash --backup-flash reads the whole flash: on an M25P16 that is 2 MiB
byte by byte (minutes of simulation, bench/flash), so here the virtual 5i25
carries the 1 Mbit M25P10-A (vboard --flash-part m25p10, 128 KiB in four
32 KiB sectors): the same code paths, the whole flash in a few seconds.

References: the flash file the model maps (the backup must equal it byte for
byte), and the Spartan-6 layout of flashhelpers.py: the boot block at 0
names the user image at 0x100000, past the end of this flash, so the FPGA
loads the fallback image at 0x10000 (CRC error on the MultiBoot image)."""

from __future__ import annotations

from pathlib import Path

from flashhelpers import (
    BOOT_BLOCK,
    FALLBACK,
    StartBoard,
    firmware_bit,
    make_bit,
    run,
    vboard,
)

SIZE = 128 << 10
SECTOR_32K = 0x8000


def test_backup_of_a_whole_small_flash(sockdir: Path, start_board: StartBoard) -> None:
    start_board(part="m25p10")
    addr = f"sim:{sockdir / 'b.sock'}"
    flash = sockdir / "flash.bin"
    p = run("--device", "5i25", "--addr", addr)
    assert "Flash size: 1 Mbit (id: 0x10, JEDEC 20 20 11)" in p.stdout
    assert "Boot status: 0x23 valid fallback-used crc-error" in p.stdout
    stock = vboard.bit_payload(firmware_bit())
    before = flash.read_bytes()
    assert before[: len(BOOT_BLOCK)] == BOOT_BLOCK  # factory contents
    assert before[FALLBACK : FALLBACK + len(stock)] == stock
    # 32 KiB sectors: a 33 KiB fallback image takes two sector erases
    data = b"\xaa\x99\x55\x66" + bytes(i % 251 for i in range(33 * 1024 - 4))
    bit = sockdir / "fb.bit"
    bit.write_bytes(make_bit(data))
    p = run(
        "--device", "5i25", "--addr", addr, "--fallback", "--no-auto-verify", "--write", str(bit)
    )
    assert "Erasing     [####" in p.stdout and "65536 bytes" in p.stdout  # 2 x 32 KiB
    out = sockdir / "backup.bin"
    p = run("--device", "5i25", "--addr", addr, "--backup-flash", str(out))
    assert f"Reading all FLASH memory ({SIZE} bytes)..." in p.stdout
    assert f"Flash memory backed up to {out}" in p.stdout
    b = out.read_bytes()
    assert len(b) == SIZE and b == flash.read_bytes()
    end = FALLBACK + 2 * SECTOR_32K
    assert b[:FALLBACK] == before[:FALLBACK]  # the boot block sector untouched
    assert b[FALLBACK : FALLBACK + len(data)] == data
    assert b[FALLBACK + len(data) : end] == b"\xff" * (end - FALLBACK - len(data))
    assert b[end:] == before[end:]
    # no user area on this flash: --write refuses, nothing changes
    before = flash.read_bytes()
    p = run("--device", "5i25", "--addr", addr, "--write", str(bit), check=1)
    assert "does not fit the 0-byte flash area" in p.stderr
    assert flash.read_bytes() == before
    # a backup file that cannot be written: the error, exit 1
    p = run("--device", "5i25", "--addr", addr, "--backup-flash", str(sockdir), check=1)
    assert "cannot write" in p.stderr
