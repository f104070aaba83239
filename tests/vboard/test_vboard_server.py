# SPDX-License-Identifier: GPL-2.0-or-later
"""The vboard server: identity, IDROM through the socket, time, clients, bad requests, exit."""

from __future__ import annotations

import errno
import os
import signal
import socket
import struct
import subprocess
import time
from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common and tools/vbfw on sys.path)
import vboard
from vbhelpers import fw_json
from vboard import VBoardClient, VBoardError, VBoardProcess

FIRMWARES = [("5i20", "SVST8_4"), ("5i20", "SV12"), ("5i25", "7I76x2")]


@pytest.mark.parametrize("board,fw", FIRMWARES)
def test_hello_and_idrom_match_the_generated_firmware(sockdir: Path, board: str, fw: str) -> None:
    desc = fw_json(board, fw)
    with VBoardProcess(sockdir / "b.sock", board, fw) as p, p.client() as c:
        h = c.hello()
        assert (h.version, h.bus, h.state) == (1, vboard.BUS_LOCAL, vboard.STATE_CONFIGURED)
        assert (h.board, h.firmware, h.fpga_part) == (board, fw, desc["board"]["fpga_part"])
        assert h.io_pins == desc["board"]["io_width"]
        assert (h.clock_low_hz, h.clock_high_hz) == (
            desc["clocks"]["low_hz"],
            desc["clocks"]["high_hz"],
        )
        assert h.lockstep
        assert p.ready_line == f"vboard: ready on {sockdir / 'b.sock'} ({board}, {fw})"
        # The ID block (cookie, name, IDROM pointer) and the whole IDROM.
        idb = desc["id_block"]
        assert c.read(idb["address"], 4) == idb["words"]
        hexfile = vboard.build_dir() / "generated" / board / fw / f"{fw}.idrom.hex"
        words = [int(w, 16) for w in hexfile.read_text().split()]
        # Two transfers in one request: their data concatenated in order.
        off = desc["idrom"]["offset"]
        data = c.read_bursts([(off, 512), (off + 512, 4 * len(words) - 512)])
        assert list(struct.unpack(f"<{len(words)}I", data)) == words


def test_reads_take_bus_clocks(client: VBoardClient) -> None:
    """A burst of N reads costs N+1 ClockLow cycles (pipelined), not N round trips."""
    t0 = client.now()
    client.read(0x400, 1)
    t1 = client.board_time_ns
    client.read(0x400, 64)
    t2 = client.board_time_ns
    period = 30  # ClockLow = 100/3 MHz on the 5i20
    one, many = t1 - t0, t2 - t1
    assert one <= 3 * period
    assert many - one == pytest.approx(63 * period, abs=period)


def test_lockstep_time_follows_the_host(client: VBoardClient) -> None:
    base = 5_000_000_000
    client.hello(time_ns=base)  # sets this connection's epoch: no jump
    t0 = client.board_time_ns
    assert t0 < 1_000_000
    client.hello(time_ns=base + 123_450)
    assert client.board_time_ns == t0 + 123_450
    client.hello(time_ns=base + 100)  # earlier: executed at the current time
    assert client.board_time_ns == t0 + 123_450
    client.hello()  # 0: no advance
    assert client.board_time_ns == t0 + 123_450
    assert client.advance(10_000) == t0 + 133_450
    # A second connection has its own epoch: its first time is "now".
    with VBoardClient(client.path) as other:
        other.hello(time_ns=7)
        assert other.board_time_ns == t0 + 133_450
        other.hello(time_ns=1007)
        assert other.board_time_ns == t0 + 134_450
    # Re-entering lockstep re-takes the epochs.
    client.lockstep()
    client.hello(time_ns=42)
    assert client.board_time_ns == t0 + 134_450


