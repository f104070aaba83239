# SPDX-License-Identifier: GPL-2.0-or-later
"""Blank boards and the configuration port: .BIT firmware files made by the build
(tools/vbfw), good and bad images, reset."""

from __future__ import annotations

import struct
import zlib
from collections.abc import Iterator
from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common and tools/vbfw on sys.path)
import vbfw
import vboard
from vbhelpers import fw_json, stop_clean
from vboard import VBoardClient, VBoardError, VBoardProcess


@pytest.fixture
def blank(sockdir: Path) -> Iterator[VBoardClient]:
    p = VBoardProcess(sockdir / "b.sock", "5i20")
    try:
        assert p.ready_line.endswith("(5i20, blank)")
        with p.client() as c:
            yield c
    finally:
        stop_clean(p)


def _payload(board: str, fw: str) -> bytes:
    return vboard.bit_payload(vboard.firmware_file(board, fw).read_bytes())


def _assert_blank(c: VBoardClient) -> None:
    h = c.hello()
    assert (h.state, h.firmware, h.clock_low_hz, h.clock_high_hz) == (vboard.STATE_BLANK, "", 0, 0)
    st = c.config(vboard.CONFIG_STATUS)
    assert (st.done, st.firmware) == (0, "")
    with pytest.raises(VBoardError, match="not configured") as e:
        c.read32(0x100)
    assert e.value.status == -19  # -ENODEV
    assert all(p.level == 1 and p.oe == 0 for p in c.probe(0, 72))


def test_the_build_makes_bit_files_for_every_firmware() -> None:
    for board, fw in [
        ("5i20", "SVST8_4"),
        ("5i20", "SV12"),
        ("5i25", "7I76x2"),
        ("7i43", "SV8"),
        ("7i43", "SVST4_4"),
    ]:
        bit = vboard.firmware_file(board, fw).read_bytes()
        desc = fw_json(board, fw)
        assert bit[:13] == vbfw.BIT_HEADER
        assert (
            b"b"
            + struct.pack(">H", len(desc["board"]["fpga_part"]) + 1)
            + desc["board"]["fpga_part"].encode()
            + b"\0"
            in bit
        )
        img = vboard.bit_payload(bit)
        magic, version, length, crc = struct.unpack_from("<IIII", img)
        assert (magic, version, length) == (0x57464256, 1, len(img))
        assert img[16:32].rstrip(b"\0").decode() == board
        assert img[32:64].rstrip(b"\0").decode() == fw
        assert struct.unpack_from("<I", img, 64)[0] == zlib.crc32(img[:64])
        words = [
            int(w, 16)
            for w in (vboard.build_dir() / "generated" / board / fw / f"{fw}.idrom.hex")
            .read_text()
            .split()
        ]
        assert crc == zlib.crc32(struct.pack(f"<{len(words)}I", *words))


def test_blank_board_then_program(blank: VBoardClient) -> None:
    _assert_blank(blank)
    st = blank.program(_payload("5i20", "SVST8_4"))
    assert (st.done, st.init, st.firmware) == (1, 1, "SVST8_4")
    h = blank.hello()
    assert (h.state, h.firmware, h.clock_low_hz) == (vboard.STATE_CONFIGURED, "SVST8_4", 33333333)
    assert blank.read32(0x100) == 0x55AACAFE
    # Another firmware replaces it; RESET makes the board blank again.
    assert blank.program(_payload("5i20", "SV12")).firmware == "SV12"
    assert blank.hello().firmware == "SV12"
    # the dog bites right after configuration (Timer powers up at 0, like
    # Mesa's firmware): let it, then drive a pin
    blank.advance(1000)
    blank.write(0x1100, 0x1)
    assert blank.pin(0).oe == 1
    assert blank.config(vboard.CONFIG_RESET).done == 0
    _assert_blank(blank)


def _image(board: str = "5i20", fw: str = "SVST8_4", crc: int | None = None) -> bytes:
    good = _payload("5i20", "SVST8_4")
    return vbfw.make_image(board, fw, struct.unpack_from("<I", good, 12)[0] if crc is None else crc)


@pytest.mark.parametrize(
    "image,text",
    [
        (_payload("5i25", "7I76x2"), "firmware image is for board 5i25, this board is a 5i20"),
        (lambda: _payload("5i20", "SVST8_4")[:40], "truncated: 40 bytes"),
        (lambda: _payload("5i20", "SVST8_4")[:67], "truncated"),
        (lambda: _payload("5i20", "SVST8_4") + b"\0", "longer than its header says"),
        (
            lambda: _payload("5i20", "SVST8_4")[:20] + b"X" + _payload("5i20", "SVST8_4")[21:],
            "corrupt: CRC-32",
        ),
        (lambda: b"\xff" * 200, "bad magic"),
        (lambda: b"", "truncated: 0 bytes"),
        (
            lambda: _image(fw="SVST9_9"),
            "firmware image SVST9_9 is not built into this vboard for board 5i20",
        ),
        (
            lambda: _image(crc=0x12345678),
            "does not match the Verilated firmware (IDROM CRC 0x12345678",
        ),
        (lambda: struct.pack("<II", 0x57464256, 2) + b"\0" * 60, "format version 2"),
    ],
    ids=[
        "wrong-board",
        "truncated",
        "truncated-1",
        "trailing",
        "corrupt",
        "not-vbfw",
        "empty",
        "unknown-fw",
        "other-build",
        "version",
    ],
)
def test_bad_images_leave_the_board_blank(blank: VBoardClient, image: object, text: str) -> None:
    data = image() if callable(image) else image
    assert isinstance(data, bytes)
    with pytest.raises(VBoardError) as e:
        blank.program(data)
    assert e.value.status == -22
    assert text in e.value.message
    assert "5i20: configuration failed, board stays blank" in e.value.message
    _assert_blank(blank)
    # A configured board keeps its firmware (the bad request is not applied).
    assert blank.program(_payload("5i20", "SV12")).done == 1
    blank.advance(1000)  # past the power-up bite (the Timer powers up at 0)
    blank.write(0x1100, 0x3)
    with pytest.raises(VBoardError) as e:
        blank.program(data)
    assert "5i20: configuration failed, board keeps firmware SV12" in e.value.message
    assert blank.hello().firmware == "SV12"
    assert blank.config(vboard.CONFIG_STATUS).firmware == "SV12"
    assert blank.read32(0x1100) == 0x3 and blank.pin(1).oe == 1


def test_config_status_and_reset_take_no_bitstream(blank: VBoardClient) -> None:
    with pytest.raises(VBoardError, match="carries no bitstream"):
        blank.config(vboard.CONFIG_STATUS, b"junk")


def test_blank_board_time_and_pins_still_work(blank: VBoardClient) -> None:
    t0 = blank.now()
    assert blank.advance(5_000) == t0 + 5_000
    blank.quad(0, 1, 1e6)
    blank.advance(100_000)
    assert blank.pin(0).rising == pytest.approx(25, abs=1)
    with pytest.raises(VBoardError, match="blank"):
        blank.dump("/tmp/never.vcd")
