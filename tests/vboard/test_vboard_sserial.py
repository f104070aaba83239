# SPDX-License-Identifier: GPL-2.0-or-later
"""The virtual 7I76 behind a Smart Serial channel (vboard --sserial): driven
through the real firmware's registers (hm2_sserial.v on the 5i25 7I76x2),
checked against the process-data layout written down in docs/sserial.md
(packed here independently), plus the cable switch and bad options."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common on sys.path)
import vboard
from vboard import VBoardClient, VBoardError, VBoardProcess

SSERIAL = 0x71
BASE = 0x5A00  # SSerial MD base on the 7I76x2
CMD, DATA, CS, IF0, IF1, IF2 = (BASE + 0x100 * k for k in range(6))
DDR, ALTSRC = 0x1100, 0x1200
TX0, RX0 = 10, 11  # SSerial 0 TxData0 / RxData0 (PIN_7I76x2_34.csv)
IN_BITS = {0: 32, 1: 80, 2: 92}


def ss(c: VBoardClient, cmd: str) -> str:
    return c.call(SSERIAL, cmd.encode()).decode()


def run_cmd(c: VBoardClient, word: int) -> tuple[int, int]:
    """Issue a port command, let 300 us pass, return (command, data) registers."""
    c.write(CMD, word)
    c.advance(300_000)
    return c.read32(CMD), c.read32(DATA)


def start(c: VBoardClient, mode: int) -> None:
    c.write(DDR, 1 << TX0)
    c.write(ALTSRC, 1 << TX0)
    c.write(CS, mode)
    assert run_cmd(c, 0xA01) == (0, 0)  # start channel 0 in normal mode: no failure


def expected_in(mode: int, inputs: int, analog: list[float], field: float) -> int:
    """The 7I76 -> host process data of docs/sserial.md."""
    v = inputs & 0xFFFFFFFF
    if mode >= 1:
        for k, a in enumerate(analog):
            v |= min(4095, max(0, round(a / 0.01))) << (32 + 12 * k)
    if mode == 2:
        v |= min(4095, max(0, round(field / 0.01))) << 80
    return v


@pytest.fixture
def board(sockdir: Path) -> VBoardProcess:
    with VBoardProcess(sockdir / "s.sock", "5i25", "7I76x2", ["--sserial", "0.0=7i76"]) as p:
        yield p


@pytest.mark.parametrize("mode", [0, 1, 2])
def test_discovery_reports_name_unit_and_sizes(board: VBoardProcess, mode: int) -> None:
    with board.client() as c:
        start(c, mode)
        assert c.read32(IF0).to_bytes(4, "little") == b"7I76"
        assert c.read32(IF1) == 0x76000000  # unit number of port 0 channel 0
        cs = c.read32(CS)
        assert (cs >> 24, (cs >> 16) & 0xFF, (cs >> 14) & 3) == (48, IN_BITS[mode], 2)
        st = vboard_json(c)
        assert (st["mode"], st["in_bits"], st["started"], st["discovers"]) == (
            mode,
            IN_BITS[mode],
            True,
            1,
        )


def vboard_json(c: VBoardClient) -> dict:
    return json.loads(ss(c, "status"))["remotes"][0]


@pytest.mark.parametrize("mode", [0, 2])
def test_process_data_round_trip(board: VBoardProcess, mode: int) -> None:
    analog = [0.0, 3.3, 12.34, 50.0]  # 50 V is past the ADC's range: it clips at 40.95
    with board.client() as c:
        for k, a in enumerate(analog):
            ss(c, f"set 0.0 analog {k} {a}")
        ss(c, "set 0.0 field 23.456")
        start(c, mode)
        for pattern in (0x00000000, 0xFFFFFFFF, 0xA5A5_5A5A, 0x0000_0001, 0x8000_0000):
            ss(c, f"set 0.0 inputs {pattern:#x}")
            outs = (~pattern) & 0xFFFF
            c.write(IF0, outs | (1 << 16))  # outputs, spindle enable on, direction off
            c.write(IF1, 0xC000)  # DAC
            assert run_cmd(c, 0x1001) == (0, 0)
            got = c.read32(IF0) | c.read32(IF1) << 32 | c.read32(IF2) << 64
            assert got == expected_in(mode, pattern, analog, 23.456)
            st = vboard_json(c)
            assert (st["outputs"], st["spinena"], st["spindir"]) == (outs, True, False)
            assert st["spinout_raw"] == 0xC000
            assert st["spinout_v"] == pytest.approx(0xC000 * 10 / 65535, abs=1e-6)
        assert vboard_json(c)["process"] == 5


def test_single_input_and_direction_bits(board: VBoardProcess) -> None:
    with board.client() as c:
        start(c, 0)
        for n in range(32):
            ss(c, "set 0.0 inputs 0")
            ss(c, f"set 0.0 input {n} 1")
            c.write(IF0, (1 << (n % 16)) | (1 << 17))
            assert run_cmd(c, 0x1001) == (0, 0)
            assert c.read32(IF0) == 1 << n
            st = vboard_json(c)
            assert (st["outputs"], st["spinena"], st["spindir"]) == (1 << (n % 16), False, True)


def test_unplugged_cable_stops_answers_until_rediscovered(board: VBoardProcess) -> None:
    with board.client() as c:
        start(c, 0)
        ss(c, "set 0.0 inputs 0x55")
        assert run_cmd(c, 0x1001) == (0, 0)
        ss(c, "set 0.0 plugged 0")
        assert run_cmd(c, 0x1001) == (0, 1)  # channel 0 failed
        assert (c.read32(CS) >> 8) & 0x1F == 0x01  # no answer
        assert c.read32(IF0) == 0x55  # the last good answer stays
        ss(c, "set 0.0 inputs 0xAA")
        ss(c, "set 0.0 plugged 1")
        # powered up again: process data is refused until a new discovery
        assert run_cmd(c, 0x1001) == (0, 1)
        assert run_cmd(c, 0xA01) == (0, 0)
        assert run_cmd(c, 0x1001) == (0, 0)
        assert c.read32(IF0) == 0xAA
        st = vboard_json(c)
        assert (st["plugged"], st["discovers"], st["unanswered"]) == (True, 2, 1)


def test_bad_commands_leave_the_remote_alone(board: VBoardProcess) -> None:
    with board.client() as c:
        before = ss(c, "status")
        for bad, msg in [
            ("set 0.1 inputs 1", "no remote on channel '0.1'"),
            ("set 0.0 input 32 1", "7i76: want"),
            ("set 0.0 analog 4 1.0", "7i76: want"),
            ("set 0.0 plugged 2", "plugged 0|1"),
            ("frobnicate", "unknown command"),
        ]:
            with pytest.raises(VBoardError) as e:
                ss(c, bad)
            assert msg in e.value.message
        assert ss(c, "status") == before


def test_mode_the_7i76_lacks_is_not_answered(board: VBoardProcess) -> None:
    with board.client() as c:
        c.write(DDR, 1 << TX0)
        c.write(ALTSRC, 1 << TX0)
        c.write(CS, 5)
        assert run_cmd(c, 0xA01) == (0, 1)
        assert vboard_json(c)["started"] is False


def test_no_remote_no_sserial_request(sockdir: Path) -> None:
    with VBoardProcess(sockdir / "n.sock", "5i25", "7I76x2") as p, p.client() as c:
        with pytest.raises(VBoardError, match="no Smart Serial remote"):
            ss(c, "status")


@pytest.mark.parametrize(
    "board_name,arg,msg",
    [
        ("5i25", "0.0=7i99", "unknown remote board '7i99'"),
        ("5i25", "4.0=7i76", "want P.C=TYPE"),
        ("5i25", "0.4=7i76", 'has no pin "SSerial 0 TxData4"'),
        ("5i25", "0.7=7i77", "a 7i77 takes two channels"),
        ("5i25", "0.3=7i77", 'has no pin "SSerial 0 TxData4"'),
        ("5i25", "0.0=7i77-analog", "unknown remote board"),
        ("5i20", "0.0=7i76", "no firmware of board 5i20 has a Smart Serial port"),
    ],
)
def test_bad_sserial_option_is_refused(sockdir: Path, board_name: str, arg: str, msg: str) -> None:
    sock = str(sockdir / "x.sock")
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--socket", sock, "--board", board_name, "--sserial", arg],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert r.returncode != 0
    assert msg in r.stderr


@pytest.mark.parametrize("mode", [0, 2])
def test_exchange_time_matches_the_frame_lengths(board: VBoardProcess, mode: int) -> None:
    """A doit takes the wire time of both frames (docs/sserial.md): host
    1 + ceil(48/8) + CRC bytes, answer 1 + ceil(in_bits/8) + CRC bytes, 10
    bits each, plus the remote's 2-bit turnaround; a little more for the
    UART synchronizers and the 500 ns polling step here."""
    with board.client() as c:
        clk = c.hello().clock_low_hz
        bit_ns = round(clk / 2.5e6) * 1e9 / clk
        start(c, mode)
        c.write(CMD, 0x1001)
        t0 = c.now()
        while c.read32(CMD) != 0:
            c.advance(500)
        took = c.now() - t0
        nbytes = (1 + 6 + 1) + (1 + (IN_BITS[mode] + 7) // 8 + 1)
        wire = (nbytes * 10 + 2) * bit_ns
        assert wire <= took <= wire + 1500, (took, wire)


MACHINE_5I25 = """board = "5i25"
firmware = "7I76x2"
[[axis]]
name = "s"
type = "rotary"
[axis.motor]
type = "dc"
resistance_ohm = 1.0
inductance_h = 1e-3
kt_nm_per_a = 0.08
ke_v_s_per_rad = 0.08
inertia_kg_m2 = 2e-5
[axis.amplifier]
a = "IO 0"
b = "IO 1"
bus_v = 24
[axis.encoder]
a = "Encoder 0 A"
b = "Encoder 0 B"
index = "Encoder 0 Index"
counts_per_rev = 400
"""


def test_remote_and_machine_run_together(sockdir: Path) -> None:
    """--machine and --sserial on one board: the machine keeps its pins
    (the encoder counts), the remote its channel (exchanges succeed)."""
    f = sockdir / "m.toml"
    f.write_text(MACHINE_5I25)
    args = ["--machine", str(f), "--sserial", "0.0=7i76"]
    with VBoardProcess(sockdir / "mm.sock", "5i25", "7I76x2", args) as p, p.client() as c:
        start(c, 0)
        ss(c, "set 0.0 inputs 0x1234")
        c0 = c.read32(0x3000) & 0xFFFF
        for _ in range(5):
            assert run_cmd(c, 0x1001) == (0, 0)
        assert c.read32(IF0) == 0x1234
        assert (c.read32(0x3000) & 0xFFFF) != c0  # the motor turned the encoder
        assert json.loads(c.plant("status"))["axes"]
        assert vboard_json(c)["process"] == 5