def test_freerun_advances_with_the_wall_clock(sockdir: Path) -> None:
    with VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--freerun"]) as p, p.client() as c:
        assert not c.hello().lockstep
        t0 = c.now()
        time.sleep(0.3)
        t1 = c.now()
        # Time passes without requests; at most as fast as the wall clock.
        assert 0 < t1 - t0 <= 0.3e9 + 50e6
        # Host times are ignored while free-running.
        c.hello(time_ns=10**15)
        assert c.board_time_ns < 10**12
        c.lockstep()
        t2 = c.now()
        time.sleep(0.1)
        assert c.now() == t2


def test_time_requests_switch_modes(client: VBoardClient) -> None:
    client.freerun()
    assert not client.hello().lockstep
    t0 = client.now()
    time.sleep(0.2)
    t1 = client.now()
    assert t1 > t0
    # advance works while free-running too
    assert client.advance(50_000) >= t1 + 50_000
    client.lockstep()
    h = client.hello()
    assert h.lockstep
    t2 = client.now()
    time.sleep(0.1)
    assert client.now() == t2
    with pytest.raises(VBoardError, match="more than one request may advance the board"):
        client.advance(2**64 - 1)


def test_one_request_advances_at_most_60_s(client: VBoardClient) -> None:
    """A bad time stamp cannot keep the board simulating for hours while the
    other clients wait: more than 60 s of board time in one request is
    refused (-ERANGE) and the board's time does not move."""
    t0 = client.now()
    for ns in (60_000_000_001, 2**63, 2**64 - 1 - t0):
        with pytest.raises(VBoardError, match="more than one request may advance the board") as e:
            client.advance(ns)
        assert e.value.status == -errno.ERANGE
        assert client.now() == t0
    # lockstep: a host time jump that far is refused the same way, and the
    # next request re-takes the connection's epoch (no jump)
    client.hello(time_ns=1_000_000)
    t1 = client.board_time_ns
    with pytest.raises(VBoardError, match="the host time jump of 3600.000 s") as e:
        client.hello(time_ns=1_000_000 + 3600 * 10**9)
    assert e.value.status == -errno.ERANGE
    assert client.now() == t1
    client.hello(time_ns=5 * 10**12)
    assert client.board_time_ns == t1
    client.hello(time_ns=5 * 10**12 + 1000)
    assert client.board_time_ns == t1 + 1000


def test_clients_at_once_and_one_after_another(svst: VBoardProcess) -> None:
    a, b = svst.client(), svst.client()
    a.write(0x1100, 0x1)  # DDR port 0 bit 0
    assert b.read32(0x1100) == 0x1
    a.close()
    assert b.read32(0x1100) == 0x1
    b.close()
    for _ in range(3):
        with svst.client() as c:
            assert c.hello().firmware == "SVST8_4"


def _raw(path: str) -> socket.socket:
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(10)
    s.connect(path)
    return s


def _reply(s: socket.socket) -> tuple[int, int, int, bytes]:
    head = b""
    while len(head) < vboard.HEADER.size:
        chunk = s.recv(vboard.HEADER.size - len(head))
        if not chunk:
            raise ConnectionError("closed")
        head += chunk
    magic, rtype, status, length, seq, _t = vboard.HEADER.unpack(head)
    assert magic == vboard.REP_MAGIC
    data = b""
    while len(data) < length:
        data += s.recv(length - len(data))
    return rtype, status, seq, data


def _closed(s: socket.socket) -> bool:
    try:
        return s.recv(1) == b""
    except ConnectionResetError:
        return True


def test_bad_magic_gets_an_error_and_closes_only_that_connection(client: VBoardClient) -> None:
    s = _raw(client.path)
    s.sendall(struct.pack("<IHhIIQ", 0xDEADBEEF, vboard.HELLO, 0, 0, 7, 0))
    rtype, status, seq, msg = _reply(s)
    assert (status, seq) == (-71, 7)  # -EPROTO
    assert b"bad request magic 0xdeadbeef" in msg
    assert _closed(s)
    assert client.hello().firmware == "SVST8_4"


def test_oversize_length_is_refused_and_closes(client: VBoardClient) -> None:
    s = _raw(client.path)
    s.sendall(vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.WRITE, 0, vboard.MAX_PAYLOAD + 1, 3, 0))
    _t, status, _seq, msg = _reply(s)
    assert status == -22 and b"over the limit" in msg
    assert _closed(s)
    assert client.hello().state == vboard.STATE_CONFIGURED


