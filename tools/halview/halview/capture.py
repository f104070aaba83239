# SPDX-License-Identifier: GPL-2.0-or-later
"""Taking captures with scope_rt: configuration, arming, waiting, decoding.

A :class:`ScopeConfig` says what to capture; :func:`capture_triggered` and
:func:`capture_roll` run it on an attached :class:`~halview.halapi.ScopeHandle`
and return a :class:`Capture` (decoded columns plus the time base).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from . import halapi
from .halapi import HalError


@dataclass
class Channel:
    name: str
    kind: int = -1  # halapi.PIN / SIG / PARAM; -1: find out
    scale: float = 1.0  # display only (plots, page)
    offset: float = 0.0
    type: int = 0  # HAL type, filled when resolved

    @property
    def label(self) -> str:
        return self.name


@dataclass
class ScopeConfig:
    channels: list[Channel] = field(default_factory=list)
    thread: str = ""
    mult: int = 1
    samples: int = 1000  # record length
    mode: str = "normal"
    trigger: str = ""  # channel name, "" = none (trigger at once)
    edge: str = "rising"
    level: float = 0.5
    position: float = 50.0  # % of the record before the trigger

    def trigger_index(self) -> int:
        if not self.trigger:
            return -1
        for i, c in enumerate(self.channels):
            if c.name == self.trigger:
                return i
        raise HalError(f"the trigger '{self.trigger}' is not one of the channels")

    def pretrig(self) -> int:
        """Samples before the trigger; none without a trigger channel (the
        capture starts at once)."""
        if not 0.0 <= self.position <= 100.0:
            raise HalError(f"trigger position {self.position}%: must be 0 to 100")
        if not self.trigger:
            return 0
        return min(self.samples - 1, int(round(self.samples * self.position / 100.0)))


@dataclass
class Capture:
    channels: list[Channel]
    interval: int  # ns between records
    t0: int  # session time of record 0 (ns)
    columns: list[np.ndarray]
    trigger: int | None = None  # record index of the trigger
    forced: bool = False
    lost: int = 0
    mode: str = "normal"
    indices: np.ndarray | None = None  # record numbers when some were lost (roll)
    board_offset: int | None = None  # a virtual board's time minus HAL's (ns)

    @property
    def length(self) -> int:
        return len(self.columns[0]) if self.columns else 0

    def index(self) -> np.ndarray:
        """Record number of every row (0 = t0)."""
        if self.indices is not None:
            return self.indices
        return np.arange(self.length, dtype=np.int64)

    def times(self) -> np.ndarray:
        """Session time (ns) of every record."""
        return self.t0 + self.index() * self.interval


def decode(raw: bytes, nchan: int, types: list[int]) -> list[np.ndarray]:
    """Raw hal_data_u records -> one numpy column per channel."""
    words = np.frombuffer(raw, dtype="<u8").reshape(-1, nchan)
    cols: list[np.ndarray] = []
    for i, t in enumerate(types):
        col = np.ascontiguousarray(words[:, i])
        if t == halapi.HAL_FLOAT:
            cols.append(col.view("<f8").copy())
        elif t == halapi.HAL_BIT:
            cols.append((col & 0xFF != 0).astype(np.uint8))
        elif t == halapi.HAL_S32:
            cols.append(col.astype(np.uint32).view(np.int32).astype(np.int64))
        elif t == halapi.HAL_U32:
            cols.append(col.astype(np.uint32).astype(np.int64))
        elif t == halapi.HAL_S64:
            cols.append(col.view("<i8").copy())
        else:
            cols.append(col.copy())
    return cols


def parse_channel(spec: str) -> Channel:
    """NAME, pin:NAME, sig:NAME or param:NAME."""
    kind = -1
    name = spec.strip()
    if ":" in name:
        prefix, rest = name.split(":", 1)
        if prefix in ("pin", "sig", "signal", "param", "parameter"):
            kind = halapi.KIND_BY_NAME[prefix]
            name = rest
    if not name:
        raise HalError(f"empty channel name in '{spec}'")
    return Channel(name=name, kind=kind)


def resolve(scope: halapi.ScopeHandle, cfg: ScopeConfig) -> None:
    """Look every channel up in HAL and give it to the scope (all or none)."""
    if not cfg.channels:
        raise HalError("no channels: name at least one (--channels)")
    if len(cfg.channels) > halapi.MAX_CHAN:
        raise HalError(f"{len(cfg.channels)} channels: the scope has {halapi.MAX_CHAN}")
    for i, ch in enumerate(cfg.channels):
        if ch.kind < 0:
            ch.kind = halapi.find_kind(ch.name)
        ch.type = scope.set_chan(i, ch.kind, ch.name)


def arm(scope: halapi.ScopeHandle, cfg: ScopeConfig, reader_wait: bool) -> None:
    if cfg.mode not in halapi.MODES:
        raise HalError(f"mode '{cfg.mode}': one of normal, auto, single, roll")
    if cfg.edge not in ("rising", "falling"):
        raise HalError(f"edge '{cfg.edge}': rising or falling")
    if cfg.mult < 1:
        raise HalError(f"sample every {cfg.mult} periods: must be 1 or more")
    if cfg.samples < 1:
        raise HalError(f"record length {cfg.samples}: must be 1 or more")
    scope.arm(
        nchan=len(cfg.channels),
        mult=cfg.mult,
        rec_len=cfg.samples,
        pretrig=cfg.pretrig(),
        trig_chan=cfg.trigger_index(),
        edge=halapi.RISING if cfg.edge == "rising" else halapi.FALLING,
        level=cfg.level,
        mode=halapi.MODES[cfg.mode],
        reader_wait=reader_wait,
    )


class Waiter:
    """Polls the scope with a wall-clock timeout and a clear reason."""

    def __init__(self, scope: halapi.ScopeHandle, timeout: float | None) -> None:
        self.scope = scope
        self.deadline = None if timeout is None else time.monotonic() + timeout
        self.timeout = timeout
        self.calls0 = scope.status().calls

    def poll(self, what: str, stop: Callable[[], bool] | None = None) -> halapi.ScopeStatus:
        time.sleep(0.002)
        st = self.scope.status()
        if st.state == halapi.ST_ERROR:
            raise HalError(f"scope_rt refused the configuration (error {st.error})")
        if stop is not None and stop():
            raise KeyboardInterrupt
        if self.deadline is not None and time.monotonic() > self.deadline:
            if st.calls == self.calls0:
                raise HalError(
                    f"no {what} within {self.timeout:g} s: scope.sample was not called "
                    "(is it in a thread, and are the threads started?)"
                )
            raise HalError(f"no {what} within {self.timeout:g} s")
        return st


def capture_triggered(
    scope: halapi.ScopeHandle,
    cfg: ScopeConfig,
    timeout: float | None = 60.0,
    on_armed: Callable[[], None] | None = None,
    stop: Callable[[], bool] | None = None,
    on_done: Callable[[Capture], None] | None = None,
) -> Capture:
    """One triggered capture (normal, single or auto).  on_done(capture)
    runs before the scope is re-armed; on the simulated clock HAL is then
    held inside scope.sample (its next call), so the session's time and a
    lockstep virtual board's time stand still."""
    resolve(scope, cfg)
    seq0 = scope.status().capture_seq
    arm(scope, cfg, reader_wait=halapi.simclock())
    if on_armed is not None:
        on_armed()
    w = Waiter(scope, timeout)
    while True:
        st = w.poll("trigger", stop)
        if st.capture_seq != seq0 and st.state == halapi.ST_DONE and not st.pending:
            break
    raw, _ = scope.read(st.start_idx, cfg.samples, len(cfg.channels))
    cols = decode(raw, len(cfg.channels), [c.type for c in cfg.channels])
    trig = st.trig_idx - st.start_idx
    cap = Capture(
        channels=list(cfg.channels),
        interval=st.interval,
        t0=st.t_trig - trig * st.interval,
        columns=cols,
        trigger=trig if cfg.trigger else None,
        forced=bool(st.forced),
        mode=cfg.mode,
    )
    if on_done is not None:
        if halapi.simclock():
            while st.calls <= st.done_calls:  # scope.sample's next call: it waits there
                st = w.poll("next period", stop)
        on_done(cap)
    return cap


