# SPDX-License-Identifier: GPL-2.0-or-later
"""pytest configuration shared by every test tree."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# cocotb test files import their shared helpers as `common.*`.
sys.path.insert(0, str(ROOT / "tests" / "cocotb"))


def build_dir() -> Path:
    """The build tree under test: $HM_BUILD (set by the Makefile) or build/."""
    import os

    return Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