@pytest.mark.parametrize(
    "rtype,payload,status,text",
    [
        (0x7F, b"", -22, "unknown request type 0x7f"),
        (vboard.PROBE, b"\0\0\0\0", -71, "want 8"),
        (vboard.READ, b"\0" * 12, -71, "not a list of 8-byte transfers"),
        (vboard.READ, struct.pack("<II", 0x102, 4), -22, "multiples of 4"),
        (vboard.READ, struct.pack("<II", 0x100, 6), -22, "multiples of 4"),
        (vboard.READ, struct.pack("<II", 0xFFFC, 8), -22, "outside the 64 KiB"),
        (vboard.WRITE, struct.pack("<II", 0x1000, 8) + b"\0" * 4, -71, "shorter than its transfer"),
        (vboard.WRITE, struct.pack("<II", 0x1001, 4) + b"\0" * 4, -22, "multiples of 4"),
        (vboard.WRITE, b"\0" * 5, -71, "ends inside a transfer header"),
        (vboard.TIME, struct.pack("<IIQ", 9, 0, 0), -22, "unknown operation 9"),
        (vboard.TIME, b"\0" * 8, -71, "want 16"),
        (vboard.CONFIG, b"\0" * 4, -71, "shorter than 8"),
        (vboard.CONFIG, struct.pack("<II", 7, 0), -22, "unknown operation 7"),
        (vboard.DRIVE, struct.pack("<II", 72, 1), -22, "does not exist"),
        (vboard.DRIVE, struct.pack("<II", 3, 5), -22, "mode 5"),
        (vboard.LOOP, struct.pack("<IIII", 3, 3, 0, 0), -22, "into itself"),
        (vboard.QUAD, b"\0" * 8, -71, "want 24"),
        (vboard.DUMP, b"\0\0", -71, "want u32 on"),
        (vboard.DUMP, struct.pack("<I", 1), -22, "needs a file path"),
        (vboard.EPP, b"", -95, "no EPP port"),
        (vboard.EPP_STALL, struct.pack("<I", 1), -95, "no EPP port"),
    ],
)
def test_malformed_requests_get_errors_and_the_connection_goes_on(
    client: VBoardClient, rtype: int, payload: bytes, status: int, text: str
) -> None:
    client.write(0x1100, 0x5)
    with pytest.raises(VBoardError) as e:
        client.call(rtype, payload)
    assert e.value.status == status
    assert text in e.value.message
    # Nothing was applied, and the same connection keeps working.
    assert client.read32(0x1100) == 0x5
    assert client.pin(3).ext == vboard.EXT_NONE


def test_pipelined_requests_are_answered_in_order(client: VBoardClient) -> None:
    s = _raw(client.path)
    n = 3000
    reqs = b"".join(
        vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.READ, 0, 8, seq, 0)
        + struct.pack("<II", 0x100, 4)
        for seq in range(1, n + 1)
    )
    # Send from a thread: the board's replies fill the socket while we send.
    import threading

    t = threading.Thread(target=s.sendall, args=(reqs,))
    t.start()
    for seq in range(1, n + 1):
        rtype, status, rseq, data = _reply(s)
        assert (rtype, status, rseq, data) == (vboard.READ, 0, seq, struct.pack("<I", 0x55AACAFE))
    t.join()
    s.close()


def test_client_disconnect_mid_request(client: VBoardClient) -> None:
    s = _raw(client.path)
    s.sendall(vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.WRITE, 0, 100, 1, 0) + b"\0" * 10)
    s.close()
    s = _raw(client.path)
    s.sendall(vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.READ, 0, 8, 1, 0)[:10])
    s.close()
    assert client.read32(0x100) == 0x55AACAFE


