# SPDX-License-Identifier: GPL-2.0-or-later
"""Compiling and installing components outside the build system.

Where things are comes from the environment that bin/halcompile (written by
CMake) sets, so an installed halcompile compiles against the headers and
libraries of the build it belongs to:

    HALCOMPILE_INCLUDE   header directory (hal.h, rtapi.h, halcomp.h, rtapi_*.h)
    HALCOMPILE_LIBDIR    directory of libhal.so and libhalcomp.so
    HALCOMPILE_RTLIB     system-wide realtime module directory (lib/rtlib)
    HALCOMPILE_BINDIR    system-wide program directory (bin)
    HALCOMPILE_CFLAGS    extra compiler flags of the build (sanitizers)

Without them (running ``python -m halcompile`` from the source tree) they
default to the source tree and $HM_BUILD (or build/).
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]


@dataclass
class Config:
    include: Path
    libdir: Path
    rtlib: Path
    bindir: Path
    cflags: list[str]
    cc: str

    @staticmethod
    def from_env() -> "Config":
        build = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
        env = os.environ
        return Config(
            include=Path(env.get("HALCOMPILE_INCLUDE", str(ROOT / "host" / "hal" / "include"))),
            libdir=Path(env.get("HALCOMPILE_LIBDIR", str(build / "lib"))),
            rtlib=Path(env.get("HALCOMPILE_RTLIB", str(build / "lib" / "rtlib"))),
            bindir=Path(env.get("HALCOMPILE_BINDIR", str(build / "bin"))),
            cflags=shlex.split(env.get("HALCOMPILE_CFLAGS", "")),
            cc=env.get("CC", "cc"),
        )

    @staticmethod
    def user_rtlib() -> Path:
        return Path.home() / ".local" / "lib" / "hm2stack" / "rtlib"

    @staticmethod
    def user_bindir() -> Path:
        return Path.home() / ".local" / "bin"


class BuildError(Exception):
    pass


def compile_c(
    cfg: Config,
    csrc: Path,
    out: Path,
    userspace: bool,
    extra_cflags: list[str] | None = None,
    extra_ldflags: list[str] | None = None,
) -> None:
    """Compile one C file into a realtime module (.so) or a program."""
    cmd = [cfg.cc, "-std=gnu11", "-O2", "-g", "-Wall", "-fPIC", f"-I{cfg.include}"]
    cmd += cfg.cflags + (extra_cflags or [])
    if not userspace:
        cmd += ["-shared", "-fvisibility=hidden", "-Wl,-Bsymbolic"]
    cmd += ["-o", str(out), str(csrc)]
    cmd += [f"-L{cfg.libdir}", f"-Wl,-rpath,{cfg.libdir}", "-lhalcomp", "-lhal", "-lm"]
    cmd += extra_ldflags or []
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.stderr:
        print(proc.stderr, end="", file=sys.stderr)
    if proc.returncode != 0:
        raise BuildError(f"compiling {csrc} failed ({cfg.cc} exited with {proc.returncode})")


def install_file(built: Path, dest_dir: Path, name: str, mode: int) -> Path:
    """Put `built` at dest_dir/name atomically: a half-written file never
    carries the final name, an old version stays until the new one is whole."""
    dest_dir.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=dest_dir)
    try:
        with os.fdopen(fd, "wb") as f, open(built, "rb") as src:
            shutil.copyfileobj(src, f)
        os.chmod(tmp, mode)
        final = dest_dir / name
        os.replace(tmp, final)
        return final
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
