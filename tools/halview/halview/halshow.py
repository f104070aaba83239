# SPDX-License-Identifier: GPL-2.0-or-later
"""halshow: the tree of everything in HAL, with values (docs/halshow.md).

``halshow --text [PATTERN]`` prints the tree once; ``--set NAME VALUE``
sets a pin, parameter or signal with halcmd's rules; ``--web`` serves the
live page (tree, filter, watch list, setting values).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import halapi, model
from .halapi import HalError
from .webargs import add_web_args

SECTIONS = (
    ("comp", "Components"),
    ("pin", "Pins"),
    ("param", "Parameters"),
    ("sig", "Signals"),
    ("funct", "Functions"),
    ("thread", "Threads"),
)


class Formats:
    def __init__(self, fformat: str | None, iformat: str | None) -> None:
        self.fformat, self.iformat = fformat, iformat
        for f, sample in ((fformat, 1.5), (iformat, 1)):
            if f is not None:
                try:
                    f % sample
                except (TypeError, ValueError):
                    raise HalError(f"format '{f}' does not format a number") from None

    def value(self, it: model.Item) -> str:
        try:
            if it.type == "float" and self.fformat:
                return self.fformat % float(it.value)
            if it.type in ("s32", "u32", "s64", "u64") and self.iformat:
                return self.iformat % int(it.value)
        except ValueError:
            pass
        return it.value


def describe(it: model.Item, fmt: Formats) -> str:
    if it.kind == "comp":
        e = it.extra
        state = "ready" if e["ready"] == "1" else "initializing"
        pid = f" pid {e['pid']}" if it.type == "User" else ""
        args = f" [{e['args']}]" if e["args"] else ""
        return f"{it.type} id {e['id']}{pid} {state}{args}"
    if it.kind == "pin":
        link = f"  {'<==' if it.dir == 'IN' else '==>' if it.dir == 'OUT' else '<=>'} "
        return f"{it.type} {it.dir} {fmt.value(it)}" + (link + it.links[0] if it.links else "")
    if it.kind == "param":
        return f"{it.type} {it.dir} {fmt.value(it)}"
    if it.kind == "sig":
        return f"{it.type} {fmt.value(it)}" + (f"  [{' '.join(it.links)}]" if it.links else "")
    if it.kind == "funct":
        e = it.extra
        fp = "fp" if e["fp"] == "1" else "no fp"
        return f"owner {e['owner_id']}, {fp}, in {e['users']} thread(s)"
    e = it.extra
    return f"period {e['period']} ns, {'fp' if e['fp'] == '1' else 'no fp'}"


def tree_lines(snap: dict[str, list[model.Item]], fmt: Formats) -> list[str]:
    """The snapshot as an indented tree, dotted names split into levels."""
    lines: list[str] = []
    for kind, title in SECTIONS:
        items = snap.get(kind, [])
        lines.append(f"{title} ({len(items)})")
        shown: list[str] = []
        for it in items:
            parts = it.name.split(".") if kind in ("pin", "param") else [it.name]
            common = 0
            while common < min(len(shown), len(parts) - 1) and shown[common] == parts[common]:
                common += 1
            shown = shown[:common]
            for depth in range(common, len(parts) - 1):
                lines.append("  " * (depth + 1) + parts[depth])
                shown.append(parts[depth])
            lines.append("  " * len(parts) + f"{parts[-1]} = {describe(it, fmt)}")
            if kind == "thread":
                for n, f in enumerate(it.links, 1):
                    lines.append(f"    {n} {f}")
    return lines


def read_watchfile(path: str) -> list[tuple[int, str]]:
    try:
        words = Path(path).read_text().split()
    except OSError as e:
        raise HalError(f"cannot read the watch file {path}: {e.strerror}") from None
    return [model.parse_item(w) for w in words]


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="halshow", description="Show HAL's tree with values.")
    p.add_argument("watchfile", nargs="?", help="watch list (pin+NAME param+NAME sig+NAME)")
    p.add_argument(
        "--text",
        nargs="?",
        const="",
        default=None,
        metavar="PATTERN",
        help="print the tree once (names matching PATTERN)",
    )
    p.add_argument(
        "--watch",
        action="append",
        default=[],
        metavar="NAME",
        help="print NAME's value (pin+, param+, sig+ or a bare name)",
    )
    p.add_argument("--set", nargs=2, metavar=("NAME", "VALUE"), help="set a value")
    p.add_argument("--fformat", default=None, help="printf format of floats, e.g. %%.5f")
    p.add_argument("--iformat", default=None, help="printf format of integers")
    p.add_argument("--noprefs", action="store_true", help="accepted (no preference file)")
    add_web_args(p)
    return p


def main(argv: list[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        fmt = Formats(a.fformat, a.iformat)
        halapi.require_session()
        watch = read_watchfile(a.watchfile) if a.watchfile else []
        watch += [model.parse_item(w) for w in a.watch]
        if a.set:
            kind, name = model.parse_item(a.set[0])
            model.set_item(kind, name, a.set[1])
        if a.web:
            from .halweb import serve_from_args

            return serve_from_args(a, page="show", watch=watch, fformat=a.fformat)
        if a.text is not None:
            print("\n".join(tree_lines(model.snapshot(a.text), fmt)))
        for kind, name in watch:
            it = model.lookup(halapi.KIND_NAMES[kind], name)
            text = "removed" if it is None else fmt.value(it)
            print(f"{halapi.KIND_NAMES[kind]}+{name} = {text}")
        if a.text is None and not watch and not a.set:
            raise HalError("nothing to do: --text, --watch, --set or --web")
    except HalError as e:
        print(f"halshow: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
