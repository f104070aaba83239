# SPDX-License-Identifier: GPL-2.0-or-later
"""Putting scope_rt in place: load it and add scope.sample to a thread.

Changes go through halcmd (the same commands a user would type), and only
after every check passed, so a bad thread name changes nothing.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from . import halapi
from .halapi import HalError


def halcmd_path() -> str:
    env = os.environ.get("HALVIEW_BIN")
    if env and (Path(env) / "halcmd").exists():
        return str(Path(env) / "halcmd")
    found = shutil.which("halcmd")
    if found:
        return found
    raise HalError("halcmd not found (put the build's bin/ on PATH: . scripts/env.sh)")


def halcmd(*args: str) -> None:
    r = subprocess.run(
        [halcmd_path(), *args], capture_output=True, text=True, stdin=subprocess.DEVNULL
    )
    if r.returncode != 0:
        msg = (r.stderr.strip() or r.stdout.strip()).splitlines()
        raise HalError(f"halcmd {' '.join(args)} failed: {msg[-1] if msg else r.returncode}")


def threads() -> list[str]:
    return halapi.list_names(halapi.THREAD)


def thread_period(name: str) -> int:
    info = halapi.info(halapi.THREAD, name)
    if info is None:
        raise HalError(no_thread_message(name))
    return int(info[0])


def no_thread_message(name: str) -> str:
    have = threads()
    listed = ", ".join(have) if have else "none"
    return f"thread '{name}' does not exist (threads: {listed})"


def sample_threads() -> list[str]:
    """Threads that run scope.sample."""
    out = []
    for t in threads():
        info = halapi.info(halapi.THREAD, t)
        if info is not None and "scope.sample" in info[2].split():
            out.append(t)
    return out


def check_thread(thread: str) -> None:
    if thread and halapi.info(halapi.THREAD, thread) is None:
        raise HalError(no_thread_message(thread))


def ensure(thread: str, num_samples: int | None) -> str:
    """scope_rt loaded and scope.sample in `thread` (or in whatever thread
    it already is when thread is ""); returns the thread."""
    check_thread(thread)
    if not halapi.info(halapi.COMP, "scope_rt"):
        if not thread:
            raise HalError("scope_rt is not loaded: name the thread to sample in (--thread)")
        args = ["loadrt", "scope_rt"]
        if num_samples:
            args.append(f"num_samples={num_samples}")
        halcmd(*args)
    current = sample_threads()
    if not thread:
        if not current:
            raise HalError("scope.sample is in no thread: name one (--thread)")
        return current[0]
    for t in current:
        if t != thread:
            halcmd("delf", "scope.sample", t)
    if thread not in current:
        halcmd("addf", "scope.sample", thread)
    return thread
