# SPDX-License-Identifier: GPL-2.0-or-later
"""The board's socket file gets its permission bits explicitly, not from the
umask: owner-only (0600) by default, --socket-mode for a group."""

from __future__ import annotations

import os
import stat
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
import vbhelpers  # noqa: F401  (puts tests/common on sys.path)
import vboard
from vboard import VBoardProcess


@contextmanager
def umask(mask: int) -> Iterator[None]:
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


def mode_of(path: str) -> int:
    st = os.lstat(path)
    assert stat.S_ISSOCK(st.st_mode)
    return stat.S_IMODE(st.st_mode)


def test_owner_only_under_umask_000(sockdir: Path) -> None:
    with umask(0o000):
        p = VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4")
    with p:
        assert mode_of(p.socket_path) == 0o600
        with p.client() as c:  # the owner still connects
            assert c.hello().firmware == "SVST8_4"


@pytest.mark.parametrize("mask", [0o077, 0o000])
def test_socket_mode_option(sockdir: Path, mask: int) -> None:
    with umask(mask):
        p = VBoardProcess(sockdir / "b.sock", "5i20", args=["--socket-mode", "0660"])
    with p:
        assert mode_of(p.socket_path) == 0o660


@pytest.mark.parametrize("bad", ["0400", "999", "", "0x1B6", "01777", "rw"])
def test_bad_socket_mode(sockdir: Path, bad: str) -> None:
    r = subprocess.run(
        [
            str(vboard.vboard_binary()),
            "--socket",
            str(sockdir / "b.sock"),
            "--board",
            "5i20",
            "--socket-mode",
            bad,
        ],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert r.returncode == 2
    assert f"vboard: bad --socket-mode '{bad}'" in r.stderr
    assert not (sockdir / "b.sock").exists()
