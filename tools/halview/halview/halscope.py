# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope: capture HAL pins, signals and parameters with scope_rt.

See docs/halscope.md.  Without --web it takes captures and writes them to
files (CSV, VCD, PNG, SVG); with --web it serves the live page.
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import sys
from types import FrameType

from . import halapi, outputs, scopectl, setupfile, vboardtime
from .capture import Capture, ScopeConfig, capture_roll, capture_triggered, parse_channel
from .halapi import HalError
from .timefmt import parse_ns


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="halscope",
        description="Capture HAL pins, signals and parameters (docs/halscope.md).",
    )
    p.add_argument(
        "loadargs",
        nargs="*",
        metavar="num_samples=N",
        help="scope_rt load argument, as LinuxCNC's halscope",
    )
    p.add_argument("--channels", "-c", default="", help="NAME[,NAME...] (pin:, sig:, param:)")
    p.add_argument("--thread", "-t", default=None, help="thread that runs scope.sample")
    p.add_argument("--mult", type=int, default=None, help="sample every Nth period")
    p.add_argument("--samples", "-n", type=int, default=None, help="record length")
    p.add_argument("--mode", choices=sorted(halapi.MODES), default=None)
    p.add_argument("--trigger", default=None, help="channel NAME, or none")
    p.add_argument("--edge", choices=("rising", "falling"), default=None)
    p.add_argument("--level", type=float, default=None)
    p.add_argument("--position", type=float, default=None, help="%% of the record before it")
    p.add_argument("--duration", default=None, help="roll mode: how long (10ms, 1s, ...)")
    p.add_argument("--count", type=int, default=1, help="normal/auto: captures to take")
    p.add_argument("--out", "-o", action="append", default=[], help="FILE.csv|.vcd|.png|.svg")
    p.add_argument("--setup", "-i", default=None, help="load a scope setup file")
    p.add_argument("--save-setup", default=None, help="write the setup to a file")
    p.add_argument("--timeout", type=float, default=60.0, help="seconds to wait (0: forever)")
    p.add_argument("--name", default="halscope", help="HAL component name while running")
    p.add_argument(
        "--board",
        default=None,
        metavar="SOCKET",
        help="a virtual board: its firmware's waveforms go into the .vcd output",
    )
    p.add_argument("--merge", default=None, help="a virtual board's VCD to merge into .vcd")
    p.add_argument(
        "--board-offset", default=None, help="with --merge: board time minus HAL time in ns"
    )
    p.add_argument("--quiet", "-q", action="store_true")
    from .webargs import add_web_args

    add_web_args(p)
    return p


def config_from_args(a: argparse.Namespace) -> ScopeConfig:
    cfg = setupfile.load(a.setup) if a.setup else ScopeConfig()
    if a.channels:
        cfg.channels = [parse_channel(s) for s in a.channels.split(",") if s.strip()]
    for attr in ("thread", "mult", "samples", "mode", "edge", "level", "position"):
        v = getattr(a, attr)
        if v is not None:
            setattr(cfg, attr, v)
    if a.trigger is not None:
        cfg.trigger = "" if a.trigger == "none" else a.trigger
    if cfg.trigger and cfg.trigger not in [c.name for c in cfg.channels]:
        if len(cfg.channels) >= halapi.MAX_CHAN:
            raise HalError(f"the trigger '{cfg.trigger}' is not a channel and all are in use")
        cfg.channels.append(parse_channel(cfg.trigger))
    return cfg


def num_samples_arg(loadargs: list[str]) -> int | None:
    n = None
    for arg in loadargs:
        key, _, val = arg.partition("=")
        if key != "num_samples" or not val.isdigit():
            raise HalError(f"'{arg}': the only load argument is num_samples=N")
        n = int(val)
    return n


def check_names(cfg: ScopeConfig) -> None:
    """Every channel exists: checked before HAL is changed."""
    for ch in cfg.channels:
        if ch.kind < 0:
            ch.kind = halapi.find_kind(ch.name)
        elif halapi.info(ch.kind, ch.name) is None:
            raise HalError(f"{halapi.KIND_NAMES[ch.kind]} '{ch.name}' does not exist")


class _Stop:
    def __init__(self) -> None:
        self.flag = False

    def __call__(self) -> bool:
        return self.flag

    def handler(self, signum: int, frame: FrameType | None) -> None:
        self.flag = True


def check_capacity(cfg: ScopeConfig, nsamp: int | None) -> None:
    """The record fits in scope_rt's memory (loaded, or about to be)."""
    if halapi.info(halapi.COMP, "scope_rt"):
        with halapi.ScopeHandle() as scope:
            total = scope.status().num_samples
    else:
        total = nsamp or 16000
    nchan = max(1, len(cfg.channels))
    if cfg.mode != "roll" and cfg.samples > total // nchan:
        raise HalError(
            f"record length {cfg.samples} with {nchan} channels: scope_rt holds "
            f"{total // nchan} (num_samples={total})"
        )
    if cfg.mode == "roll" and total // nchan < 2:
        raise HalError(f"{nchan} channels: scope_rt's num_samples={total} is too small")


