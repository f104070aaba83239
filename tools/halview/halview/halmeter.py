# SPDX-License-Identifier: GPL-2.0-or-later
"""halmeter: watch HAL pins, signals and parameters (docs/halmeter.md).

In a terminal it shows the current values and redraws them; with --text (or
when stdout is not a terminal) it prints one line per value change:
``TIME NAME VALUE`` with TIME the session's clock in seconds (the simulated
time under ``halrun -S``).  A removed item prints ``TIME NAME removed``; it is
watched again if it comes back.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time
from types import FrameType

from . import halapi, model
from .halapi import HalError
from .session import SessionComponent
from .webargs import add_web_args

KIND_WORDS = ("pin", "sig", "param")


def parse_items(words: list[str]) -> list[tuple[int, str]]:
    """`pin A sig B param C` (as LinuxCNC's halmeter), or bare names."""
    items: list[tuple[int, str]] = []
    i = 0
    while i < len(words):
        w = words[i]
        if w in KIND_WORDS:
            if i + 1 >= len(words):
                raise HalError(f"'{w}' needs a name")
            items.append((halapi.KIND_BY_NAME[w], words[i + 1]))
            i += 2
        else:
            items.append(model.parse_item(w))
            i += 1
    return items


def check_items(items: list[tuple[int, str]]) -> None:
    for kind, name in items:
        if halapi.info(kind, name) is None:
            raise HalError(f"{halapi.KIND_NAMES[kind]} '{name}' does not exist")


class Meter:
    def __init__(self, items: list[tuple[int, str]]) -> None:
        self.items = items
        self.last: list[str | None] = [""] * len(items)

    def poll(self) -> list[tuple[int, str | None]]:
        """(index, new value or None for removed) of what changed."""
        vals = halapi.get_many(self.items)
        out = []
        for i, v in enumerate(vals):
            if v != self.last[i]:
                out.append((i, v))
                self.last[i] = v
        return out


def run_text(m: Meter, interval: float, count: int, stop: "_Stop") -> None:
    lines = 0
    while not stop.flag:
        t = halapi.now_ns() / 1e9
        for i, v in m.poll():
            name = m.items[i][1]
            print(f"{t:.9f} {name} {'removed' if v is None else v}", flush=True)
            lines += 1
            if count and lines >= count:
                return
        time.sleep(interval)


def run_screen(m: Meter, interval: float, small: bool, stop: "_Stop") -> None:
    width = max(len(n) for _, n in m.items)
    first = True
    while not stop.flag:
        m.poll()
        if not first:
            sys.stdout.write(f"\x1b[{len(m.items)}F")  # back to the first line
        first = False
        for (kind, name), v in zip(m.items, m.last):
            text = "removed" if v is None else v
            if small:
                sys.stdout.write(f"\x1b[2K{text}\n")
            else:
                kname = halapi.KIND_NAMES[kind]
                sys.stdout.write(f"\x1b[2K{kname:5s} {name:<{width}s}  {text}\n")
        sys.stdout.flush()
        time.sleep(interval)


class _Stop:
    def __init__(self) -> None:
        self.flag = False

    def handler(self, signum: int, frame: FrameType | None) -> None:
        self.flag = True


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="halmeter", description="Watch HAL pins, signals and parameters."
    )
    p.add_argument("items", nargs="*", help="[pin|sig|param] NAME ...")
    p.add_argument("-s", "--small", action="store_true", help="values only")
    p.add_argument(
        "-g", nargs=2, metavar=("X", "Y"), help="window position [and width] (ignored: no window)"
    )
    p.add_argument("--text", action="store_true", help="print value changes, one per line")
    p.add_argument("--interval", type=float, default=0.1, help="seconds between polls")
    p.add_argument("--count", type=int, default=0, help="--text: stop after N lines")
    add_web_args(p)
    return p


def drop_width(argv: list[str]) -> list[str]:
    """LinuxCNC's `-g X Y [WIDTH]`: the optional width, when a number,
    is taken out so that it is not read as a name to watch."""
    out = list(argv)
    for i, w in enumerate(out):
        if w == "-g" and i + 3 < len(out):
            if out[i + 3].lstrip("-").isdigit():
                del out[i + 3]
            break
    return out


def main(argv: list[str] | None = None) -> int:
    a = build_parser().parse_args(drop_width(sys.argv[1:] if argv is None else argv))
    stop = _Stop()
    signal.signal(signal.SIGTERM, stop.handler)
    signal.signal(signal.SIGINT, stop.handler)
    try:
        halapi.require_session()
        items = parse_items(a.items)
        check_items(items)
        if a.web:
            from .halweb import serve_from_args

            return serve_from_args(a, page="meter", watch=items)
        if not items:
            raise HalError("nothing to watch: name a pin, signal or parameter")
        if a.interval <= 0:
            raise HalError(f"interval {a.interval}: must be more than 0")
        m = Meter(items)
        with SessionComponent("halmeter"):
            if a.text or not sys.stdout.isatty():
                run_text(m, a.interval, a.count, stop)
            else:
                run_screen(m, a.interval, a.small, stop)
    except HalError as e:
        print(f"halmeter: {e}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
