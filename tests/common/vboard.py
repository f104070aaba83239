# SPDX-License-Identifier: GPL-2.0-or-later
"""Python client of the virtual board (sim/verilator, docs/vboard-protocol.md).

Two parts:

* :class:`VBoardProcess` starts ``bin/vboard`` on a socket, waits for its
  ``vboard: ready on ...`` line and stops it (SIGTERM) - a context manager,
  fixture friendly.
* :class:`VBoardClient` is one connection speaking the binary protocol of
  ``sim/verilator/include/vboard/proto.h``, with a typed method per request.
  Board errors raise :class:`VBoardError` (status and message); the client
  stays usable afterwards unless the board closed the connection.

Import it from a test tree with ``sys.path.insert(0, <repo>/tests/common)``
then ``import vboard`` (``common`` is taken by tests/cocotb/common).
"""

from __future__ import annotations

import errno
import os
import select
import signal
import socket
import struct
import subprocess
import tempfile
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

PROTO_VERSION = 1
REQ_MAGIC = 0x51524256
REP_MAGIC = 0x50524256
MAX_PAYLOAD = 16 << 20
HEADER = struct.Struct("<IHhIIQ")  # magic, type, status, length, seq, time_ns

HELLO, READ, WRITE = 0x01, 0x10, 0x11
EPP, EPP_STALL = 0x20, 0x21
CONFIG, TIME = 0x30, 0x40
PROBE, DRIVE, QUAD, LOOP, PROBE_RESET = 0x50, 0x51, 0x52, 0x53, 0x54
DUMP = 0x60
PLANT = 0x70
SSERIAL = 0x71

BUS_LOCAL, BUS_EPP_HM2, BUS_EPP_PLUTO = 1, 2, 3
STATE_BLANK, STATE_CONFIGURED = 0, 1
CONFIG_STATUS, CONFIG_RESET, CONFIG_PROGRAM = 0, 1, 2
TIME_ADVANCE, TIME_LOCKSTEP, TIME_FREERUN = 0, 1, 2
DRIVE_RELEASE, DRIVE_LOW, DRIVE_HIGH = 0, 1, 2
EXT_NONE, EXT_LOW, EXT_HIGH, EXT_LOOP, EXT_QUAD, EXT_PLANT = 0, 1, 2, 3, 4, 5
NO_PIN = 0xFFFFFFFF
NEVER = 0xFFFFFFFFFFFFFFFF

# enum epp_op_kind (host/driver/include/hm2/epp_port.h), for VB_EPP ops.
_HELLO = struct.Struct("<8I16s32s32s")
_PIN = struct.Struct("<BBBBIII7Q")
_CONFIG_STATUS = struct.Struct("<II32s")


def _text(raw: bytes) -> str:
    return raw.split(b"\0", 1)[0].decode("utf-8", "replace")


def build_dir() -> Path:
    """$HM_BUILD or <repo>/build."""
    root = Path(__file__).resolve().parents[2]
    return Path(os.environ.get("HM_BUILD", str(root / "build")))


def vboard_binary() -> Path:
    return build_dir() / "bin" / "vboard"


def firmware_file(board: str, firmware: str) -> Path:
    """The .BIT file the build made for a virtual hm2 firmware."""
    return build_dir() / "lib" / "firmware" / "hm2" / board / f"{firmware}.BIT"


class VBoardError(Exception):
    """A reply with a negative status (``status`` is -errno)."""

    def __init__(self, status: int, message: str, request: int) -> None:
        super().__init__(
            f"vboard request 0x{request:02x}: {message} ({errno.errorcode.get(-status, status)})"
        )
        self.status = status
        self.message = message
        self.request = request


@dataclass(frozen=True)
class Hello:
    version: int
    bus: int
    state: int
    io_pins: int
    clock_low_hz: int
    clock_high_hz: int
    lockstep: bool
    board: str
    firmware: str
    fpga_part: str


