# SPDX-License-Identifier: GPL-2.0-or-later
"""Fixtures for the virtual-board tests: a vboard per test on a short socket path."""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "common"))
sys.path.insert(0, str(ROOT / "tools" / "vbfw"))

import vboard  # noqa: E402


def fw_json(board: str, fw: str) -> dict[str, Any]:
    """hm2gen's description of a generated firmware (the reference for the tests)."""
    path = vboard.build_dir() / "generated" / board / fw / f"{fw}.json"
    return json.loads(path.read_text())


@pytest.fixture(scope="session", autouse=True)
def _need_vboard() -> None:
    if not vboard.vboard_binary().exists():
        pytest.skip(f"{vboard.vboard_binary()} not built (no Verilator in this build)")


@pytest.fixture
def sockdir() -> Iterator[Path]:
    # sun_path is limited to 108 bytes: pytest's tmp_path can be longer.
    d = Path(tempfile.mkdtemp(prefix="vb"))
    yield d
    shutil.rmtree(d, ignore_errors=True)


def stop_clean(p: vboard.VBoardProcess) -> None:
    """SIGTERM must end the board with status 0 and no sanitizer report."""
    status = p.stop()
    assert "Sanitizer" not in p.stderr_text, p.stderr_text
    assert status == 0, p.stderr_text


@pytest.fixture
def svst(sockdir: Path) -> Iterator[vboard.VBoardProcess]:
    """A 5i20 running SVST8_4."""
    p = vboard.VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    try:
        yield p
    finally:
        stop_clean(p)


@pytest.fixture
def client(svst: vboard.VBoardProcess) -> Iterator[vboard.VBoardClient]:
    with svst.client() as c:
        yield c
