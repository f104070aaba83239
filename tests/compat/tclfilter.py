# SPDX-License-Identifier: GPL-2.0-or-later
"""The compat rule for Tcl HAL files (docs/compat.md): make compat's side of
compat_filter.tcl.

A Tcl HAL file cannot be prepared line by line like a .hal file: its HAL
commands are made while it runs (procedures, loops, INI arrays).  So
haltcl runs it with compat_filter.tcl loaded first, which asks this server
about every HAL command before it runs; the answer comes from the same
rule (halprep.classify and the virtual-hardware hook) with the same
context as the configuration's .hal files.
"""

from __future__ import annotations

import select
import socket
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

import halprep

HERE = Path(__file__).resolve().parent
FILTER = HERE / "compat_filter.tcl"

Hook = Callable[[int, str, list[str], halprep.Action], halprep.Action]


def hal_line(words: list[str]) -> str:
    """The halcmd line for a command's words (a value with blanks quoted)."""
    out = []
    for w in words:
        key, eq, value = w.partition("=")
        if any(c.isspace() for c in w):
            w = f'{key}="{value}"' if eq else f'"{w}"'
        out.append(w)
    return " ".join(out)


def decide(words: list[str], ini: halprep.Ini, ctx: halprep.Context, hook: Hook) -> halprep.Action:
    """The rule's action for one HAL command of a Tcl file."""
    if not words:
        return halprep.KEEP
    line = hal_line(words)
    action = halprep.classify(line, ini, ctx)
    if action.kind == "keep":
        action = hook(0, line, words, action)
    return action


def _hex(s: str) -> str:
    return s.encode().hex()


def reply(action: halprep.Action) -> str:
    if action.kind == "remove":
        return "remove"
    if action.kind == "rewrite":
        return " ".join(["rewrite", *(_hex(w) for w in halprep.split_words(action.text))])
    return "keep"


def wrapper(port: int, file: Path, args: list[str], twopass: bool) -> str:
    """The script haltcl runs: the filter, then FILE as LinuxCNC runs it
    ($::argv the arguments of its HALFILE line)."""
    tcl_list = " ".join("{" + a + "}" for a in args)
    lines = [
        "# written by make compat (tests/compat/tclfilter.py)",
        f"set ::compat_filter [open {{{FILTER}}}]",
        "eval [read $::compat_filter]",
        "close $::compat_filter",
        "unset ::compat_filter",
        f"::compat::connect {port}",
        "::compat::install",
    ]
    if twopass:
        # LinuxCNC's TWOPASS runs a .tcl file twice; here it runs once,
        # as the pass that executes everything.
        lines.append("namespace eval ::tp { proc passnumber {} { return 1 } }")
    lines += [
        f"set ::argv [list {tcl_list}]",
        f"set ::argc {len(args)}",
        f"set ::argv0 {{{file}}}",
        f"source {{{file}}}",
    ]
    return "\n".join(lines) + "\n"


class Server:
    """A local TCP server answering one haltcl's filter requests."""

    def __init__(
        self,
        ini: halprep.Ini,
        ctx: halprep.Context,
        hook: Hook,
        first: Callable[[], list[str]] | None = None,
    ) -> None:
        """`first()`, called after each decision, returns HAL lines haltcl
        runs before the command (make compat's motion stand-in)."""
        self.ini, self.ctx, self.hook, self.first = ini, ctx, hook, first
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(1)
        self.actions: list[tuple[int, halprep.Action]] = []

    @property
    def port(self) -> int:
        return int(self.sock.getsockname()[1])

    def close(self) -> None:
        self.sock.close()

    def serve(self, proc: subprocess.Popen[bytes], deadline: float) -> bool:
        """Answer requests until haltcl exits; False on the deadline."""
        conn = None
        buf = b""
        try:
            while proc.poll() is None:
                if time.monotonic() > deadline:
                    return False
                wait = [conn] if conn is not None else [self.sock]
                ready, _, _ = select.select(wait, [], [], 0.05)
                if not ready:
                    continue
                if conn is None:
                    conn, _ = self.sock.accept()
                    continue
                data = conn.recv(65536)
                if not data:
                    conn.close()
                    conn = None
                    continue
                buf += data
                while b"\n" in buf:
                    line, buf = buf.split(b"\n", 1)
                    words = [bytes.fromhex(h).decode() for h in line.decode().split()]
                    action = decide(words, self.ini, self.ctx, self.hook)
                    for cmd in self.first() if self.first is not None else []:
                        hexed = (_hex(w) for w in halprep.split_words(cmd))
                        conn.sendall((" ".join(["first", *hexed]) + "\n").encode())
                    if action.kind != "keep" or action.why:
                        self.actions.append((len(self.actions) + 1, action))
                    conn.sendall((reply(action) + "\n").encode())
            return True
        finally:
            if conn is not None:
                conn.close()
