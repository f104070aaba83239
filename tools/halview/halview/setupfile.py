# SPDX-License-Identifier: GPL-2.0-or-later
"""Scope setups as text files: what to capture and how to show it.

::

    # halscope setup
    thread servo-thread
    mult 1
    samples 1000
    mode normal
    trigger siggen.0.square rising 0.5 position 25
    chan pin siggen.0.square scale 1 offset 0
    chan sig velocity scale 0.5 offset 0

``trigger none`` captures at once.  Blank lines and ``#`` comments are
ignored; an error names the file, the line and the cause, and nothing of a
bad file is used.
"""

from __future__ import annotations

from pathlib import Path

from . import halapi
from .capture import Channel, ScopeConfig
from .halapi import HalError

_KINDS = {"pin": halapi.PIN, "sig": halapi.SIG, "param": halapi.PARAM}
_KIND_WORD = {v: k for k, v in _KINDS.items()}


def dumps(cfg: ScopeConfig) -> str:
    lines = ["# halscope setup (docs/halscope.md)"]
    if cfg.thread:
        lines.append(f"thread {cfg.thread}")
    lines.append(f"mult {cfg.mult}")
    lines.append(f"samples {cfg.samples}")
    lines.append(f"mode {cfg.mode}")
    if cfg.trigger:
        lines.append(f"trigger {cfg.trigger} {cfg.edge} {cfg.level!r} position {cfg.position!r}")
    else:
        lines.append("trigger none")
    for c in cfg.channels:
        kind = _KIND_WORD.get(c.kind, "auto")
        lines.append(f"chan {kind} {c.name} scale {c.scale!r} offset {c.offset!r}")
    return "\n".join(lines) + "\n"


def _num(words: list[str], i: int, where: str, cast: type = float) -> float:
    if i >= len(words):
        raise HalError(f"{where}: a number is missing")
    try:
        return cast(words[i])  # type: ignore[no-any-return]
    except ValueError:
        raise HalError(f"{where}: '{words[i]}' is not a number") from None


def _options(words: list[str], where: str, allowed: tuple[str, ...]) -> dict[str, float]:
    out: dict[str, float] = {}
    if len(words) % 2:
        raise HalError(f"{where}: options go in pairs (NAME VALUE)")
    for i in range(0, len(words), 2):
        if words[i] not in allowed:
            raise HalError(f"{where}: unknown option '{words[i]}' (expected {', '.join(allowed)})")
        out[words[i]] = _num(words, i + 1, where)
    return out


def loads(text: str, source: str = "setup") -> ScopeConfig:
    cfg = ScopeConfig()
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        where = f"{source}:{n}"
        words = line.split()
        key, args = words[0], words[1:]
        if key == "thread" and len(args) == 1:
            cfg.thread = args[0]
        elif key == "mult" and len(args) == 1:
            cfg.mult = int(_num(args, 0, where, int))
        elif key == "samples" and len(args) == 1:
            cfg.samples = int(_num(args, 0, where, int))
        elif key == "mode" and len(args) == 1:
            if args[0] not in halapi.MODES:
                raise HalError(f"{where}: mode '{args[0]}': one of normal, auto, single, roll")
            cfg.mode = args[0]
        elif key == "trigger" and args == ["none"]:
            cfg.trigger = ""
        elif key == "trigger" and len(args) >= 3:
            if args[1] not in ("rising", "falling"):
                raise HalError(f"{where}: edge '{args[1]}': rising or falling")
            cfg.trigger, cfg.edge = args[0], args[1]
            cfg.level = _num(args, 2, where)
            cfg.position = _options(args[3:], where, ("position",)).get("position", 50.0)
        elif key == "chan" and len(args) >= 2:
            if args[0] not in _KINDS and args[0] != "auto":
                raise HalError(f"{where}: '{args[0]}': pin, sig, param or auto")
            opts = _options(args[2:], where, ("scale", "offset"))
            cfg.channels.append(
                Channel(
                    name=args[1],
                    kind=_KINDS.get(args[0], -1),
                    scale=opts.get("scale", 1.0),
                    offset=opts.get("offset", 0.0),
                )
            )
        else:
            raise HalError(f"{where}: cannot understand '{line}'")
    if len(cfg.channels) > halapi.MAX_CHAN:
        raise HalError(f"{source}: {len(cfg.channels)} channels, the scope has {halapi.MAX_CHAN}")
    return cfg


def load(path: str) -> ScopeConfig:
    try:
        text = Path(path).read_text()
    except OSError as e:
        raise HalError(f"cannot read the setup {path}: {e.strerror}") from None
    return loads(text, path)


def save(cfg: ScopeConfig, path: str) -> None:
    try:
        Path(path).write_text(dumps(cfg))
    except OSError as e:
        raise HalError(f"cannot write the setup {path}: {e.strerror}") from None
