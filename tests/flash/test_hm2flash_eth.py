# SPDX-License-Identifier: GPL-2.0-or-later
"""bin/hm2flash on the Ethernet boards: the virtual 7i92 and 7i96S
(vboard --udp) whose configuration flash is a file, reached through LBP16
memory space 3.

References: the flash layout and the messages of Debian's mesaflash
recorded against the same boards (tests/data/eth/mesaflash: user area
0x100000 on the 7i92, 0x200000 on the 7i96S, the wrong-board refusal), and
the flash file itself, read by the test."""

from __future__ import annotations

from pathlib import Path

import pytest
from ethboard import FIRMWARE, LAYOUT, recorded_output, start_eth
from flashhelpers import BOOT_BLOCK, firmware_bit, make_bit, run, vbfw_image, vboard


def flash(sockdir: Path, board: str) -> bytes:
    return (sockdir / f"flash-{board}.bin").read_bytes()


def bit_of(board: str) -> Path:
    return vboard.firmware_file(board, FIRMWARE[board])


def recorded_lines(name: str) -> list[str]:
    """mesaflash's lines but its progress marks (|E, |W, |V) and the
    second 'Checking file' block its --write prints before verifying."""
    return [line for line in recorded_output(name).splitlines() if not line.startswith("  |")]


@pytest.mark.parametrize("board", ["7i92", "7i96s"])
def test_write_verify_reload(sockdir: Path, board: str) -> None:
    lay = LAYOUT[board]
    p, ip = start_eth(sockdir, board)
    with p:
        r = run("--device", board, "--addr", ip)
        assert r.stdout.startswith(f"ETH device {board.upper()} at ip={ip}\n")
        want_id = {"7i92": "16 Mbit (id: 0x14)", "7i96s": "32 Mbit (id: 0x15)"}[board]
        assert f"  Flash size: {want_id}\n" in r.stdout
        before = flash(sockdir, board)
        assert len(before) == lay["size"]
        # another configuration for the same FPGA (a Xilinx one carries the
        # sync word), 12 pages: only the user area changes
        data = bytes((i * 7 + 3) & 0xFF for i in range(3000))
        if board == "7i92":
            data = b"\xff" * 16 + bytes.fromhex("AA995566") + data
        f = sockdir / "new.bit"
        f.write_bytes(make_bit(data, part=_part(board)))
        r = run("--device", board, "--addr", ip, "--write", str(f))
        after = flash(sockdir, board)
        user, size = lay["user"], len(data)
        assert after[user : user + size] == data
        assert after[user + size : user + 0x10000] == b"\xff" * (0x10000 - size)
        assert after[:user] == before[:user]  # fallback (and boot block) untouched
        assert after[user + 0x10000 :] == before[user + 0x10000 :]
        want = recorded_lines(f"{board}-write")
        got = r.stdout.splitlines()
        for line in want:
            if line.startswith(("Checking file", "  File type", "Boot sector")):
                continue
            assert line in got, (line, r.stdout)
        r = run("--device", board, "--addr", ip, "--verify", str(f))
        assert "Board FLASH memory verified successfully." in r.stdout
        # the stock image back, then reload: the board answers again
        run("--device", board, "--addr", ip, "--write", str(bit_of(board)))
        r = run("--device", board, "--addr", ip, "--reload")
        assert "Board reloaded from the flash image: firmware HostMot2 (cookie 0x55AACAFE)" in (
            r.stdout
        )
        run("--device", board, "--addr", ip, "--verify", str(bit_of(board)))


def _part(board: str) -> str:
    return {"7i92": "6slx9tqg144", "7i96s": "T20F256"}[board]


