# SPDX-License-Identifier: GPL-2.0-or-later
"""Every Verilog module under hdl/ must be accepted by Verilator
(--lint-only -Wall, no waivers outside the file itself), Icarus (-g2005) and
yosys (read_verilog + hierarchy + proc), as the engineering standards say."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HDL = ROOT / "hdl"
# Library directories searched for instantiated modules (one module per file,
# named after it).  Generated sources live under build/ and are found there.
LIBDIRS = sorted({p.parent for p in HDL.rglob("*.v")})
GENERATED_INCLUDE = ROOT / "build" / "generated"


def _modules() -> list[Path]:
    return sorted(p for p in HDL.rglob("*.v") if not p.name.endswith("_inc.v"))


def _id(p: Path) -> str:
    return str(p.relative_to(HDL))


def _libargs(flag: str) -> list[str]:
    args: list[str] = []
    for d in LIBDIRS:
        args += [flag, str(d)]
    return args


@pytest.mark.parametrize("src", _modules(), ids=_id)
def test_verilator_lint(src: Path) -> None:
    cmd = [
        "verilator",
        "--lint-only",
        "-Wall",
        "--top-module",
        src.stem,
        *_libargs("-y"),
        f"-I{GENERATED_INCLUDE}",
        str(src),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, f"{' '.join(cmd)}\n{r.stdout}{r.stderr}"


@pytest.mark.parametrize("src", _modules(), ids=_id)
def test_icarus_accepts(src: Path, tmp_path: Path) -> None:
    cmd = [
        "iverilog",
        "-g2005",
        "-Wall",
        "-Wno-timescale",
        "-s",
        src.stem,
        *_libargs("-y"),
        f"-I{GENERATED_INCLUDE}",
        "-o",
        str(tmp_path / "a.out"),
        str(src),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert (
        r.returncode == 0 and "warning" not in r.stderr.lower()
    ), f"{' '.join(cmd)}\n{r.stdout}{r.stderr}"


@pytest.mark.parametrize("src", _modules(), ids=_id)
def test_yosys_accepts(src: Path) -> None:
    libs = " ".join(f"-libdir {d}" for d in LIBDIRS)
    script = (
        f"read_verilog -I {GENERATED_INCLUDE} {src}; "
        f"hierarchy -check -top {src.stem} {libs}; proc"
    )
    r = subprocess.run(["yosys", "-q", "-p", script], capture_output=True, text=True)
    out = r.stdout + r.stderr
    assert r.returncode == 0 and "warning" not in out.lower(), f"yosys -p '{script}'\n{out}"
