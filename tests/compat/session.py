# SPDX-License-Identifier: GPL-2.0-or-later
"""One HAL session of `make compat`, run the way LinuxCNC's `linuxcnc`
script runs a configuration: every HALFILE by its own program (halcmd for
a .hal file, haltcl for a .tcl file) in one HAL session, then the threads
run, then the session ends.

The session runs on the simulated clock (HAL_SIMCLOCK=1) and stays up
between the programs (HAL_HALRUN=1, as under halrun).  Everything the
programs and rtapi_app print goes, in order, to one log file; each step
gets the part of the log it wrote.
"""

from __future__ import annotations

import os
import subprocess
import time
import uuid
from collections.abc import Callable
from pathlib import Path

# LinuxCNC's HAL library, where LIB:name files are (HALLIB_DIR).
HALLIB = Path("/usr/share/linuxcnc/hallib")


class Timeout(Exception):
    """The configuration ran out of time."""


class Session:
    def __init__(self, bindir: Path, work: Path, ini: str, deadline: float) -> None:
        self.bindir, self.work, self.deadline = bindir, work, deadline
        self.log_path = work.parent / "session.log"
        self.log = open(self.log_path, "ab")
        self.offset = 0
        env = dict(os.environ)
        env["HAL_INSTANCE"] = "compat-" + uuid.uuid4().hex[:10]
        env["PATH"] = f"{bindir}:{env.get('PATH', '')}"
        # userspace components written in Python import our hal module
        env["PYTHONPATH"] = str(bindir.parent / "lib" / "python")
        env.update(
            HAL_SIMCLOCK="1",
            HAL_HALRUN="1",
            HAL_RTAPI_STDIO="inherit",
            # what LinuxCNC's linuxcnc script exports for HAL files
            INI_FILE_NAME=str(work / ini),
            HALLIB_DIR=str(HALLIB),
            HALLIB_PATH=f".:{HALLIB}",
            CONFIG_DIR=str(work),
        )
        self.env = env

    def _new_output(self) -> str:
        with open(self.log_path, "rb") as f:
            f.seek(self.offset)
            data = f.read()
        self.offset += len(data)
        return data.decode(errors="replace")

    def run(
        self, argv: list[str], serve: Callable[[subprocess.Popen[bytes], float], bool] | None = None
    ) -> tuple[int, str]:
        """Run one program of the session: (exit status, what it printed).
        `serve(proc, deadline)` runs while it does (the Tcl filter)."""
        if time.monotonic() > self.deadline:
            raise Timeout()
        proc = subprocess.Popen(
            argv,
            cwd=self.work,
            env=self.env,
            stdin=subprocess.DEVNULL,
            stdout=self.log,
            stderr=self.log,
        )
        try:
            if serve is not None and not serve(proc, self.deadline):
                raise Timeout()
            proc.wait(timeout=max(0.1, self.deadline - time.monotonic()))
        except (subprocess.TimeoutExpired, Timeout):
            proc.kill()
            proc.wait()
            raise Timeout() from None
        return proc.returncode, self._new_output()

    def halcmd(self, *args: str) -> tuple[int, str]:
        return self.run([str(self.bindir / "halcmd"), *args])

    def end(self) -> str:
        """Stop, unload everything, wait for rtapi_app, remove the session;
        also after a timeout."""
        try:
            self.deadline = max(self.deadline, time.monotonic() + 60)
            _, out = self.halcmd("--session-end")
        except Timeout:
            out = ""
        subprocess.run(
            [str(self.bindir / "halrun"), "-U"], env=self.env, capture_output=True, timeout=60
        )
        self.log.close()
        return out + self._new_output()