def test_client_that_vanishes_before_its_reply(client: VBoardClient) -> None:
    s = _raw(client.path)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    s.sendall(
        vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.READ, 0, 8, 1, 0)
        + struct.pack("<II", 0x400, 4096)
    )
    s.close()
    assert client.read32(0x100) == 0x55AACAFE


def test_sigterm_exits_cleanly_and_removes_the_socket(sockdir: Path) -> None:
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    with p.client() as c:
        c.hello()
        assert p.stop() == 0
    assert not (sockdir / "b.sock").exists()


def test_sigterm_ends_a_long_request(sockdir: Path) -> None:
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    s = _raw(p.socket_path)
    # 100 s of board time: minutes of wall time.
    s.sendall(
        vboard.HEADER.pack(vboard.REQ_MAGIC, vboard.TIME, 0, 16, 1, 0)
        + struct.pack("<IIQ", 0, 0, 10**11)
    )
    time.sleep(0.3)
    t0 = time.monotonic()
    assert p.stop(timeout=20) == 0
    assert time.monotonic() - t0 < 5
    s.close()
    assert not (sockdir / "b.sock").exists()


def test_stale_socket_file_is_replaced_but_a_live_one_is_not(sockdir: Path) -> None:
    path = sockdir / "b.sock"
    dead = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    dead.bind(str(path))
    dead.close()
    with VBoardProcess(path, "5i20", "SVST8_4"):
        r = subprocess.run(
            [str(vboard.vboard_binary()), "--socket", str(path), "--board", "5i20"],
            capture_output=True,
            text=True,
            timeout=30,
        )
        assert r.returncode == 1
        assert "in use by another running board" in r.stderr


@pytest.mark.parametrize(
    "args,text",
    [
        (["--board", "5i20"], "--socket and --board are required"),
        (["--socket", "S", "--board", "9x99"], "unknown board '9x99' (this vboard knows: "),
        (["--socket", "S", "--board", "5i20", "--firmware", "NOPE"], "firmware NOPE is not built"),
        (["--socket", "S", "--board", "5i20", "--loop", "1-2"], "bad loop '1-2'"),
        (["--socket", "S", "--board", "5i20", "--loop", "1:99"], "I/O pin 99 does not exist"),
        (["--socket", "S", "--board", "5i20", "--quad", "1:2"], "bad quadrature source"),
        (
            ["--socket", "S", "--board", "5i20", "--loop-file", "/nonexistent"],
            "cannot read loop file",
        ),
        (
            [
                "--socket",
                "S",
                "--board",
                "5i20",
                "--firmware",
                "SVST8_4",
                "--dump",
                "/nonexistent/x.vcd",
            ],
            "cannot open /nonexistent/x.vcd",
        ),
        (["--socket", "S", "--board", "5i20", "extra"], "unexpected argument 'extra'"),
        (["--socket", "S", "--board", "5i20", "--spin", "-1"], "bad --spin '-1'"),
    ],
)
def test_command_line_errors(sockdir: Path, args: list[str], text: str) -> None:
    args = [a.replace("S", str(sockdir / "s.sock")) if a == "S" else a for a in args]
    r = subprocess.run(
        [str(vboard.vboard_binary()), *args], capture_output=True, text=True, timeout=30
    )
    assert r.returncode != 0
    assert text in r.stderr
    assert not (sockdir / "s.sock").exists()


def test_spin_serves_like_the_default(sockdir: Path) -> None:
    with VBoardProcess(
        sockdir / "b.sock", "5i20", "SVST8_4", ["--spin", "100"]
    ) as p, p.client() as c:
        t0 = c.now()
        for _ in range(20):
            assert c.read32(0x100) == 0x55AACAFE
        # Spinning does not move lockstep time.
        time.sleep(0.01)
        assert c.now() - t0 == 20 * 2 * 30
        assert p.stop() == 0


