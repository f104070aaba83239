# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_7i43 on both sizes of the virtual 7i43: `vboard --board 7i43` (400K,
3s400tq144) and `--board 7i43-2` (200K, 3s200tq144), with the firmware
directories Mesa's packages use and LinuxCNC's sample configurations name
(hm2/7i43-4/ and hm2/7i43-2/).  The driver reads the size from the CPLD and
the hostmot2 core refuses a .BIT whose part is not that FPGA, before it
sends anything: the board stays blank.  The expected parts come from the
.BIT files themselves (their 'b' chunk, parsed here) and from the CPLD size
bit as spec/hostmot2.md 17.2 gives it (1 = 400K)."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from hm2e2e import BUILD, halrun, vboard

FW = BUILD / "lib" / "firmware" / "hm2"
HM2_7I43 = BUILD / "lib" / "rtlib" / "hm2_7i43.so"
pytestmark = pytest.mark.requires_build(
    HM2_7I43,
    BUILD / "bin" / "vboard",
    FW / "7i43-2" / "SVST4_4.BIT",
    FW / "7i43-4" / "SVST4_4.BIT",
    FW / "7i43-2" / "SV8.BIT",
    FW / "7i43-4" / "SV8.BIT",
)
PFX = "hm2_7i43.0"
PART = {"7i43": "3s400tq144", "7i43-2": "3s200tq144"}
DIR_PART = {"7i43-4": "3s400tq144", "7i43-2": "3s200tq144", "7i43": "3s400tq144"}


def bit_chunks(data: bytes) -> dict[str, bytes]:
    """The a..e chunks of a Xilinx .BIT file (13-byte header, then
    tag + 16-bit length for a..d, tag + 32-bit length for e)."""
    out: dict[str, bytes] = {}
    i = 13
    while i < len(data):
        tag = chr(data[i])
        if tag == "e":
            (n,) = struct.unpack_from(">I", data, i + 1)
            out[tag] = data[i + 5 : i + 5 + n]
            break
        (n,) = struct.unpack_from(">H", data, i + 1)
        out[tag] = data[i + 3 : i + 3 + n]
        i += 3 + n
    return out


def load(sock: Path, firmware: str) -> str:
    return (
        "loadrt hostmot2\n"
        f'loadrt hm2_7i43 port=sim:{sock} config="firmware={firmware} num_encoders=1"\n'
        "loadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read servo\n"
        f"addf {PFX}.write servo\n"
        "simrun 1ms\n"
    )


def state(sock: Path) -> tuple[int, str]:
    with vboard.VBoardClient(sock) as c:
        h = c.hello()
    return h.state, h.firmware


@pytest.mark.parametrize("fw", ["SVST4_4", "SV8"])
@pytest.mark.parametrize("fwdir", ["7i43-4", "7i43-2", "7i43"])
def test_bit_files_name_their_part(fwdir: str, fw: str) -> None:
    chunks = bit_chunks((FW / fwdir / f"{fw}.BIT").read_bytes())
    assert chunks["b"] == DIR_PART[fwdir].encode() + b"\0"
    assert chunks["a"].startswith(f"{fw}.ncd".encode())
    image = chunks["e"]
    board = image[16:32].rstrip(b"\0").decode()
    # a 200K image is for the 200K board only
    assert board == ("7i43-2" if fwdir == "7i43-2" else "7i43")
    assert image[32:64].rstrip(b"\0").decode() == fw
    # the 400K directory holds the same file as hm2/7i43/
    if fwdir == "7i43-4":
        assert (FW / fwdir / f"{fw}.BIT").read_bytes() == (FW / "7i43" / f"{fw}.BIT").read_bytes()


@pytest.mark.parametrize(
    "board,fwdir", [("7i43", "7i43-4"), ("7i43-2", "7i43-2"), ("7i43", "7i43")]
)
def test_the_right_size_loads(tmp_path: Path, board: str, fwdir: str) -> None:
    with vboard.VBoardProcess(tmp_path / "b.sock", board) as vb:
        sock = Path(vb.socket_path)
        fw = f"hm2/{fwdir}/SVST4_4.BIT"
        r = halrun(tmp_path, "debug 4\n" + load(sock, fw))
        out = r.stdout + r.stderr
        assert r.returncode == 0, out
        assert f"{PFX}: detected FPGA '{PART[board]}'" in out, out
        assert f"Part Name: {PART[board]}" in out, out
        assert state(sock) == (vboard.STATE_CONFIGURED, "SVST4_4")
        assert f"vboard: {board}: configured with SVST4_4" in vb.stderr_so_far()


@pytest.mark.parametrize(
    "board,fwdir", [("7i43", "7i43-2"), ("7i43-2", "7i43-4"), ("7i43-2", "7i43")]
)
def test_the_wrong_size_is_refused(tmp_path: Path, board: str, fwdir: str) -> None:
    with vboard.VBoardProcess(tmp_path / "b.sock", board) as vb:
        sock = Path(vb.socket_path)
        fw = f"hm2/{fwdir}/SV8.BIT"
        r = halrun(tmp_path, load(sock, fw))
        out = r.stdout + r.stderr
        assert r.returncode != 0, out
        assert (
            f"{PFX}: board has FPGA '{PART[board]}', but the firmware in {fw} is for FPGA "
            f"'{DIR_PART[fwdir]}'" in out
        ), out
        # refused before a byte was sent: the CPLD left it blank
        assert state(sock)[0] == vboard.STATE_BLANK
        assert "configured with" not in vb.stderr_so_far()
        assert "configuration failed" not in vb.stderr_so_far()


def test_a_400k_image_sent_to_the_200k_board_leaves_it_blank(tmp_path: Path) -> None:
    # the .BIT part check bypassed (a file claiming 3s200tq144 around a
    # 400K image): the board itself refuses it, as a 3s200 refuses a 3s400
    # bitstream
    good = (FW / "7i43-4" / "SVST4_4.BIT").read_bytes()
    forged = good.replace(b"3s400tq144\0", b"3s200tq144\0")
    assert forged != good
    fwdir = tmp_path / "fw" / "hm2" / "7i43-2"
    fwdir.mkdir(parents=True)
    (fwdir / "X.BIT").write_bytes(forged)
    with vboard.VBoardProcess(tmp_path / "b.sock", "7i43-2") as vb:
        sock = Path(vb.socket_path)
        r = halrun(
            tmp_path,
            load(sock, "hm2/7i43-2/X.BIT"),
            extra_env={"HM2_FIRMWARE_PATH": str(tmp_path / "fw")},
        )
        assert r.returncode != 0, r.stdout + r.stderr
        assert state(sock)[0] == vboard.STATE_BLANK
        assert "vboard: 7i43-2: configuration failed, board stays blank" in vb.stderr_so_far()


def test_vboard_lists_both_sizes() -> None:
    import subprocess

    r = subprocess.run(
        [str(BUILD / "bin" / "vboard"), "--list"], capture_output=True, text=True, timeout=30
    )
    assert r.returncode == 0, r.stderr
    assert "7i43 (3s400tq144): SVST4_4 SV8 SVST2_4_7I47" in r.stdout.splitlines()
    assert "7i43-2 (3s200tq144): SVST4_4 SV8 SVST2_4_7I47" in r.stdout.splitlines()
