# SPDX-License-Identifier: GPL-2.0-or-later
"""Fixtures for the virtual-board tests: a vboard per test on a short socket path."""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from vbhelpers import stop_clean, vboard

HERE = Path(__file__).resolve().parent


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    # Every test here needs the virtual board: a missing one fails them.
    for item in items:
        if HERE in item.path.parents:
            item.add_marker(pytest.mark.requires_build(vboard.vboard_binary()))


@pytest.fixture
def sockdir() -> Iterator[Path]:
    # sun_path is limited to 108 bytes: pytest's tmp_path can be longer.
    d = Path(tempfile.mkdtemp(prefix="vb"))
    yield d
    shutil.rmtree(d, ignore_errors=True)


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


@pytest.fixture
def rtl_client(sockdir: Path) -> Iterator[vboard.VBoardClient]:
    """A 5i20 running SVST8_4 on the Verilated firmware (--model rtl): waveform
    dumps need it (the default for a firmware the fast model covers is fast)."""
    p = vboard.VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--model", "rtl"])
    try:
        with p.client() as c:
            yield c
    finally:
        stop_clean(p)
