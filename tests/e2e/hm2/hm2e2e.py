# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers of the hm2 end-to-end tests: the real hostmot2 + hm2_sim driver
against the real Verilog (bin/vboard), in a halrun session on the
simulated clock.

A test writes a HAL script; pin stimulus and measurements that must happen
while HAL is loaded run inside the script as ``loadusr -w vbprobe.py ...``
(the threads only run inside ``simrun``, so the probe sees the board at an
exact simulated time).  Tagged values are collected by :func:`values`.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import uuid
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
sys.path.insert(0, str(ROOT / "tests" / "common"))
sys.path.insert(0, str(ROOT / "tests" / "driver"))
import vboard  # noqa: E402

HALRUN = BUILD / "bin" / "halrun"
VBOARD = BUILD / "bin" / "vboard"
HM2_SIM = BUILD / "lib" / "rtlib" / "hm2_sim.so"
PROBE = HERE / "vbprobe.py"

needs_vboard = pytest.mark.requires_build(HALRUN, VBOARD, HM2_SIM)

SEED_CONFIG = "firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=3"
PFX = "hm2_5i20.0"

# SVST8_4 on the 5i20 (PIN_SVST8_4_72.csv): the pins the tests use.
ENC0_A, ENC0_B, ENC0_IDX = 3, 2, 5
PWM0_OUT0, PWM0_OUT1, PWM0_NENA = 7, 9, 11
SG0_STEP, SG0_DIR = 48, 49


def load(
    sock: Path,
    config: str = SEED_CONFIG,
    period_ns: int = 1_000_000,
    board: str = "5i20",
    extra: str = "",
) -> str:
    """HAL lines: hostmot2 + hm2_sim on sock, a servo thread with read/write."""
    return (
        "loadrt hostmot2\n"
        f'loadrt hm2_sim socket={sock} board={board} config="{config}" {extra}\n'
        f"loadrt threads name1=servo period1={period_ns}\n"
        f"addf {PFX}.read servo\n"
        f"addf {PFX}.write servo\n"
    )


def probe(sock: Path, *args: object) -> str:
    """A script line running vbprobe.py against the board now."""
    return f"loadusr -w {sys.executable} {PROBE} {sock} {' '.join(str(a) for a in args)}\n"


def tag(name: str, *hal_names: str) -> str:
    """Script lines printing '@@name' and then getp of each object."""
    out = f"loadusr -w echo @@{name}\n"
    for h in hal_names:
        out += f"getp {h}\n"
    return out


def halrun(
    tmp: Path,
    script: str,
    timeout: float = 120,
    simclock: bool = True,
    extra_env: dict[str, str] | None = None,
    drop_env: tuple[str, ...] = (),
) -> subprocess.CompletedProcess[str]:
    f = tmp / f"t{uuid.uuid4().hex[:6]}.hal"
    f.write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = "hm2-e2e-" + uuid.uuid4().hex[:10]
    env["HM_BUILD"] = str(BUILD)
    env.pop("HM2_FIRMWARE_PATH", None)  # firmware from $HM_BUILD/lib/firmware
    env.update(extra_env or {})
    for name in drop_env:
        env.pop(name, None)
    opts = ["-S"] if simclock else []
    r = subprocess.run(
        [str(HALRUN), *opts, "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=env,
        cwd=tmp,
    )
    out = r.stdout + r.stderr
    for bad in ("AddressSanitizer", "LeakSanitizer", "runtime error:"):
        assert bad not in out, f"sanitizer report in the HAL session:\n{out}"
    return r


def values(out: str) -> dict[str, list[str]]:
    """'@@name' markers and the lines after them (until the next marker)."""
    res: dict[str, list[str]] = {}
    cur: str | None = None
    for line in out.splitlines():
        if line.startswith("@@"):
            cur = line[2:].strip()
            res[cur] = []
        elif line.startswith("%%"):  # vbprobe output
            key, _, payload = line[2:].partition(" ")
            res[key] = [payload]
            cur = None
        elif cur is not None and line.strip() and not line.startswith(("hm2", "rtapi")):
            res[cur].append(line.strip())
    return res


def probed(out: str, key: str) -> list[dict[str, int]]:
    """The pins vbprobe.py printed under key."""
    v = values(out)
    assert key in v, f"probe {key} missing in:\n{out}"
    return json.loads(v[key][0])


def num(v: dict[str, list[str]], key: str, i: int = 0) -> float:
    assert key in v and len(v[key]) > i, f"{key}[{i}] missing: {v}"
    s = v[key][i]
    return float(1 if s == "TRUE" else 0 if s == "FALSE" else s)


def processes_mentioning(text: str) -> list[str]:
    """Command lines of live processes whose arguments contain text."""
    found = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            cmd = (d / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if text in cmd and str(os.getpid()) != d.name:
            found.append(f"{d.name}: {cmd}")
    return found