def capture_roll(
    scope: halapi.ScopeHandle,
    cfg: ScopeConfig,
    records: int | None,
    timeout: float | None = 60.0,
    on_armed: Callable[[], None] | None = None,
    stop: Callable[[], bool] | None = None,
    on_chunk: Callable[[Capture], None] | None = None,
    keep: bool = True,
) -> Capture:
    """Sample continuously until `records` records (None: until stop()).
    keep=False hands the records to on_chunk only (a live view)."""
    resolve(scope, cfg)
    nchan = len(cfg.channels)
    types = [c.type for c in cfg.channels]
    reader_wait = halapi.simclock()
    arm(scope, cfg, reader_wait=reader_wait)
    if on_armed is not None:
        on_armed()
    w = Waiter(scope, timeout)
    chunks: list[list[np.ndarray]] = []
    idx: list[np.ndarray] = []
    got = lost = rd = 0
    st = scope.status()
    while records is None or got + lost < records:
        try:
            st = w.poll("samples", stop)
        except KeyboardInterrupt:
            break
        if st.state != halapi.ST_ROLLING or st.pending:
            continue
        avail = st.widx
        if records is not None:
            avail = min(avail, records)
        if avail <= rd:
            continue
        raw, valid = scope.read(rd, avail - rd, nchan)
        skip = valid - rd
        lost += skip
        cols = decode(raw[skip * nchan * 8 :], nchan, types)
        if cols and len(cols[0]):
            if keep:
                chunks.append(cols)
                idx.append(np.arange(valid, valid + len(cols[0]), dtype=np.int64))
            got += len(cols[0])
            if on_chunk is not None:
                on_chunk(
                    Capture(list(cfg.channels), st.interval, st.t_first + valid * st.interval, cols)
                )
        rd = avail
        scope.consume(rd)
        if w.deadline is not None:
            w.deadline = time.monotonic() + (w.timeout or 0)
    scope.stop()
    columns = [
        np.concatenate([c[i] for c in chunks]) if chunks else np.array([]) for i in range(nchan)
    ]
    return Capture(
        channels=list(cfg.channels),
        interval=st.interval,
        t0=st.t_first,
        columns=columns,
        lost=lost,
        mode="roll",
        indices=np.concatenate(idx) if lost and idx else None,
    )
