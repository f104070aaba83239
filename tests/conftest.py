# SPDX-License-Identifier: GPL-2.0-or-later
"""pytest configuration shared by every test tree.

The skip guard (tests/common/skipguard.py) is loaded here for every run: any
skip or xfail not explained by tests/skips.txt fails the session, and
``@pytest.mark.requires_build(path, ...)`` turns a part that was not built
into a failure instead of a skip.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# cocotb test files import their shared helpers as `common.*`.
sys.path.insert(0, str(ROOT / "tests" / "cocotb"))
# tests/common holds plain modules (vboard, skipguard), imported by name.
sys.path.insert(0, str(ROOT / "tests" / "common"))

from skipguard import pytest_addoption, pytest_configure  # noqa: E402,F401


def build_dir() -> Path:
    """The build tree under test: $HM_BUILD (set by the Makefile) or build/."""
    return Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
