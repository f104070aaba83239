# SPDX-License-Identifier: GPL-2.0-or-later
"""A halrun -S session for component tests: run a HAL script on the
simulated clock in a private HAL_INSTANCE and read back what it printed."""

from __future__ import annotations

import os
import subprocess
import uuid
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALRUN = BUILD / "bin" / "halrun"


def run(tmp: Path, script: str, timeout: float = 120) -> str:
    """Run `script` with halrun -S in tmp; a failing line fails the test."""
    (tmp / "t.hal").write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = f"comp{uuid.uuid4().hex[:10]}"
    env["PATH"] = f"{BUILD / 'bin'}:{env.get('PATH', '')}"
    env.pop("HAL_SIMCLOCK", None)
    try:
        r = subprocess.run(
            [str(HALRUN), "-S", "-f", "t.hal"],
            cwd=tmp,
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
        )
    finally:
        subprocess.run([str(HALRUN), "-U"], env=env, capture_output=True, timeout=30)
    assert r.returncode == 0, f"halrun failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r.stdout


def rows(text: str, width: int) -> list[list[str]]:
    """halsampler lines of `width` fields."""
    out = []
    for line in text.splitlines():
        f = line.split()
        if len(f) == width:
            out.append(f)
    return out
