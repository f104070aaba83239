# SPDX-License-Identifier: GPL-2.0-or-later
"""Load-time errors of pluto_servo, pluto_step and hm2_7i43 under our halrun,
without any board: every failure names the object and the reason, the
loadrt fails, and nothing of the component is left in HAL.  (No test here
uses the raw port backend: as root it would touch real I/O ports.)"""

from __future__ import annotations

import os
import subprocess
import uuid
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALRUN = BUILD / "bin" / "halrun"
RTLIB = BUILD / "lib" / "rtlib"
pytestmark = pytest.mark.requires_build(HALRUN, RTLIB / "pluto_servo.so")


def halrun(tmp_path: Path, script: str) -> subprocess.CompletedProcess[str]:
    f = tmp_path / "test.hal"
    f.write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = "pluto-load-" + uuid.uuid4().hex[:10]
    env["HM_BUILD"] = str(BUILD)
    env["HM2_FIRMWARE_PATH"] = str(tmp_path)
    return subprocess.run(
        [str(HALRUN), "-k", "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=60,
        env=env,
        cwd=tmp_path,
    )


def firmware(tmp_path: Path, name: str = "fw.rbf", size: int = 100) -> Path:
    p = tmp_path / name
    p.write_bytes(bytes(range(256)) * (size // 256) + bytes(size % 256))
    return p


@pytest.mark.parametrize("comp", ["pluto_servo", "pluto_step"])
def test_missing_firmware(tmp_path: Path, comp: str) -> None:
    r = halrun(tmp_path, f"loadrt {comp} port=bogus:1 firmware=nope.rbf\nshow comp\nshow pin\n")
    out = r.stdout + r.stderr
    assert f"{comp}: firmware 'nope.rbf' not found (searched {tmp_path})" in out
    assert comp not in r.stdout.split("Loaded HAL Components:")[-1]
    assert "pluto-" not in r.stdout.split("Component Pins:")[-1]


@pytest.mark.parametrize("comp", ["pluto_servo", "pluto_step"])
def test_default_firmware_name(tmp_path: Path, comp: str) -> None:
    r = halrun(tmp_path, f"loadrt {comp} port=bogus:1\n")
    assert f"{comp}: firmware '{comp}.rbf' not found" in r.stdout + r.stderr


@pytest.mark.parametrize("comp", ["pluto_servo", "pluto_step"])
@pytest.mark.parametrize(
    "spec,msg",
    [
        ("bogus:1", "port 'bogus:1': unknown port kind"),
        ("raw:xyz", "port 'raw:xyz': bad I/O address 'xyz'"),
        ("ppdev:/nonexistent/parport7", "ppdev /nonexistent/parport7: open failed: No such file"),
        ("gpiod:gpiochip0:1/2", "need 12 line offsets"),
        ("sim:", "missing socket path"),
    ],
)
def test_bad_port(tmp_path: Path, comp: str, spec: str, msg: str) -> None:
    fw = firmware(tmp_path)
    r = halrun(tmp_path, f"loadrt {comp} port={spec} firmware={fw}\nshow comp\n")
    out = r.stdout + r.stderr
    assert f"{comp}: cannot open the parallel port: " in out
    assert msg in out
    assert comp not in r.stdout.split("Loaded HAL Components:")[-1]


def test_empty_firmware_file(tmp_path: Path) -> None:
    fw = tmp_path / "empty.rbf"
    fw.write_bytes(b"")
    r = halrun(tmp_path, f"loadrt pluto_servo port=bogus:1 firmware={fw}\n")
    assert f"pluto_servo: firmware file {fw} has 0 bytes (expected 1..1048576)" in (
        r.stdout + r.stderr
    )


def test_step_speedrange(tmp_path: Path) -> None:
    r = halrun(tmp_path, "loadrt pluto_step speedrange=4 port=bogus:1\nshow comp\n")
    out = r.stdout + r.stderr
    assert "pluto_step: speedrange=4 is out of range (0..3)" in out
    assert "pluto_step" not in r.stdout.split("Loaded HAL Components:")[-1]


def test_hm2_7i43_bad_port(tmp_path: Path) -> None:
    assert (RTLIB / "hm2_7i43.so").exists(), "hm2_7i43.so not built (run `make build`)"
    r = halrun(
        tmp_path, "loadrt hostmot2\nloadrt hm2_7i43 port=ppdev:/nonexistent/pp0\nshow comp\n"
    )
    out = r.stdout + r.stderr
    assert "hm2_7i43: loading HostMot2 Mesa 7i43 driver version 0.3" in out
    assert (
        "hm2_7i43: board 0: cannot open the parallel port: ppdev /nonexistent/pp0: open failed"
        in out
    )
    assert "hm2_7i43" not in r.stdout.split("Loaded HAL Components:")[-1]
