# SPDX-License-Identifier: GPL-2.0-or-later
"""ctypes access to HAL through libhalview.so (tools/halview/native/halview.h).

Names, values and halcmd's set rules for the viewers, and the scope_rt
control/sample blocks for halscope.  Errors raise :class:`HalError` with a
one-line reason in halcmd's wording.
"""

from __future__ import annotations

import ctypes
import errno
import os
from dataclasses import dataclass
from pathlib import Path

COMP, PIN, PARAM, SIG, FUNCT, THREAD = range(6)
KIND_NAMES = {
    COMP: "comp",
    PIN: "pin",
    PARAM: "param",
    SIG: "sig",
    FUNCT: "funct",
    THREAD: "thread",
}
KIND_BY_NAME = {
    "comp": COMP,
    "pin": PIN,
    "param": PARAM,
    "parameter": PARAM,
    "sig": SIG,
    "signal": SIG,
    "funct": FUNCT,
    "thread": THREAD,
}

# scope_shm.h
MODE_NORMAL, MODE_AUTO, MODE_SINGLE, MODE_ROLL = range(4)
MODES = {"normal": MODE_NORMAL, "auto": MODE_AUTO, "single": MODE_SINGLE, "roll": MODE_ROLL}
ST_IDLE, ST_ARMED, ST_TRIGGERED, ST_DONE, ST_ROLLING, ST_ERROR = range(6)
STATE_NAMES = ["idle", "armed", "triggered", "done", "rolling", "error"]
RISING, FALLING = 0, 1
MAX_CHAN = 16

# hal.h types
HAL_BIT, HAL_FLOAT, HAL_S32, HAL_U32, HAL_S64, HAL_U64 = 1, 2, 3, 4, 6, 7
TYPE_NAMES = {HAL_BIT: "bit", HAL_FLOAT: "float", HAL_S32: "s32", HAL_U32: "u32"}
TYPE_NAMES.update({HAL_S64: "s64", HAL_U64: "u64"})
TYPE_BY_NAME = {v: k for k, v in TYPE_NAMES.items()}


class HalError(Exception):
    """A HAL operation failed; str() is the reason."""

    def __init__(self, message: str, code: int = -errno.EINVAL) -> None:
        super().__init__(message)
        self.code = code


class _ScopeStatus(ctypes.Structure):
    _fields_ = [
        (n, ctypes.c_int64)
        for n in (
            "state",
            "error",
            "capture_seq",
            "forced",
            "nchan",
            "capacity",
            "widx",
            "trig_idx",
            "start_idx",
            "t_first",
            "t_trig",
            "interval",
            "lost",
            "calls",
            "num_samples",
            "pending",
            "done_calls",
        )
    ]


def _find_lib() -> Path:
    env = os.environ.get("HALVIEW_LIB")
    if env:
        return Path(env)
    build = Path(os.environ.get("HM_BUILD", Path(__file__).resolve().parents[3] / "build"))
    return build / "lib" / "libhalview.so"


_lib: ctypes.CDLL | None = None