def test_the_c_client_talks_to_the_board(svst: VBoardProcess) -> None:
    """bin/vboard-bench speaks through the project's C client (vbclient)."""
    bench = vboard.build_dir() / "bin" / "vboard-bench"
    assert bench.exists(), f"{bench} not built (run `make build`)"
    with svst.client() as c:
        # what a driver does at load: disable the dog, clear its power-up bite
        c.write(0x0C00, 0x80000000)
        c.write(0x0D00, 0)
    r = subprocess.run(
        [str(bench), svst.socket_path, "servo", "20", "100000"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert r.returncode == 0, r.stderr
    assert "per read+write (20 cycles, 100000 ns advance each)" in r.stdout
    with svst.client() as c:
        # 20 cycles of 100 us from the epoch the bench took: ~2 ms of board time.
        assert 2_000_000 <= c.now() < 2_100_000
        # Its watchdog pets (0xE00) never let the (disabled) watchdog bite.
        assert c.read32(0x0D00) & 1 == 0
    r = subprocess.run(
        [str(bench), svst.socket_path, "speed", "0.1"], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0 and "M ClockLow cycles/s" in r.stdout, r.stderr


def test_help_and_unknown_option() -> None:
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--help"], capture_output=True, text=True, timeout=30
    )
    assert r.returncode == 0 and r.stdout.startswith("usage: vboard --socket PATH --board NAME")
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--bogus"], capture_output=True, text=True, timeout=30
    )
    assert (
        r.returncode == 2 and "unrecognized option '--bogus'" in r.stderr and "usage:" in r.stderr
    )


def test_list(sockdir: Path) -> None:
    r = subprocess.run(
        [str(vboard.vboard_binary()), "--list"], capture_output=True, text=True, timeout=30
    )
    assert r.returncode == 0
    boards = {}
    for line in r.stdout.splitlines():
        head, _, fws = line.partition(": ")
        boards[head] = fws.split()
    assert {"SV12", "SV2ST2_PRB", "SVST8_4"} <= set(boards["5i20 (2s200pq208)"])
    assert boards["5i20 (2s200pq208)"] == sorted(boards["5i20 (2s200pq208)"])
    assert "7I76x2" in boards["5i25 (6slx9tqg144)"]


def test_log_option_reports_requests(sockdir: Path) -> None:
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--log"])
    with p.client() as c:
        c.hello()
        with pytest.raises(VBoardError):
            c.read(0x2, 1)
    with p.client() as c2:  # served after client 1's hang-up was seen
        c2.hello()
    assert p.stop() == 0
    assert "HELLO seq 1 len 0 -> 0" in p.stderr_text
    assert "READ seq 2 len 8 -> -22" in p.stderr_text
    assert "disconnected" in p.stderr_text


def test_signal_while_a_client_is_connected(sockdir: Path) -> None:
    p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    c = p.client()
    c.hello()
    os.kill(p.proc.pid, signal.SIGINT)
    assert p.proc.wait(timeout=10) == 0
    with pytest.raises((ConnectionError, OSError)):
        c.hello()
    c.close()


def test_one_epp_request_is_bounded(sockdir: Path) -> None:
    """An EPP request may ask for at most 2^20 bus cycles and 1 s of delays
    (-E2BIG otherwise, nothing executed): a single request cannot keep the
    board busy for minutes."""
    with VBoardProcess(sockdir / "p.sock", "pluto", "pluto_servo") as p, p.client() as c:
        t0 = c.now()
        for ops, what in [
            ([vboard.EppOp(4, n=(1 << 20) + 1)], "bus cycles"),
            (
                [vboard.EppOp(4, n=1 << 19), vboard.EppOp(4, n=1 << 19), vboard.EppOp(1)],
                "bus cycles",
            ),
            (
                [vboard.EppOp(10, val=600_000_000), vboard.EppOp(10, val=400_000_001)],
                "more than 1 s",
            ),
        ]:
            with pytest.raises(VBoardError, match=what) as e:
                c.epp(ops)
            assert e.value.status == -errno.E2BIG
            assert c.now() == t0  # nothing ran
        # within the bounds: executed (a 1 s delay is allowed)
        assert c.epp([vboard.EppOp(5), vboard.EppOp(10, val=1000)]) == b"\x00"
        assert c.now() >= t0 + 1000
