# SPDX-License-Identifier: GPL-2.0-or-later
"""vboard's flash options: bad ones end the board with a clear message."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from flashhelpers import vboard


@pytest.mark.parametrize(
    "board, extra, message",
    [
        ("5i20", ["--flash", "F"], "is configured by its bus, it has no configuration flash"),
        ("5i25", ["--flash-part", "w25q64"], "unknown flash part 'w25q64' (known: m25p16"),
        ("5i25", ["--flash", "SMALL"], "has 100 bytes, an m25p16 holds 2097152"),
        ("5i25", ["--flash-speedup", "0"], "bad --flash-speedup '0'"),
        ("5i25", ["--firmware", "NOPE"], "firmware NOPE is not built into this vboard"),
    ],
)
def test_bad_flash_options(sockdir: Path, board: str, extra: list[str], message: str) -> None:
    (sockdir / "SMALL").write_bytes(b"\xff" * 100)
    args = [a if a not in ("F", "SMALL") else str(sockdir / a) for a in extra]
    p = subprocess.run(
        [str(vboard.vboard_binary()), "--socket", str(sockdir / "b.sock"), "--board", board] + args,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert p.returncode in (1, 2)
    assert message in p.stderr, p.stderr
    assert (sockdir / "SMALL").read_bytes() == b"\xff" * 100