def lib() -> ctypes.CDLL:
    """The loaded helper library (loaded once per process)."""
    global _lib
    if _lib is None:
        path = _find_lib()
        if not path.exists():
            raise HalError(f"{path} is missing: build the tree first (make)", -errno.ENOENT)
        L = ctypes.CDLL(str(path))
        c_char_p, c_size_t, c_int = ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int
        L.hv_attach.restype = c_int
        L.hv_session_exists.restype = c_int
        L.hv_simclock.restype = c_int
        L.hv_time.restype = ctypes.c_longlong
        L.hv_list.argtypes = [c_int, c_char_p, c_char_p, c_size_t]
        L.hv_list.restype = ctypes.c_long
        L.hv_info.argtypes = [c_int, c_char_p, c_char_p, c_size_t]
        L.hv_info.restype = ctypes.c_long
        L.hv_get.argtypes = [c_int, c_char_p, c_char_p, c_size_t, c_char_p, c_size_t]
        L.hv_set.argtypes = [c_int, c_char_p, c_char_p, c_char_p, c_size_t]
        L.hv_get_many.argtypes = [
            c_int,
            ctypes.POINTER(c_int),
            c_char_p,
            c_char_p,
            c_size_t,
        ]
        L.hv_get_many.restype = ctypes.c_long
        L.hv_scope_open.argtypes = [c_char_p, c_size_t]
        L.hv_scope_open.restype = ctypes.c_void_p
        L.hv_scope_close.argtypes = [ctypes.c_void_p]
        L.hv_scope_close.restype = None
        L.hv_scope_status.argtypes = [ctypes.c_void_p, ctypes.POINTER(_ScopeStatus)]
        L.hv_scope_set_chan.argtypes = [
            ctypes.c_void_p,
            c_int,
            c_int,
            c_char_p,
            c_char_p,
            c_size_t,
        ]
        L.hv_scope_arm.argtypes = [
            ctypes.c_void_p,
            c_int,
            c_int,
            ctypes.c_uint64,
            ctypes.c_uint64,
            c_int,
            c_int,
            ctypes.c_double,
            c_int,
            c_int,
            c_char_p,
            c_size_t,
        ]
        L.hv_scope_stop.argtypes = [ctypes.c_void_p]
        L.hv_scope_read.argtypes = [
            ctypes.c_void_p,
            ctypes.c_uint64,
            ctypes.c_uint64,
            ctypes.c_void_p,
        ]
        L.hv_scope_read.restype = ctypes.c_int64
        L.hv_scope_consume.argtypes = [ctypes.c_void_p, ctypes.c_uint64]
        L.hv_scope_consume.restype = None
        _lib = L
    return _lib


def _enc(s: str) -> bytes:
    return s.encode()


def require_session() -> None:
    """Attach to the session's HAL; HalError when none is running."""
    L = lib()
    if not L.hv_session_exists():
        inst = os.environ.get("HAL_INSTANCE", "0") or "0"
        raise HalError(
            f"no HAL session is running (HAL_INSTANCE={inst}); start one with halrun",
            -errno.ENOENT,
        )
    r = L.hv_attach()
    if r < 0:
        raise HalError(f"cannot attach to HAL: {os.strerror(-r)}", r)


def simclock() -> bool:
    return bool(lib().hv_simclock())


def now_ns() -> int:
    """The session's time: virtual under the simulated clock, else monotonic."""
    return int(lib().hv_time())


def _grow(call: "ctypes._FuncPointer", *args: object) -> str:
    size = 65536
    while True:
        buf = ctypes.create_string_buffer(size)
        n = call(*args, buf, size)
        if n < 0:
            raise HalError(os.strerror(-n), n)
        if n < size:
            return buf.value.decode()
        size = n + 1


def list_names(kind: int, pattern: str = "") -> list[str]:
    """Names of a kind in halcmd's show order (pattern: prefix or glob)."""
    text = _grow(lib().hv_list, kind, _enc(pattern))
    return text.splitlines()


def info(kind: int, name: str) -> list[str] | None:
    """Tab-separated facts about one object (halview.h), None when gone."""
    buf = ctypes.create_string_buffer(65536)
    n = lib().hv_info(kind, _enc(name), buf, len(buf))
    if n == -errno.ENOENT:
        return None
    if n < 0:
        raise HalError(f"{KIND_NAMES.get(kind, '?')} '{name}': {os.strerror(-n)}", n)
    return buf.value.decode().split("\t")


def get(kind: int, name: str) -> str:
    """getp/gets: the value text as halcmd prints it."""
    buf = ctypes.create_string_buffer(128)
    err = ctypes.create_string_buffer(256)
    r = lib().hv_get(kind, _enc(name), buf, len(buf), err, len(err))
    if r < 0:
        raise HalError(err.value.decode() or os.strerror(-r), r)
    return buf.value.decode()


