# SPDX-License-Identifier: GPL-2.0-or-later
"""Fixtures for the configuration-flash tests: a virtual 5i25 with its flash
in a file, on a short socket path."""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from flashhelpers import StartBoard, hm2flash_binary, vboard

HERE = Path(__file__).resolve().parent


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if HERE in item.path.parents:
            item.add_marker(pytest.mark.requires_build(vboard.vboard_binary()))
            item.add_marker(pytest.mark.requires_build(hm2flash_binary()))


@pytest.fixture
def sockdir() -> Iterator[Path]:
    # sun_path is limited to 108 bytes: pytest's tmp_path can be longer.
    d = Path(tempfile.mkdtemp(prefix="fl"))
    yield d
    shutil.rmtree(d, ignore_errors=True)


@pytest.fixture
def start_board(sockdir: Path) -> Iterator[StartBoard]:
    """start_board(speedup=1000, firmware="7I76x2", part=None): a 5i25 whose
    flash is sockdir/flash.bin (factory-programmed when new)."""
    procs: list[vboard.VBoardProcess] = []

    def start(
        speedup: int = 1000, firmware: str | None = "7I76x2", part: str | None = None
    ) -> vboard.VBoardProcess:
        args = ["--flash", str(sockdir / "flash.bin"), "--flash-speedup", str(speedup)]
        if part:
            args += ["--flash-part", part]
        p = vboard.VBoardProcess(sockdir / "b.sock", "5i25", firmware, args=args)
        procs.append(p)
        return p

    yield start
    for p in procs:
        if p.proc.poll() is None:
            status = p.stop()
            assert "Sanitizer" not in p.stderr_text, p.stderr_text
            assert status == 0, p.stderr_text
