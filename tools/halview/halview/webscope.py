# SPDX-License-Identifier: GPL-2.0-or-later
"""The web page's scope: one scope_rt, captures taken in a background
thread and handed to the server as JSON-ready dictionaries."""

from __future__ import annotations

import threading
import time
from typing import Callable

import numpy as np

from . import halapi, scopectl, setupfile
from .capture import Capture, ScopeConfig, capture_roll, capture_triggered, parse_channel
from .halapi import HalError


def capture_json(cap: Capture, cfg: ScopeConfig, chunk: bool = False) -> dict[str, object]:
    cols = []
    for col in cap.columns:
        a = np.asarray(col, dtype=np.float64)
        cols.append([None if not np.isfinite(v) else float(v) for v in a])
    return {
        "type": "scope_chunk" if chunk else "scope",
        "names": [c.name for c in cap.channels],
        "types": [halapi.TYPE_NAMES.get(c.type, "?") for c in cap.channels],
        "scales": [c.scale for c in cap.channels],
        "offsets": [c.offset for c in cap.channels],
        "interval": cap.interval,
        "t0": cap.t0,
        "trigger": cap.trigger,
        "forced": cap.forced,
        "lost": cap.lost,
        "index": [int(i) for i in cap.index()],
        "columns": cols,
        "mode": cfg.mode,
        "thread": cfg.thread,
    }


def merge(caps: list[Capture]) -> Capture:
    """Consecutive roll chunks as one (their record numbers kept)."""
    first = caps[0]
    index = np.concatenate([c.index() + (c.t0 - first.t0) // max(1, c.interval) for c in caps])
    cols = [np.concatenate([c.columns[i] for c in caps]) for i in range(len(first.columns))]
    return Capture(first.channels, first.interval, first.t0, cols, indices=index, mode="roll")


def config_from_json(d: dict[str, object]) -> ScopeConfig:
    cfg = ScopeConfig()
    chans = d.get("channels", [])
    if not isinstance(chans, list):
        raise HalError("channels: a list of names")
    for c in chans:
        if isinstance(c, dict):
            ch = parse_channel(str(c.get("name", "")))
            ch.scale = float(c.get("scale", 1.0))  # type: ignore[arg-type]
            ch.offset = float(c.get("offset", 0.0))  # type: ignore[arg-type]
        else:
            ch = parse_channel(str(c))
        cfg.channels.append(ch)
    try:
        cfg.thread = str(d.get("thread", ""))
        cfg.mult = int(d.get("mult", 1))  # type: ignore[call-overload]
        cfg.samples = int(d.get("samples", 1000))  # type: ignore[call-overload]
        cfg.mode = str(d.get("mode", "normal"))
        cfg.trigger = str(d.get("trigger", "") or "")
        cfg.edge = str(d.get("edge", "rising"))
        cfg.level = float(d.get("level", 0.5))  # type: ignore[arg-type]
        cfg.position = float(d.get("position", 50.0))  # type: ignore[arg-type]
    except (TypeError, ValueError) as e:
        raise HalError(f"bad scope setting: {e}") from None
    return cfg


def config_json(cfg: ScopeConfig) -> dict[str, object]:
    return {
        "channels": [{"name": c.name, "scale": c.scale, "offset": c.offset} for c in cfg.channels],
        "thread": cfg.thread,
        "mult": cfg.mult,
        "samples": cfg.samples,
        "mode": cfg.mode,
        "trigger": cfg.trigger,
        "edge": cfg.edge,
        "level": cfg.level,
        "position": cfg.position,
        "text": setupfile.dumps(cfg),
    }


class WebScope:
    """Runs captures until stopped; publish() gets every result."""

    def __init__(self, publish: Callable[[dict[str, object]], None]) -> None:
        self.publish = publish
        self.cfg = ScopeConfig()
        self.thread: threading.Thread | None = None
        self.stop_flag = False
        self.lock = threading.Lock()

    @property
    def running(self) -> bool:
        return self.thread is not None and self.thread.is_alive()

    def status(self, text: str, error: bool = False) -> None:
        self.publish(
            {"type": "scope_status", "text": text, "error": error, "running": self.running}
        )

    def start(self, cfg: ScopeConfig, may_change_hal: bool) -> None:
        """Check everything, put scope_rt in place, start capturing."""
        self.stop()
        from .halscope import check_capacity, check_names

        check_names(cfg)
        if cfg.trigger and cfg.trigger not in [c.name for c in cfg.channels]:
            raise HalError(f"the trigger '{cfg.trigger}' is not one of the channels")
        cfg.pretrig()
        scopectl.check_thread(cfg.thread)
        check_capacity(cfg, None)
        placed = halapi.info(halapi.COMP, "scope_rt") and (
            not cfg.thread or cfg.thread in scopectl.sample_threads()
        )
        if not placed and not may_change_hal:
            raise HalError(
                "read-only page: scope_rt is not loaded in that thread (load it and "
                "addf scope.sample with halcmd, or serve without --read-only)"
            )
        cfg.thread = scopectl.ensure(cfg.thread, None)
        self.cfg = cfg
        self.stop_flag = False
        self.thread = threading.Thread(target=self._run, name="halweb-scope", daemon=True)
        self.thread.start()

    def stop(self) -> None:
        self.stop_flag = True
        if self.thread is not None:
            self.thread.join(timeout=5)
        self.thread = None

    def _stopped(self) -> bool:
        return self.stop_flag

    def _run(self) -> None:
        cfg = self.cfg
        try:
            with halapi.ScopeHandle() as scope:
                try:
                    self._loop(scope, cfg)
                finally:
                    scope.stop()
        except HalError as e:
            self.status(str(e), error=True)
        except KeyboardInterrupt:
            pass
        self.status("stopped")

    def _loop(self, scope: halapi.ScopeHandle, cfg: ScopeConfig) -> None:
        if cfg.mode == "roll":
            self.status("rolling")

            pending: list[Capture] = []
            last = [time.monotonic()]

            def chunk(c: Capture) -> None:
                pending.append(c)
                if time.monotonic() - last[0] >= 0.1:
                    self.publish(capture_json(merge(pending), cfg, chunk=True))
                    pending.clear()
                    last[0] = time.monotonic()

            capture_roll(scope, cfg, None, None, None, self._stopped, chunk, keep=False)
            return
        while not self.stop_flag:
            self.status("armed")
            cap = capture_triggered(scope, cfg, None, None, self._stopped)
            self.publish(capture_json(cap, cfg))
            if cfg.mode == "single":
                break