@dataclass(frozen=True)
class Pin:
    level: int
    oe: int
    ext: int
    rising: int
    falling: int
    last_high_ns: int
    last_low_ns: int
    period_ns: int
    high_total_ns: int
    total_ns: int
    min_high_ns: int
    min_low_ns: int

    @property
    def duty(self) -> float:
        return self.high_total_ns / self.total_ns if self.total_ns else 0.0


@dataclass(frozen=True)
class ConfigStatus:
    done: int
    init: int
    firmware: str


@dataclass(frozen=True)
class EppOp:
    """One VB_EPP op: kind is enum epp_op_kind; data for DATA_WRITE."""

    kind: int
    n: int = 0
    val: int = 0
    data: bytes = b""

    def encode(self) -> bytes:
        return struct.pack("<B3xII", self.kind, self.n, self.val) + self.data


class VBoardClient:
    """One connection to a vboard socket."""

    def __init__(self, path: str | os.PathLike[str], timeout: float = 10.0) -> None:
        self.path = str(path)
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.settimeout(timeout)
        self.sock.connect(self.path)
        self.seq = 0
        self.board_time_ns = 0

    # -- transport ------------------------------------------------------
    def close(self) -> None:
        self.sock.close()

    def __enter__(self) -> VBoardClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def send_raw(self, data: bytes) -> None:
        self.sock.sendall(data)

    def recv_reply(self) -> tuple[int, int, int, int, bytes]:
        """(type, status, seq, time_ns, payload) of the next reply."""
        head = self._recv_exact(HEADER.size)
        magic, rtype, status, length, seq, t = HEADER.unpack(head)
        if magic != REP_MAGIC:
            raise ConnectionError(f"bad reply magic 0x{magic:08x}")
        payload = self._recv_exact(length)
        self.board_time_ns = t
        return rtype, status, seq, t, payload

    def _recv_exact(self, n: int) -> bytes:
        buf = bytearray()
        while len(buf) < n:
            chunk = self.sock.recv(n - len(buf))
            if not chunk:
                raise ConnectionError("vboard closed the connection")
            buf += chunk
        return bytes(buf)

    def call(self, rtype: int, payload: bytes = b"", time_ns: int = 0) -> bytes:
        """Send one request and return the reply payload; VBoardError on status < 0."""
        self.seq = (self.seq + 1) & 0xFFFFFFFF
        self.sock.sendall(
            HEADER.pack(REQ_MAGIC, rtype, 0, len(payload), self.seq, time_ns) + payload
        )
        got_type, status, seq, _t, data = self.recv_reply()
        if got_type != rtype or seq != self.seq:
            raise ConnectionError(
                f"reply type 0x{got_type:02x} seq {seq} for request 0x{rtype:02x} seq {self.seq}"
            )
        if status < 0:
            raise VBoardError(status, data.decode("utf-8", "replace"), rtype)
        return data

    # -- requests ---------------------------------------------------------
    def hello(self, time_ns: int = 0) -> Hello:
        f = _HELLO.unpack(self.call(HELLO, b"", time_ns))
        return Hello(
            f[0], f[1], f[2], f[3], f[4], f[5], bool(f[6]), _text(f[8]), _text(f[9]), _text(f[10])
        )

    def read_bursts(self, xfers: Sequence[tuple[int, int]], time_ns: int = 0) -> bytes:
        """Read (addr, size-in-bytes) transfers; their data concatenated."""
        payload = b"".join(struct.pack("<II", a, s) for a, s in xfers)
        return self.call(READ, payload, time_ns)

    def read(self, addr: int, count: int = 1, time_ns: int = 0) -> list[int]:
        """`count` 32-bit words from hm2 address `addr`."""
        data = self.read_bursts([(addr, 4 * count)], time_ns)
        return list(struct.unpack(f"<{count}I", data))

    def read32(self, addr: int, time_ns: int = 0) -> int:
        return self.read(addr, 1, time_ns)[0]

    def write_bursts(self, xfers: Sequence[tuple[int, Sequence[int]]], time_ns: int = 0) -> None:
        """Write (addr, [words]) transfers."""
        payload = b"".join(
            struct.pack("<II", a, 4 * len(w)) + struct.pack(f"<{len(w)}I", *w) for a, w in xfers
        )
        self.call(WRITE, payload, time_ns)

    def write(self, addr: int, words: Sequence[int] | int, time_ns: int = 0) -> None:
        ws = [words] if isinstance(words, int) else list(words)
        self.write_bursts([(addr, ws)], time_ns)

    def config(self, op: int, bitstream: bytes = b"", time_ns: int = 0) -> ConfigStatus:
        done, init, fw = _CONFIG_STATUS.unpack(
            self.call(CONFIG, struct.pack("<II", op, 0) + bitstream, time_ns)
        )
        return ConfigStatus(done, init, _text(fw))

    def program(self, bitstream: bytes) -> ConfigStatus:
        """VB_CONFIG_PROGRAM with a .BIT file's 'e' chunk (see bit_payload)."""
        return self.config(CONFIG_PROGRAM, bitstream)

    def advance(self, ns: int) -> int:
        """Run the clocks ns more; returns the board time."""
        self.call(TIME, struct.pack("<IIQ", TIME_ADVANCE, 0, ns))
        return self.board_time_ns

    def lockstep(self) -> None:
        self.call(TIME, struct.pack("<IIQ", TIME_LOCKSTEP, 0, 0))

    def freerun(self) -> None:
        self.call(TIME, struct.pack("<IIQ", TIME_FREERUN, 0, 0))

    def now(self) -> int:
        """Board time (a HELLO without advance)."""
        self.hello()
        return self.board_time_ns

    def probe(self, first: int, count: int = 1, time_ns: int = 0) -> list[Pin]:
        data = self.call(PROBE, struct.pack("<II", first, count), time_ns)
        out = []
        for i in range(len(data) // _PIN.size):
            f = _PIN.unpack_from(data, i * _PIN.size)
            out.append(Pin(*f[0:3], *f[4:6], *f[7:]))  # skip the reserved fields
        return out

    def pin(self, pin: int) -> Pin:
        return self.probe(pin, 1)[0]

    def probe_reset(self, first: int, count: int = 1) -> None:
        self.call(PROBE_RESET, struct.pack("<II", first, count))

    def drive(self, pins: Iterable[tuple[int, int]] | int, mode: int | None = None) -> None:
        """drive(pin, mode) or drive([(pin, mode), ...])."""
        items = (
            [(pins, mode if mode is not None else DRIVE_RELEASE)]
            if isinstance(pins, int)
            else list(pins)
        )
        self.call(DRIVE, b"".join(struct.pack("<II", p, m) for p, m in items))

    def quad(
        self, a: int, b: int, counts_per_s: float, index: int = NO_PIN, index_every: int = 0
    ) -> None:
        self.call(QUAD, struct.pack("<IIIId", a, b, index, index_every, counts_per_s))

    def loop(self, loops: Iterable[tuple[int, int] | tuple[int, int, bool]]) -> None:
        """[(from, to[, invert]), ...]; to = NO_PIN removes the loops of `from`."""
        payload = b""
        for item in loops:
            inv = bool(item[2]) if len(item) > 2 else False  # type: ignore[misc]
            payload += struct.pack("<IIII", item[0], item[1], int(inv), 0)
        self.call(LOOP, payload)

    def dump(self, path: str | os.PathLike[str] | None) -> None:
        """Start a waveform dump into path (.vcd), or stop it (None)."""
        if path is None:
            self.call(DUMP, struct.pack("<I", 0))
        else:
            self.call(DUMP, struct.pack("<I", 1) + str(path).encode())

    def epp(self, ops: Sequence[EppOp], time_ns: int = 0) -> bytes:
        return self.call(EPP, b"".join(op.encode() for op in ops), time_ns)

    def epp_stall(self, on: bool) -> None:
        self.call(EPP_STALL, struct.pack("<I", int(on)))

    def plant(self, command: str) -> str:
        """A VB_PLANT text command ("status", "trace PATH", "trace off"): its JSON reply."""
        return self.call(PLANT, command.encode()).decode()


def bit_payload(bit: bytes) -> bytes:
    """The 'e' chunk of a .BIT file (what VB_CONFIG_PROGRAM takes)."""
    pos = 13
    while pos < len(bit):
        tag = bit[pos : pos + 1]
        pos += 1
        if tag in (b"a", b"b", b"c", b"d"):
            n = struct.unpack(">H", bit[pos : pos + 2])[0]
            pos += 2 + n
        elif tag == b"e":
            n = struct.unpack(">I", bit[pos : pos + 4])[0]
            return bit[pos + 4 : pos + 4 + n]
        else:
            break
    raise ValueError("not a .BIT file with an 'e' chunk")


class VBoardProcess:
    """A running ``vboard``; ``with VBoardProcess(tmp/'vb.sock', '5i20', 'SVST8_4') as vb: ...``."""

    def __init__(
        self,
        socket_path: str | os.PathLike[str],
        board: str,
        firmware: str | None = None,
        args: Sequence[str] = (),
        binary: Path | None = None,
        timeout: float = 30.0,
        cwd: str | os.PathLike[str] | None = None,
    ) -> None:
        self.socket_path = os.path.abspath(str(socket_path))
        cmd = [str(binary or vboard_binary()), "--socket", self.socket_path, "--board", board]
        if firmware:
            cmd += ["--firmware", firmware]
        cmd += list(args)
        self.cmd = cmd
        # cwd: where relative paths (dumps) land; default: the socket's directory.
        workdir = cwd if cwd is not None else os.path.dirname(os.path.abspath(self.socket_path))
        # stderr goes to a file, not a pipe: with --log the board writes a
        # line per request and would block on a full pipe nobody reads.
        self._err = tempfile.TemporaryFile(mode="w+")
        self.stderr_text = ""
        self.proc = subprocess.Popen(
            cmd, stdout=subprocess.PIPE, stderr=self._err, text=True, cwd=workdir
        )
        self.ready_line = self._wait_ready(timeout)

    def _wait_ready(self, timeout: float) -> str:
        assert self.proc.stdout is not None
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            r, _, _ = select.select([self.proc.stdout], [], [], 0.1)
            if r:
                line = self.proc.stdout.readline()
                if line.startswith("vboard: ready on "):
                    return line.strip()
                if line == "" and self.proc.poll() is not None:
                    break
            elif self.proc.poll() is not None:
                break
        self.kill()
        raise RuntimeError(
            f"vboard did not become ready ({' '.join(self.cmd)}): {self.stderr_text.strip()}"
        )

    def stderr_so_far(self) -> str:
        """What the board wrote to stderr until now."""
        self._err.flush()
        self._err.seek(0)
        text = self._err.read()
        self._err.seek(0, os.SEEK_END)
        return text

    def client(self, timeout: float = 10.0) -> VBoardClient:
        return VBoardClient(self.socket_path, timeout)

    def stop(self, timeout: float = 10.0) -> int:
        """SIGTERM, wait, return the exit status; stderr ends up in stderr_text."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            self.proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise
        self.stderr_text = self.stderr_so_far()
        return self.proc.returncode

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.communicate()
        self.stderr_text = self.stderr_so_far()

    def __enter__(self) -> VBoardProcess:
        return self

    def __exit__(
        self, et: type[BaseException] | None, ev: BaseException | None, tb: TracebackType | None
    ) -> None:
        if self.proc.poll() is None:
            self.stop()