def test_7i92_boot_block_and_fallback(sockdir: Path) -> None:
    p, ip = start_eth(sockdir, "7i92")
    img = vboard.bit_payload(bit_of("7i92").read_bytes())
    with p:
        f = flash(sockdir, "7i92")
        assert f[: len(BOOT_BLOCK)] == BOOT_BLOCK
        run("--device", "7i92", "--addr", ip, "--fallback", "--write", str(bit_of("7i92")))
        assert flash(sockdir, "7i92")[0x10000 : 0x10000 + len(img)] == img
    # a flash whose boot block is gone (written while the board is off)
    path = sockdir / "flash-7i92.bin"
    f = bytearray(path.read_bytes())
    f[:256] = b"\xff" * 256
    path.write_bytes(bytes(f))
    p, ip = start_eth(sockdir, "7i92")
    with p:
        r = run("--device", "7i92", "--addr", ip, "--write", str(bit_of("7i92")), check=1)
        assert "Error: BootSector is invalid" in r.stderr
        assert flash(sockdir, "7i92") == bytes(f)
        r = run(
            "--device", "7i92", "--addr", ip, "--fix-boot-block", "--write", str(bit_of("7i92"))
        )
        assert "Writing boot block..." in r.stdout
        assert flash(sockdir, "7i92")[: len(BOOT_BLOCK)] == BOOT_BLOCK


def test_backup_flash_equals_the_board_flash(sockdir: Path) -> None:
    p, ip = start_eth(sockdir, "7i96s")
    with p:
        out = sockdir / "backup.bin"
        r = run("--device", "7i96s", "--addr", ip, "--backup-flash", str(out))
        assert "Reading all FLASH memory (4194304 bytes)" in r.stdout
        assert out.read_bytes() == flash(sockdir, "7i96s")


def test_refusals_leave_the_flash_untouched(sockdir: Path) -> None:
    p, ip = start_eth(sockdir, "7i96s")
    with p:
        before = flash(sockdir, "7i96s")
        # another FPGA: mesaflash's message (recorded)
        r = run("--device", "7i96s", "--addr", ip, "--write", str(bit_of("7i92")), check=1)
        want = [x for x in recorded_lines("7i96s-wrong-board") if x.startswith("Error:")][0]
        assert want.removeprefix("Error: ") in r.stderr
        # not a .BIT file; truncated; a firmware image for another board
        bad = sockdir / "bad.bit"
        bad.write_bytes(b"not a bitfile, but long enough to hold a header")
        r = run("--device", "7i96s", "--addr", ip, "--write", str(bad), check=1)
        assert "invalid header" in r.stderr
        good = bit_of("7i96s").read_bytes()
        bad.write_bytes(good[: len(good) - 20])
        run("--device", "7i96s", "--addr", ip, "--write", str(bad), check=1)
        other = vbfw_image("7i92", "7I76x2", 0x12345678)
        bad.write_bytes(make_bit(other, part="T20F256"))
        r = run("--device", "7i96s", "--addr", ip, "--write", str(bad), check=1)
        assert "nothing written" in r.stderr
        # too large for the area
        bad.write_bytes(make_bit(b"\x00" * (0x200000 + 4), part="T20F256"))
        r = run("--device", "7i96s", "--addr", ip, "--write", str(bad), check=1)
        assert "does not fit" in r.stderr
        assert flash(sockdir, "7i96s") == before
        # verify against other data: the first difference
        bad.write_bytes(make_bit(b"\x01\x02\x03\x04", part="T20F256"))
        r = run("--device", "7i96s", "--addr", ip, "--verify", str(bad), check=None)
        assert r.returncode == 1
        assert "verification failed at 0x200000" in r.stderr
        # the wrong board at that address; nobody at another
        r = run("--device", "7i92", "--addr", ip, check=1)
        assert f"No 7I92 board found (the board at {ip} is a 7i96s)" in r.stderr
        r = run("--device", "7i96s", "--addr", f"sim:{sockdir / 'x.sock'}", check=1)
        assert "give its IP address" in r.stderr
    r = run("--device", "7i96s", "--addr", ip, check=1)
    assert "no reply" in r.stderr
