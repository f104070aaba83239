# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers for the halcompile tests: run bin/halcompile and halrun of the
build under test, each HAL session in its own HAL_INSTANCE."""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALCOMPILE = BUILD / "bin" / "halcompile"
HALRUN = BUILD / "bin" / "halrun"
COMPS = HERE / "comps"
DATA = HERE / "data"
sys.path.insert(0, str(ROOT / "tests" / "hal"))
sys.path.insert(0, str(ROOT / "tools" / "halcompile"))

from halnorm import normalize  # noqa: E402

_seq = itertools.count()


def require_built() -> None:
    """A missing build is a failure, never a skip."""
    for p in (HALCOMPILE, HALRUN):
        assert p.exists(), f"{p} is not built: run make build"


def halcompile(
    *args: str | Path, cwd: Path, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    require_built()
    return subprocess.run(
        [str(HALCOMPILE), *map(str, args)],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )


def compile_ok(src: Path, outdir: Path, *extra: str) -> Path:
    p = halcompile("--compile", *extra, src, cwd=outdir)
    assert p.returncode == 0, p.stderr
    return outdir


def hal_env(rtlib: list[Path] | None = None, home: Path | None = None) -> dict[str, str]:
    env = dict(os.environ)
    env["HAL_INSTANCE"] = f"hc{os.getpid()}-{next(_seq)}"
    env["PATH"] = f"{BUILD / 'bin'}:{env.get('PATH', '')}"
    dirs = [str(d) for d in (rtlib or [])] + [str(BUILD / "lib" / "rtlib")]
    env["HAL_RTLIB_DIR"] = ":".join(dirs)
    env["HAL_RTLIB_PATH"] = ":".join(str(d) for d in (rtlib or []))
    if home is not None:
        env["HOME"] = str(home)
    env.pop("HAL_SIMCLOCK", None)
    env.pop("RTAPI_MSG_LEVEL", None)
    return env


def python_sanitizer_env(env: dict[str, str]) -> dict[str, str]:
    """For a Python component under a sanitized build (make test SANITIZE=1):
    _hal.so links the ASan runtime, which the uninstrumented interpreter
    needs preloaded; Python's own allocations at exit are not ours."""
    ext = next((BUILD / "lib" / "python").glob("_hal*.so"), None)
    if ext is None:
        return env
    ldd = subprocess.run(["ldd", str(ext)], capture_output=True, text=True).stdout
    libs = [
        line.split("=>")[1].split()[0]
        for line in ldd.splitlines()
        if "=>" in line and ("libasan" in line or "libubsan" in line)
    ]
    if libs:
        env = dict(env, LD_PRELOAD=" ".join(libs), ASAN_OPTIONS="detect_leaks=0")
    return env


def halrun(
    hal_text: str, cwd: Path, env: dict[str, str], *args: str
) -> subprocess.CompletedProcess[str]:
    require_built()
    f = cwd / f"t{next(_seq)}.hal"
    f.write_text(hal_text)
    try:
        return subprocess.run(
            [str(HALRUN), *args, "-f", str(f)],
            cwd=cwd,
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
        )
    finally:
        subprocess.run([str(HALRUN), "-U"], env=env, capture_output=True, timeout=30)


def pins(output: str) -> dict[str, tuple[str, str, str]]:
    """name -> (type, dir, value) from `show pin` / `show param` output."""
    out = {}
    for line in output.splitlines():
        f = line.split()
        if len(f) == 5 and f[0].isdigit() and f[1] in ("bit", "float", "s32", "u32", "s64", "u64"):
            out[f[4]] = (f[1], f[2], f[3])
    return out


__all__ = ["normalize", "halcompile", "compile_ok", "hal_env", "halrun", "pins"]