class Ready:
    """halscope's HAL component, ready once the scope is armed (so that
    `loadusr -Wn halscope halscope ...` returns when nothing can be missed)
    and gone once the files are written (`waitusr halscope`)."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.comp: object | None = None

    def ready(self) -> None:
        if self.comp is None:
            import hal

            self.comp = hal.component(self.name)
            self.comp.ready()  # type: ignore[attr-defined]

    def exit(self) -> None:
        if self.comp is not None:
            self.comp.exit()  # type: ignore[attr-defined]
            self.comp = None


def take(a: argparse.Namespace, cfg: ScopeConfig, comp: Ready) -> list[Capture]:
    nsamp = num_samples_arg(a.loadargs)
    thread = scopectl.ensure(cfg.thread, nsamp)
    cfg.thread = thread
    timeout = a.timeout if a.timeout > 0 else None
    stop = _Stop()
    signal.signal(signal.SIGTERM, stop.handler)
    signal.signal(signal.SIGINT, stop.handler)
    board_dump = board_dump_path(a)
    dumping = False

    def armed() -> None:
        nonlocal dumping
        if comp.comp is None:
            if board_dump:
                vboardtime.dump(a.board, True, board_dump)
                dumping = True
            comp.ready()

    def done(cap: Capture) -> None:
        nonlocal dumping
        if board_dump and dumping:
            cap.board_offset = vboardtime.board_time(a.board) - halapi.now_ns()
            vboardtime.dump(a.board, False)
            dumping = False

    caps: list[Capture] = []
    try:
        with halapi.ScopeHandle() as scope:
            try:
                if cfg.mode == "roll":
                    records = None
                    if a.duration:
                        interval = scopectl.thread_period(thread) * cfg.mult
                        records = math.ceil(parse_ns(a.duration) / interval)
                    caps.append(capture_roll(scope, cfg, records, timeout, armed, stop))
                else:
                    count = 1 if cfg.mode == "single" else max(1, a.count)
                    for _ in range(count):
                        caps.append(capture_triggered(scope, cfg, timeout, armed, stop, done))
            finally:
                scope.stop()
    except KeyboardInterrupt:
        pass
    finally:
        if dumping:
            vboardtime.dump(a.board, False)
    return caps


def board_dump_path(a: argparse.Namespace) -> str:
    """Where the board writes its dump for --board (next to the .vcd output)."""
    if not a.board:
        return ""
    vcds = [p for p in a.out if p.lower().endswith(".vcd")]
    return os.path.abspath(vcds[0] + ".board.vcd")


def check_board(a: argparse.Namespace, cfg: ScopeConfig) -> None:
    if not a.board:
        return
    if not [p for p in a.out if p.lower().endswith(".vcd")]:
        raise HalError("--board merges the firmware's waveforms into a .vcd output: name one")
    if a.merge:
        raise HalError("--board and --merge: one or the other")
    if cfg.mode == "roll" or (cfg.mode != "single" and a.count != 1):
        raise HalError("--board takes one triggered capture (not roll, not --count)")
    if not halapi.simclock():
        raise HalError("--board needs the simulated clock (halrun -S) and a lockstep board")
    vboardtime.board_time(a.board)  # it answers


def title_of(cfg: ScopeConfig, cap: Capture) -> str:
    trig = f"trigger {cfg.trigger} {cfg.edge} {cfg.level:g}" if cfg.trigger else "no trigger"
    if cap.forced:
        trig += " (forced)"
    return (
        f"halscope: {cap.length} samples every {cap.interval} ns, thread {cfg.thread}, "
        f"{cfg.mode}, {trig}"
    )


def write_outputs(a: argparse.Namespace, cfg: ScopeConfig, caps: list[Capture]) -> None:
    for n, cap in enumerate(caps):
        for path in a.out:
            if len(caps) > 1:
                stem, dot, ext = path.rpartition(".")
                path = f"{stem}-{n + 1}.{ext}"
            if a.board and path.lower().endswith(".vcd"):
                from .vcdmerge import write_merged

                dump = board_dump_path(a)
                write_merged(cap, dump, path, None, title_of(cfg, cap))
                os.unlink(dump)
            elif a.merge and path.lower().endswith(".vcd"):
                from .vcdmerge import write_merged

                write_merged(cap, a.merge, path, a.board_offset, title_of(cfg, cap))
            else:
                outputs.write(cap, path, title_of(cfg, cap))


def main(argv: list[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        cfg = config_from_args(a)
        if a.save_setup:
            setupfile.save(cfg, a.save_setup)
        if a.web:
            from .halweb import serve_from_args

            return serve_from_args(a, page="scope", scope_cfg=cfg)
        if not a.out:
            if a.save_setup:
                return 0
            raise HalError("nothing to do: name an output (--out FILE) or --web")
        for path in a.out:
            outputs.check_writable(path)
        if a.merge:
            from .vcdmerge import check_merge

            check_merge(a.merge, a.board_offset)
            if not [p for p in a.out if p.lower().endswith(".vcd")]:
                raise HalError("--merge writes the merged waveforms into a .vcd output: name one")
            if a.board_offset is None:
                raise HalError("--merge needs --board-offset NS (or use --board SOCKET)")
        halapi.require_session()
        check_names(cfg)
        scopectl.check_thread(cfg.thread or "")
        check_capacity(cfg, num_samples_arg(a.loadargs))
        check_board(a, cfg)
        comp = Ready(a.name)
        try:
            caps = take(a, cfg, comp)
            if not caps:
                raise HalError("stopped before a capture was complete")
            write_outputs(a, cfg, caps)
        finally:
            comp.exit()
        if not a.quiet:
            for cap in caps:
                extra = f", {cap.lost} lost" if cap.mode == "roll" else ""
                print(f"halscope: {cap.length} samples{extra}", file=sys.stderr)
    except HalError as e:
        print(f"halscope: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
