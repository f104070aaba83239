# SPDX-License-Identifier: GPL-2.0-or-later
"""HAL regression tests in LinuxCNC's directory style.

Every directory tests/hal/<name>/ is one test:

* ``test.hal`` (or ``test.tcl``, a Tcl HAL file that halrun runs with
  haltcl) + ``expected``: ``halrun -f test.hal`` runs in the directory
  in a fresh HAL_INSTANCE; its stdout, normalized (halnorm.py), must equal
  ``expected``.  Optional files: ``expected.stderr`` (stderr must equal it,
  normalized), ``halrun.args`` (extra halrun options, one line, e.g. ``-k``
  or ``-S``), ``exitcode`` (expected exit status, default 0), ``env``
  (KEY=VALUE lines added to the environment).
* ``test.sh`` + ``checkresult``: ``bash test.sh`` runs in the directory with
  stdout captured to a file ``result`` in a temporary directory; then
  ``bash checkresult <result>`` must exit 0 (LinuxCNC's convention).

The environment of each test: HAL_INSTANCE unique to it, HM_BUILD, PATH
with $HM_BUILD/bin first, HAL_RTLIB_PATH including lib/rtlib-test (the
test-only component hm_testmod).  After each test the instance is cleaned
with ``halrun -U`` so a failing test leaves nothing behind.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from halnorm import normalize  # noqa: E402

ROOT = HERE.parents[1]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALRUN = BUILD / "bin" / "halrun"


def _cases() -> list[Path]:
    out = []
    for d in sorted(HERE.iterdir()):
        if d.is_dir() and any((d / f).exists() for f in ("test.hal", "test.tcl", "test.sh")):
            out.append(d)
    return out


def hal_env(instance: str) -> dict[str, str]:
    env = dict(os.environ)
    env["HAL_INSTANCE"] = instance
    env["HM_BUILD"] = str(BUILD)
    env["PATH"] = f"{BUILD / 'bin'}:{env.get('PATH', '')}"
    env["HAL_RTLIB_PATH"] = f"{BUILD / 'lib' / 'rtlib-test'}:{BUILD / 'lib' / 'rtlib'}"
    env.pop("HAL_RTLIB_DIR", None)
    for var in (
        "HAL_SIMCLOCK",
        "RTAPI_MSG_LEVEL",
        "HAL_HALRUN",
        "HAL_RTAPI_STDIO",
        "HAL_GROUP",
        "HAL_OWNER",
        "HAL_TIMING_EVERY",
    ):
        env.pop(var, None)
    return env


def _cleanup(env: dict[str, str]) -> None:
    subprocess.run([str(HALRUN), "-U"], env=env, capture_output=True, timeout=30)


@pytest.mark.requires_build(HALRUN)
@pytest.mark.parametrize("case", _cases(), ids=lambda p: p.name)
def test_hal(case: Path, tmp_path: Path) -> None:
    env = hal_env(f"t{os.getpid()}-{case.name}")
    if (case / "env").exists():
        for line in (case / "env").read_text().splitlines():
            if "=" in line and not line.startswith("#"):
                k, v = line.split("=", 1)
                env[k.strip()] = v.strip()
    _cleanup(env)
    try:
        script = next((f for f in ("test.hal", "test.tcl") if (case / f).exists()), None)
        if script is not None:
            args = []
            if (case / "halrun.args").exists():
                args = (case / "halrun.args").read_text().split()
            proc = subprocess.run(
                [str(HALRUN), *args, "-f", script],
                cwd=case,
                env=env,
                capture_output=True,
                text=True,
                timeout=120,
            )
            want_rc = 0
            if (case / "exitcode").exists():
                want_rc = int((case / "exitcode").read_text().strip())
            got = normalize(proc.stdout)
            want = normalize((case / "expected").read_text())
            assert got == want, f"stdout differs\n--- stderr:\n{proc.stderr}"
            if (case / "expected.stderr").exists():
                assert normalize(proc.stderr) == normalize((case / "expected.stderr").read_text())
            assert proc.returncode == want_rc, proc.stderr
        else:
            result = tmp_path / "result"
            with open(result, "w") as out:
                proc = subprocess.run(
                    ["bash", "test.sh"],
                    cwd=case,
                    env=env,
                    stdout=out,
                    stderr=subprocess.PIPE,
                    text=True,
                    timeout=300,
                )
            check = subprocess.run(
                ["bash", "checkresult", str(result)],
                cwd=case,
                env=env,
                capture_output=True,
                text=True,
                timeout=60,
            )
            assert check.returncode == 0, (
                f"checkresult failed:\n{check.stdout}{check.stderr}\n"
                f"--- test.sh rc={proc.returncode} stderr:\n{proc.stderr}\n"
                f"--- result:\n{result.read_text()}"
            )
    finally:
        _cleanup(env)
