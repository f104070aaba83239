# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers shared by the virtual-board tests (a uniquely named module: every
test tree has a conftest.py, so `from conftest import ...` is ambiguous)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
for _p in (ROOT / "tests" / "common", ROOT / "tools" / "vbfw"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

import vboard  # noqa: E402


def fw_json(board: str, fw: str) -> dict[str, Any]:
    """hm2gen's description of a generated firmware (the reference for the tests)."""
    path = vboard.build_dir() / "generated" / board / fw / f"{fw}.json"
    return json.loads(path.read_text())


def stop_clean(p: vboard.VBoardProcess) -> None:
    """SIGTERM must end the board with status 0 and no sanitizer report."""
    status = p.stop()
    assert "Sanitizer" not in p.stderr_text, p.stderr_text
    assert status == 0, p.stderr_text
