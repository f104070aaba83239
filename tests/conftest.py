# SPDX-License-Identifier: GPL-2.0-or-later
"""pytest configuration shared by every test tree."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# cocotb test files import their shared helpers as `common.*`.
sys.path.insert(0, str(ROOT / "tests" / "cocotb"))