def set_value(kind: int, name: str, value: str) -> None:
    """setp/sets with halcmd's rules; HalError with halcmd's reason."""
    err = ctypes.create_string_buffer(256)
    r = lib().hv_set(kind, _enc(name), _enc(value), err, len(err))
    if r < 0:
        raise HalError(err.value.decode() or os.strerror(-r), r)


def get_many(items: list[tuple[int, str]]) -> list[str | None]:
    """Values of several objects in one call; None for an object that is gone."""
    if not items:
        return []
    kinds = (ctypes.c_int * len(items))(*[k for k, _ in items])
    names = "\n".join(n for _, n in items).encode()
    text = _grow(lib().hv_get_many, len(items), kinds, names)
    out: list[str | None] = []
    for v in text.split("\n")[: len(items)]:
        out.append(None if v == "?" else v)
    return out


def find_kind(name: str) -> int:
    """Whether a name is a pin, a signal or a parameter (in that order)."""
    for kind in (PIN, SIG, PARAM):
        if info(kind, name) is not None:
            return kind
    raise HalError(f"no pin, signal or parameter named '{name}'", -errno.ENOENT)


@dataclass
class ScopeStatus:
    state: int
    error: int
    capture_seq: int
    forced: int
    nchan: int
    capacity: int
    widx: int
    trig_idx: int
    start_idx: int
    t_first: int
    t_trig: int
    interval: int
    lost: int
    calls: int
    num_samples: int
    pending: int
    done_calls: int

    @property
    def state_name(self) -> str:
        return STATE_NAMES[self.state] if 0 <= self.state < len(STATE_NAMES) else "?"


class ScopeHandle:
    """The attached scope_rt (close() when done)."""

    def __init__(self) -> None:
        err = ctypes.create_string_buffer(256)
        h = lib().hv_scope_open(err, len(err))
        if not h:
            raise HalError(err.value.decode(), -errno.ENOENT)
        self._h: int | None = h

    def close(self) -> None:
        if self._h:
            lib().hv_scope_close(self._h)
            self._h = None

    def __enter__(self) -> "ScopeHandle":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _handle(self) -> int:
        if not self._h:
            raise HalError("the scope handle is closed")
        return self._h

    def status(self) -> ScopeStatus:
        st = _ScopeStatus()
        r = lib().hv_scope_status(self._handle(), ctypes.byref(st))
        if r < 0:
            raise HalError("scope_rt was unloaded", r)
        return ScopeStatus(*[getattr(st, f) for f, _ in _ScopeStatus._fields_])

    def set_chan(self, index: int, kind: int, name: str) -> int:
        """Resolve channel index (0-based); returns its HAL type."""
        err = ctypes.create_string_buffer(256)
        r = lib().hv_scope_set_chan(self._handle(), index, kind, _enc(name), err, len(err))
        if r < 0:
            raise HalError(err.value.decode(), r)
        return int(r)

    def arm(
        self,
        nchan: int,
        mult: int,
        rec_len: int,
        pretrig: int,
        trig_chan: int,
        edge: int,
        level: float,
        mode: int,
        reader_wait: bool,
    ) -> None:
        err = ctypes.create_string_buffer(256)
        r = lib().hv_scope_arm(
            self._handle(),
            nchan,
            mult,
            rec_len,
            pretrig,
            trig_chan,
            edge,
            level,
            mode,
            int(reader_wait),
            err,
            len(err),
        )
        if r < 0:
            raise HalError(err.value.decode(), r)

    def stop(self) -> None:
        lib().hv_scope_stop(self._handle())

    def read(self, first: int, count: int, nchan: int) -> tuple[bytes, int]:
        """Raw records [first, first+count) and the first intact index."""
        buf = ctypes.create_string_buffer(max(1, count * nchan * 8))
        r = lib().hv_scope_read(self._handle(), first, count, buf)
        if r < 0:
            raise HalError("scope_rt was unloaded", int(r))
        return buf.raw[: count * nchan * 8], int(r)

    def consume(self, idx: int) -> None:
        lib().hv_scope_consume(self._handle(), idx)
